// test_cpu_shadow.cpp — lab 4's part of the oracle (tests/reference/cpu_shadow.h) against hand
// calculation: shadow boundaries worked out on paper from similar triangles, translucent factors
// from the rule Π (1 − α), and the blending of translucent layers from c = α·layer + (1 − α)·c.
//
// The shapes (docs/scene-format.md): a plane is 1 × 1 in XZ at y = 0 facing +Y; a cube is side 1
// centred on its position; a sphere has radius 0.5.
#include "reference/cpu_shadow.h"
#include "reference/cpu_reference.h"
#include "reference/image_compare.h"
#include "reference/scene_object.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace {

using glm::dvec3;

using ref::object;  // position, rotation, scale: tests/reference/scene_object.h

lab::LightDesc directional(dvec3 direction) {
    lab::LightDesc l;
    l.type = lab::LightDesc::Type::Directional;
    l.direction = glm::vec3(direction);
    l.cast_shadows = true;
    return l;
}

lab::LightDesc positional(lab::LightDesc::Type type, dvec3 position) {
    lab::LightDesc l;
    l.type = type;
    l.position = glm::vec3(position);
    l.direction = {0.0f, -1.0f, 0.0f};
    l.outer_deg = 80.0f;
    l.inner_deg = 70.0f;
    l.cast_shadows = true;
    return l;
}

// A floor (plane 10 × 10 at y = 0) and materials "opaque", "glass30" (α = 0.3), "glass50" (α = 0.5).
lab::Scene floor_scene() {
    lab::Scene s;
    s.materials["opaque"].albedo = {0.5f, 0.5f, 0.5f};
    s.materials["glass30"].opacity = 0.3f;
    s.materials["glass50"].opacity = 0.5f;
    s.objects.push_back(object("plane", "opaque", {0, 0, 0}, {0, 0, 0}, {10, 1, 10}));
    return s;
}

const dvec3 kUp(0, 1, 0);  // the floor's normal
// What the glasses let through, from the float opacities the scene stores.
const double kT30 = 1.0 - double(0.3f), kT50 = 0.5;

double through(const lab::Scene& s, const lab::LightDesc& light, dvec3 p, dvec3 n = kUp) {
    const ref::ShadowCasters casters(s);
    return casters.transmittance(light, p, n);
}

// --- opaque casters: boundaries on paper ------------------------------------------------------

TEST(CpuShadow, UnitCubeUnderA45DegreeDirectionalLight) {
    // Cube [−0.5, 0.5] × [0, 1] × [−0.5, 0.5]; light travelling (−1, −1, 0): from a floor point (x, 0, z)
    // the ray goes (x + s, s, z), s ≥ 0. It meets the cube iff |z| ≤ 0.5 and x + s ∈ [−0.5, 0.5] for
    // some s ∈ [0, 1], i.e. x ∈ [−1.5, 0.5]: the shadow reaches 1 unit beyond the cube's −X face.
    lab::Scene s = floor_scene();
    s.objects.push_back(object("cube", "opaque", {0, 0.5f, 0}));
    const lab::LightDesc light = directional({-1, -1, 0});
    EXPECT_EQ(through(s, light, {-1.49, 0, 0}), 0.0);
    EXPECT_EQ(through(s, light, {-1.0, 0, 0.49}), 0.0);
    EXPECT_EQ(through(s, light, {-1.0, 0, -0.49}), 0.0);
    EXPECT_EQ(through(s, light, {-1.51, 0, 0}), 1.0);
    EXPECT_EQ(through(s, light, {-1.0, 0, 0.51}), 1.0);
    EXPECT_EQ(through(s, light, {0.51, 0, 0}), 1.0);  // the lit side right next to the cube
    EXPECT_EQ(through(s, light, {3.0, 0, 0}), 1.0);
    // The cube's own faces: the +X face (facing the light) is lit, the −X face is in its own shadow.
    EXPECT_EQ(through(s, light, {0.5, 0.5, 0}, {1, 0, 0}), 1.0);
    EXPECT_EQ(through(s, light, {-0.5, 0.5, 0}, {-1, 0, 0}), 0.0);
}

TEST(CpuShadow, UnitCubeUnderAPointAndASpotLight) {
    // Light at (0, 3, 0). The ray from (x, 0, 0) reaches height 1 (the cube's top) at x·(1 − 1/3):
    // blocked iff |2x/3| ≤ 0.5, i.e. |x| ≤ 0.75. Along the diagonal: (x, 0, x) is blocked iff x ≤ 0.75.
    lab::Scene s = floor_scene();
    s.objects.push_back(object("cube", "opaque", {0, 0.5f, 0}));
    for (const auto type : {lab::LightDesc::Type::Point, lab::LightDesc::Type::Spot}) {
        const lab::LightDesc light = positional(type, {0, 3, 0});
        EXPECT_EQ(through(s, light, {0.74, 0, 0}), 0.0);
        EXPECT_EQ(through(s, light, {-0.74, 0, 0}), 0.0);
        EXPECT_EQ(through(s, light, {0, 0, 0.74}), 0.0);
        EXPECT_EQ(through(s, light, {0.70, 0, 0.70}), 0.0);
        EXPECT_EQ(through(s, light, {0.76, 0, 0}), 1.0);
        EXPECT_EQ(through(s, light, {0, 0, -0.76}), 1.0);
        EXPECT_EQ(through(s, light, {0.80, 0, 0.80}), 1.0);
        EXPECT_EQ(through(s, light, {0, 1, 0}), 1.0);  // the top face itself
    }
}

TEST(CpuShadow, APlaneFacingAwayFromTheLightStillBlocksIt) {
    // Opaque casters block from either side: a 2 × 2 plane at y = 1 turned upside down (front −Y).
    lab::Scene s = floor_scene();
    s.objects.push_back(object("plane", "opaque", {0, 1, 0}, {180, 0, 0}, {2, 1, 2}));
    EXPECT_EQ(through(s, directional({0, -1, 0}), {0.9, 0, 0}), 0.0);
    EXPECT_EQ(through(s, directional({0, -1, 0}), {1.1, 0, 0}), 1.0);
}

TEST(CpuShadow, CasterBehindTheLightCastsNothing) {
    // The light at y = 1, an opaque plane above it at y = 2: the segment floor → light is free.
    lab::Scene s = floor_scene();
    s.objects.push_back(object("plane", "opaque", {0, 2, 0}, {0, 0, 0}, {4, 1, 4}));
    for (const auto type : {lab::LightDesc::Type::Point, lab::LightDesc::Type::Spot}) {
        EXPECT_EQ(through(s, positional(type, {0, 1, 0}), {0, 0, 0}), 1.0);
        EXPECT_EQ(through(s, positional(type, {0, 3, 0}), {0, 0, 0}), 0.0);  // control: light above it
    }
}

TEST(CpuShadow, ObjectsWithCastShadowsOffCastNothing) {
    lab::Scene s = floor_scene();
    s.objects.push_back(object("cube", "opaque", {0, 0.5f, 0}));
    s.objects.back().cast_shadows = false;
    EXPECT_EQ(through(s, directional({0, -1, 0}), {0, 0, 0.2}), 1.0);
    EXPECT_EQ(through(s, positional(lab::LightDesc::Type::Point, {0, 3, 0}), {0.2, 0, 0}), 1.0);
}

TEST(CpuShadow, ALightInsideAnOpaqueObjectLightsNothingOutside) {
    lab::Scene s = floor_scene();
    s.objects.push_back(object("cube", "opaque", {0, 2, 0}));
    const lab::LightDesc light = positional(lab::LightDesc::Type::Point, {0, 2, 0});
    EXPECT_EQ(through(s, light, {0, 0, 0}), 0.0);
    EXPECT_EQ(through(s, light, {4, 0, 1}), 0.0);
}

TEST(CpuShadow, NoSelfShadowOnAPlaneAtGrazingLight) {
    // The offset rule: a lit plane never shadows itself, down to a light 89.9° from its normal.
    lab::Scene s = floor_scene();
    const double a = 89.9 * 3.14159265358979323846 / 180.0;
    const lab::LightDesc light = directional({-std::sin(a), -std::cos(a), 0});
    for (double x = -4.9; x < 5; x += 0.37)
        for (double z = -4.9; z < 5; z += 0.41) ASSERT_EQ(through(s, light, {x, 0, z}), 1.0) << x << ", " << z;
}

TEST(CpuShadow, ATessellatedSpheresTerminatorFollowsItsFacets) {
    // Convex mesh: a facet facing the light sees it (the ray leaves the sphere for good); a facet facing
    // away starts its ray inside the mesh (the light's side of its plane) and meets the far side: 0.
    // Near the smooth terminator the interpolated normal may still face the light while the facet
    // does not — those points are shadowed.
    lab::Scene s;
    s.materials["opaque"] = {};
    s.objects.push_back(object("sphere", "opaque", {0.2f, 1.0f, -0.3f}, {0, 0, 0}, {2, 2, 2}));
    const ref::SceneGeometry geometry(s);
    const ref::ShadowCasters casters(s);
    const dvec3 centre(0.2, 1.0, -0.3);
    const lab::LightDesc light = directional({-1, -2, -0.5});
    const dvec3 L = -glm::normalize(dvec3(-1, -2, -0.5));
    std::mt19937 rng(7);
    std::normal_distribution<double> g;
    int lit = 0, shadowed = 0, smooth_lit_but_facet_dark = 0;
    for (int i = 0; i < 4000; ++i) {
        dvec3 d(g(rng), g(rng), g(rng));
        d = glm::normalize(d);
        // Mostly near the terminator: tilt samples toward the plane perpendicular to L.
        if (i % 2) d = glm::normalize(d - L * (0.9 * glm::dot(d, L)));
        ref::Ray ray;
        ray.origin = centre + 5.0 * d;
        ray.dir = -d;
        ref::Hit hit;
        ASSERT_TRUE(geometry.trace(ray, 0.0, 10.0, &hit));
        const double facing = glm::dot(hit.geometric_normal, L);
        if (std::abs(facing) < 1e-9) continue;
        const double t = casters.transmittance(light, hit.position, hit.geometric_normal);
        ASSERT_EQ(t, facing > 0.0 ? 1.0 : 0.0) << "facet·L = " << facing;
        (facing > 0.0 ? lit : shadowed)++;
        smooth_lit_but_facet_dark += facing < 0.0 && glm::dot(hit.normal, L) > 0.0;
    }
    EXPECT_GT(lit, 1000);
    EXPECT_GT(shadowed, 1000);
    EXPECT_GT(smooth_lit_but_facet_dark, 10);  // the case this test is about did occur
}

// --- translucent casters ------------------------------------------------------------------------

TEST(CpuShadow, ATranslucentQuadLetsOneMinusAlphaThrough) {
    lab::Scene s = floor_scene();
    s.objects.push_back(object("plane", "glass30", {0, 1, 0}, {0, 0, 0}, {2, 1, 2}));  // faces +Y: the light
    const lab::LightDesc light = directional({0, -1, 0});
    EXPECT_DOUBLE_EQ(through(s, light, {0, 0, 0}), kT30);
    EXPECT_DOUBLE_EQ(through(s, light, {0.5, 0, 0.5}), kT30);  // a ray through the quad's diagonal: once
    EXPECT_EQ(through(s, light, {1.1, 0, 0}), 1.0);
    // The same quad facing away from the light has no face turned to it: no translucent shadow.
    s.objects.back().rotation_deg = {180, 0, 0};
    EXPECT_EQ(through(s, light, {0, 0, 0}), 1.0);
}

TEST(CpuShadow, OverlappingTranslucentCastersMultiply) {
    // Two quads, α = 0.3 at y = 1 over x ∈ [−1, 1] and α = 0.5 at y = 2 over x ∈ [0, 2].
    lab::Scene s = floor_scene();
    s.objects.push_back(object("plane", "glass30", {0, 1, 0}, {0, 0, 0}, {2, 1, 2}));
    s.objects.push_back(object("plane", "glass50", {1, 2, 0}, {0, 0, 0}, {2, 1, 2}));
    const lab::LightDesc light = directional({0, -1, 0});
    EXPECT_DOUBLE_EQ(through(s, light, {-0.5, 0, 0}), kT30);
    EXPECT_DOUBLE_EQ(through(s, light, {0.5, 0, 0}), kT30 * kT50);
    EXPECT_DOUBLE_EQ(through(s, light, {1.5, 0, 0}), kT50);
    EXPECT_EQ(through(s, light, {2.5, 0, 0}), 1.0);
    // An opaque caster anywhere on the ray still wins.
    s.objects.push_back(object("cube", "opaque", {0.5f, 3.0f, 0}, {0, 0, 0}, {0.2f, 0.2f, 0.2f}));
    EXPECT_EQ(through(s, light, {0.5, 0, 0}), 0.0);
}

TEST(CpuShadow, AConvexTranslucentObjectCountsOnce) {
    lab::Scene s = floor_scene();
    s.objects.push_back(object("cube", "glass50", {0, 1.5f, 0}));
    s.objects.push_back(object("sphere", "glass30", {3, 1.5f, 0}));
    EXPECT_DOUBLE_EQ(through(s, directional({0, -1, 0}), {0.2, 0, 0.1}), 0.5);
    EXPECT_DOUBLE_EQ(through(s, directional({-1, -2, 0}), {-0.6, 0, 0.1}), 0.5);  // in through a side face
    EXPECT_DOUBLE_EQ(through(s, directional({0, -1, 0}), {3.1, 0, 0.05}), kT30);
    EXPECT_DOUBLE_EQ(through(s, positional(lab::LightDesc::Type::Point, {3, 4, 0}), {3.1, 0, 0.05}), kT30);
}

// --- the picture: translucent layers -----------------------------------------------------------

// A camera looking down −Z from z = 5 at the origin, ambient 1 and no lights: a surface's colour is
// its albedo exactly, so blending can be checked by hand.
lab::Scene blend_scene() {
    lab::Scene s;
    s.camera.position = {0, 0, 5};
    s.camera.target = {0, 0, 0};
    s.camera.fov_y_deg = 60.0f;
    s.background = {0.2f, 0.4f, 0.6f};
    s.ambient.intensity = 1.0f;
    s.materials["red"].albedo = {1, 0, 0};
    s.materials["red"].opacity = 0.25f;
    s.materials["blue"].albedo = {0, 0, 1};
    s.materials["blue"].opacity = 0.5f;
    s.materials["wall"].albedo = {0, 1, 0};
    return s;
}

dvec3 centre_pixel(const lab::Scene& s) {
    const ref::RefImage image = ref::render_shadowed(s, 9, 9);
    return image.linear[size_t(image.index(4, 4))];
}

// The scene stores colours and opacities as floats (0.8f ≠ 0.8): agreement to 1e-7.
void expect_colour(dvec3 actual, dvec3 expected) {
    EXPECT_NEAR(actual.x, expected.x, 1e-7);
    EXPECT_NEAR(actual.y, expected.y, 1e-7);
    EXPECT_NEAR(actual.z, expected.z, 1e-7);
}

TEST(CpuShadowPicture, AMarginExtendsTheSamePixelGrid) {
    // The picture rendered with a margin is the plain one in its centre, bit for bit: the same rays
    // through the same pixel centres (the margin only adds rays past the frame). A spot light, an
    // opaque and a translucent caster, a non-square frame.
    lab::Scene s = floor_scene();
    s.camera.position = {3, 4, 5};
    s.camera.target = {0, 0.5f, 0};
    s.objects.push_back(object("cube", "opaque", {0.5f, 0.6f, 0}, {20, 30, 0}, {0.8f, 0.5f, 0.7f}));
    s.objects.push_back(object("cube", "glass50", {-1, 1.2f, 0.5f}));
    s.lights.push_back(positional(lab::LightDesc::Type::Spot, {1, 4, 1}));
    for (const bool shadows : {true, false}) {
        const ref::RefImage plain = ref::render_shadowed(s, 23, 17, shadows);
        const ref::RefImage big = ref::render_shadowed(s, 23, 17, shadows, 2);
        ASSERT_EQ(big.width, 27);
        ASSERT_EQ(big.height, 21);
        const ref::RefImage crop = ref::crop_margin(big, 2);
        ASSERT_EQ(crop.width, 23);
        ASSERT_EQ(crop.height, 17);
        ASSERT_EQ(crop.linear.size(), plain.linear.size());
        size_t differing = 0;
        for (size_t i = 0; i < plain.linear.size(); ++i)
            differing += crop.linear[i] != plain.linear[i] || crop.object_id[i] != plain.object_id[i] ||
                         crop.triangle_id[i] != plain.triangle_id[i] || crop.hits[i].position != plain.hits[i].position ||
                         crop.translucent_objects[i] != plain.translucent_objects[i];
        EXPECT_EQ(differing, 0u) << (shadows ? "shadowed" : "unshadowed");
        // The margin holds new rays: its bottom row sees the floor beyond the frame's bottom row.
        const ref::Hit& below = big.hits[size_t(big.index(2, 20))];
        const ref::Hit& last = plain.hits[size_t(plain.index(0, 16))];
        ASSERT_TRUE(below.hit && last.hit);
        EXPECT_NE(below.position, last.position);
    }
}

TEST(CpuShadowPicture, TranslucentLayersBlendBackToFront) {
    lab::Scene s = blend_scene();
    const dvec3 bg(0.2, 0.4, 0.6), red(1, 0, 0), blue(0, 0, 1), wall(0, 1, 0);
    // A quad facing the camera (plane rotated +90° about X: front +Z).
    s.objects.push_back(object("plane", "red", {0, 0, 1}, {90, 0, 0}, {2, 1, 2}));
    expect_colour(centre_pixel(s), 0.25 * red + 0.75 * bg);
    // Its back (rotated −90°: front −Z, seen from behind) is drawn too.
    s.objects.back().rotation_deg = {-90, 0, 0};
    expect_colour(centre_pixel(s), 0.25 * red + 0.75 * bg);
    // A second layer behind it and an opaque wall behind both.
    s.objects.push_back(object("plane", "blue", {0, 0, 0}, {90, 0, 0}, {2, 1, 2}));
    s.objects.push_back(object("plane", "wall", {0, 0, -1}, {90, 0, 0}, {4, 1, 4}));
    expect_colour(centre_pixel(s), 0.25 * red + 0.75 * (0.5 * blue + 0.5 * wall));
    // A translucent cube: back face, then front face, over the background.
    lab::Scene c = blend_scene();
    c.objects.push_back(object("cube", "blue", {0, 0, 0}));
    expect_colour(centre_pixel(c), 0.5 * blue + 0.5 * (0.5 * blue + 0.5 * bg));
    // Behind an opaque wall nothing translucent shows.
    c.objects.push_back(object("plane", "wall", {0, 0, 2}, {90, 0, 0}, {4, 1, 4}));
    expect_colour(centre_pixel(c), wall);
}

TEST(CpuShadowPicture, ATranslucentCubeOnTheFloorShowsTheFloorThroughIt) {
    // The cube's bottom face lies in the floor's plane: the opaque floor wins the tie.
    lab::Scene s = blend_scene();
    s.camera.position = {0, 5, 0.001f};
    s.objects.push_back(object("plane", "wall", {0, 0, 0}, {0, 0, 0}, {8, 1, 8}));
    s.objects.push_back(object("cube", "blue", {0, 0.5f, 0}));
    const dvec3 blue(0, 0, 1), wall(0, 1, 0);
    expect_colour(centre_pixel(s), 0.5 * blue + 0.5 * wall);
}

TEST(CpuShadowPicture, ShadowsDarkenOnlyShadowCastingLights) {
    // Floor seen from above, a cube over the centre, one directional light straight down (Lambert).
    lab::Scene s = floor_scene();
    s.camera.position = {0, 6, 0.001f};
    s.camera.target = {0, 0, 0};
    s.ambient.intensity = 0.0f;
    s.lighting.model = lab::LightingDesc::Model::Lambert;
    s.objects.push_back(object("cube", "glass50", {0, 2, 0}, {0, 0, 0}, {0.5f, 0.5f, 0.5f}));
    s.objects.back().cast_shadows = true;
    s.lights.push_back(directional({0, -1, 0}));
    // The centre pixel sees, front to back: the cube's top (lit: 0.8 albedo · 1), its bottom from inside
    // (normal flipped to +Y; its light came through the top: 0.8 · 0.5) and the floor (0.5 albedo,
    // light through the cube once: · 0.5). Blended: c = 0.5·layer + 0.5·c from the back.
    const double cube = 0.8, floor_lit = 0.5;
    expect_colour(centre_pixel(s), dvec3(0.5 * cube + 0.5 * (0.5 * cube * 0.5 + 0.5 * floor_lit * 0.5)));
    s.lights.back().cast_shadows = false;
    expect_colour(centre_pixel(s), dvec3(0.5 * cube + 0.5 * (0.5 * cube + 0.5 * floor_lit)));
}

// --- the shadow error metric on synthetic pictures ------------------------------------------------

lab::Image8 grey(int w, int h, uint8_t v) {
    lab::Image8 im;
    im.width = w;
    im.height = h;
    im.rgba.assign(size_t(w) * size_t(h) * 4, v);
    for (size_t i = 3; i < im.rgba.size(); i += 4) im.rgba[i] = 255;
    return im;
}

void set(lab::Image8& im, int x, int y, uint8_t v) {
    for (int ch = 0; ch < 3; ++ch) im.rgba[(size_t(y) * size_t(im.width) + size_t(x)) * 4 + size_t(ch)] = v;
}

// 20 × 10: U = 200 (lit), Z = 40 (light off); S lit for x < 10, shadow from x = 10.
// `actual`'s shadow starts at column `edge`.
lab::Image8 half_shadow(int edge) {
    lab::Image8 im = grey(20, 10, 200);
    for (int y = 0; y < 10; ++y)
        for (int x = edge; x < 20; ++x) set(im, x, y, 40);
    return im;
}

TEST(ShadowMetric, LitFractionByHand) {
    const uint8_t u[3] = {200, 200, 200}, z[3] = {40, 40, 40};
    const uint8_t half[3] = {120, 120, 120}, full[3] = {200, 200, 200}, none[3] = {40, 40, 40};
    EXPECT_DOUBLE_EQ(ref::lit_fraction(half, u, z), 0.5);
    EXPECT_DOUBLE_EQ(ref::lit_fraction(full, u, z), 1.0);
    EXPECT_DOUBLE_EQ(ref::lit_fraction(none, u, z), 0.0);
    // Coloured light: only the channels the light changes weigh. (u − z) = (100, 0, 0).
    const uint8_t cu[3] = {140, 40, 40}, cx[3] = {90, 250, 0};
    EXPECT_DOUBLE_EQ(ref::lit_fraction(cx, cu, z), 0.5);
}

TEST(ShadowMetric, ShiftedShadowEdgesCountOnlyOutsideTheBand) {
    const lab::Image8 U = grey(20, 10, 200), Z = grey(20, 10, 40), S = half_shadow(10);
    ref::ShadowMetricOptions o;
    o.band = 2;
    // Identical: nothing wrong. Band: columns 8, 9 (a shadow pixel within 2) and 10, 11.
    ref::ShadowMetric m = ref::shadow_metric(S, S, U, Z, o);
    EXPECT_EQ(m.receivers, 200u);
    EXPECT_EQ(m.banded, 40u);
    EXPECT_EQ(m.wrong_side, 0u);
    EXPECT_DOUBLE_EQ(m.mae, 0.0);
    // Shadow 2 px early: columns 8, 9 differ but lie in the band; MAE = 20 pixels · 160 / 200.
    m = ref::shadow_metric(half_shadow(8), S, U, Z, o);
    EXPECT_EQ(m.wrong_side, 0u);
    EXPECT_DOUBLE_EQ(m.mae, 16.0);
    // 4 px early: columns 6, 7 are outside the band: 20 wrong of 160 counted.
    m = ref::shadow_metric(half_shadow(6), S, U, Z, o);
    EXPECT_EQ(m.wrong_side, 20u);
    EXPECT_DOUBLE_EQ(m.wrong_side_share, 20.0 / 160.0);
    EXPECT_DOUBLE_EQ(m.mae, 32.0);
    EXPECT_EQ(m.wrong[size_t(6)], 1);
    EXPECT_EQ(m.wrong[size_t(8)], 0);
    // The same 4 px with k = 4: all inside the band.
    o.band = 4;
    EXPECT_EQ(ref::shadow_metric(half_shadow(6), S, U, Z, o).wrong_side, 0u);
    // k = 0: every differing pixel counts.
    o.band = 0;
    m = ref::shadow_metric(half_shadow(8), S, U, Z, o);
    EXPECT_EQ(m.banded, 0u);
    EXPECT_EQ(m.wrong_side, 20u);
}

TEST(ShadowMetric, StatesSplitAtHalfTheLight) {
    // A translucent shadow at 130 (f = 90/160 > ½) counts as lit, at 110 (f = 70/160) as shadow.
    const lab::Image8 U = grey(20, 10, 200), Z = grey(20, 10, 40);
    lab::Image8 S = grey(20, 10, 200), X = S;
    for (int x = 0; x < 20; ++x) set(S, x, 5, 130);
    ref::ShadowMetricOptions o;
    o.band = 0;
    ref::ShadowMetric m = ref::shadow_metric(X, S, U, Z, o);
    EXPECT_EQ(m.wrong_side, 0u);
    EXPECT_DOUBLE_EQ(m.mae, 20 * 70.0 / 200);
    for (int x = 0; x < 20; ++x) set(S, x, 5, 110);
    m = ref::shadow_metric(X, S, U, Z, o);
    EXPECT_EQ(m.wrong_side, 20u);
}

TEST(ShadowMetric, NonReceiversAreLeftOutAndBoundTheBand) {
    // Row 0: the shadow-casting light adds less than 3/255 (U − Z = 2): not a receiver.
    lab::Image8 U = grey(20, 10, 200), Z = grey(20, 10, 40);
    for (int x = 0; x < 20; ++x) set(U, x, 0, 42);
    const lab::Image8 S = U;  // all lit
    lab::Image8 X = S;
    for (int x = 0; x < 20; ++x) set(X, x, 0, 0), set(X, x, 1, 40), set(X, x, 5, 40);
    ref::ShadowMetricOptions o;
    o.band = 1;
    const ref::ShadowMetric m = ref::shadow_metric(X, S, U, Z, o);
    EXPECT_EQ(m.receivers, 180u);
    EXPECT_EQ(m.banded, 20u);       // row 1 borders the non-receivers
    EXPECT_EQ(m.wrong_side, 20u);   // row 5 only
    EXPECT_DOUBLE_EQ(m.mae, 40 * 160.0 / 180);
}

TEST(ShadowMetric, SizesMustAgree) {
    const lab::Image8 a = grey(4, 4, 9), b = grey(4, 5, 9);
    EXPECT_THROW(ref::shadow_metric(a, b, b, b), std::invalid_argument);
    EXPECT_THROW(ref::shadow_metric(b, b, a, b), std::invalid_argument);
    EXPECT_THROW(ref::shadow_metric(b, b, b, a), std::invalid_argument);
    // With a margin the references are 2·margin larger each way, and only then.
    ref::ShadowMetricOptions o;
    o.margin = 1;
    const lab::Image8 big = grey(6, 7, 9);
    EXPECT_NO_THROW(ref::shadow_metric(b, big, big, big, o));
    EXPECT_THROW(ref::shadow_metric(b, b, b, b, o), std::invalid_argument);
    EXPECT_THROW(ref::shadow_metric(a, big, big, big, o), std::invalid_argument);
    EXPECT_THROW(ref::shadow_metric(b, big, b, big, o), std::invalid_argument);
}

TEST(ShadowMetric, AnEdgeJustOutsideTheFrameBandsTheBorderRows) {
    // The judged picture is 20 × 10; the references are 24 × 14 (margin 2). S is lit down to the
    // frame's last row and in shadow from the first row below it (big-frame row 12). X is in shadow
    // on its last two rows (crop rows 8, 9): 1 and 2 px from S's edge, ties under k = 2.
    const lab::Image8 U = grey(24, 14, 200), Z = grey(24, 14, 40);
    lab::Image8 S = grey(24, 14, 200);
    for (int y = 12; y < 14; ++y)
        for (int x = 0; x < 24; ++x) set(S, x, y, 40);
    lab::Image8 X = grey(20, 10, 200);
    for (int y = 8; y < 10; ++y)
        for (int x = 0; x < 20; ++x) set(X, x, y, 40);
    ref::ShadowMetricOptions o;
    o.band = 2;
    o.margin = 2;
    ref::ShadowMetric m = ref::shadow_metric(X, S, U, Z, o);
    EXPECT_EQ(m.width, 20);
    EXPECT_EQ(m.state.size(), 200u);
    EXPECT_EQ(m.receivers, 200u);
    EXPECT_EQ(m.banded, 40u);  // rows 8, 9: within 2 of big-frame row 12
    EXPECT_EQ(m.wrong_side, 0u);
    EXPECT_EQ(m.state[size_t(9 * 20)], 1);  // S's state of the crop, not of the margin
    // Judged on the crop alone, the same picture's border rows count (the defect the margin fixes).
    lab::Image8 s = grey(20, 10, 200), u = grey(20, 10, 200), z = grey(20, 10, 40);
    o.margin = 0;
    m = ref::shadow_metric(X, s, u, z, o);
    EXPECT_EQ(m.banded, 0u);
    EXPECT_EQ(m.wrong_side, 40u);
    // One row more (crop row 7, 3 px from the edge) is outside the band, margin or not.
    for (int x = 0; x < 20; ++x) set(X, x, 7, 40);
    o.margin = 2;
    m = ref::shadow_metric(X, S, U, Z, o);
    EXPECT_EQ(m.banded, 40u);
    EXPECT_EQ(m.wrong_side, 20u);
    EXPECT_EQ(m.wrong[size_t(7 * 20)], 1);
    // Colours and MAE come from the crop: X equal to S's centre gives 0.
    lab::Image8 centre = grey(20, 10, 200);
    EXPECT_DOUBLE_EQ(ref::shadow_metric(centre, S, U, Z, o).mae, 0.0);
}

}  // namespace
