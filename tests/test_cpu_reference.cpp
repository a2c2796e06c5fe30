// test_cpu_reference.cpp — unit tests of the oracle itself.
//
// The CPU reference decides whether the GPU labs are right, so it is checked
// here against values worked out by hand from docs/conventions.md — never
// against a GPU image. Most tests use a tiny image and a 90° field of view:
// then tan(fov/2) = 1 and a point (x, y, −d) in camera space lands at
// ndc = (x/d, y/d); pixel centres of an N-pixel row sit at
// ndc = (k + 0.5)·2/N − 1, e.g. for N = 8: ±0.125, ±0.375, ±0.625, ±0.875.
#include "reference/cpu_reference.h"
#include "reference/image_compare.h"
#include "reference/scene_object.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <set>

namespace {

using glm::dvec3;

// ---------------------------------------------------------------------------
// Scene-building helpers
// ---------------------------------------------------------------------------

lab::Scene base_scene() {
    lab::Scene s;
    s.background = {0.0f, 0.0f, 0.0f};
    s.materials["red"].albedo = {1.0f, 0.0f, 0.0f};
    s.materials["green"].albedo = {0.0f, 1.0f, 0.0f};
    s.materials["blue"].albedo = {0.0f, 0.0f, 1.0f};
    s.camera.mode = lab::CameraDesc::Mode::LookAt;
    s.camera.fov_y_deg = 90.0f;
    s.camera.near_plane = 0.1f;
    s.camera.far_plane = 100.0f;
    return s;
}

void look(lab::Scene& s, dvec3 eye, dvec3 target, dvec3 up = {0, 1, 0}) {
    s.camera.mode = lab::CameraDesc::Mode::LookAt;
    s.camera.position = glm::vec3(eye);
    s.camera.target = glm::vec3(target);
    s.camera.up = glm::vec3(up);
}

using ref::object;  // position, rotation, scale: tests/reference/scene_object.h

// A plane of side `size` centred at `position`, rotated so its front (+Y in
// model space) faces +Z: Rx(90°) maps (x, y, z) to (x, −z, y).
lab::ObjectDesc facing_plus_z(const std::string& material, glm::vec3 position, float size) {
    return object("plane", material, position, {90.0f, 0.0f, 0.0f}, glm::vec3(size));
}

// Set of pixels (x, y) showing object `id`.
std::set<std::pair<int, int>> pixels_of(const ref::RefImage& img, int id) {
    std::set<std::pair<int, int>> out;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (img.object_id[img.index(x, y)] == id) out.insert({x, y});
    return out;
}

std::set<std::pair<int, int>> rect(int x0, int x1, int y0, int y1) {  // inclusive
    std::set<std::pair<int, int>> out;
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) out.insert({x, y});
    return out;
}

void expect_near(const dvec3& a, const dvec3& b, double eps, const char* what) {
    EXPECT_NEAR(a.x, b.x, eps) << what;
    EXPECT_NEAR(a.y, b.y, eps) << what;
    EXPECT_NEAR(a.z, b.z, eps) << what;
}

// ---------------------------------------------------------------------------
// Matrices
// ---------------------------------------------------------------------------

TEST(RefMatrices, ExactRightAngles) {
    EXPECT_EQ(ref::sin_deg(90.0), 1.0);
    EXPECT_EQ(ref::cos_deg(90.0), 0.0);
    EXPECT_EQ(ref::cos_deg(180.0), -1.0);
    EXPECT_EQ(ref::sin_deg(-90.0), -1.0);
    EXPECT_EQ(ref::sin_deg(450.0), 1.0);
    EXPECT_NEAR(ref::sin_deg(30.0), 0.5, 1e-15);
    EXPECT_NEAR(ref::cos_deg(-60.0), 0.5, 1e-15);
}

TEST(RefMatrices, RotationsFollowTheRightHandRule) {
    // +90° about Z turns +X into +Y; about X turns +Y into +Z; about Y turns +Z into +X.
    expect_near(dvec3(ref::rotate_z(90) * glm::dvec4(1, 0, 0, 1)), {0, 1, 0}, 0, "Rz");
    expect_near(dvec3(ref::rotate_x(90) * glm::dvec4(0, 1, 0, 1)), {0, 0, 1}, 0, "Rx");
    expect_near(dvec3(ref::rotate_y(90) * glm::dvec4(0, 0, 1, 1)), {1, 0, 0}, 0, "Ry");
}

TEST(RefMatrices, ModelMatrixOrderIsTRzRyRxS) {
    // rotation [90, 90, 0], scale (2, 3, 4), position (1, 2, 3), applied to (0, 1, 0):
    //   S → (0, 3, 0); Rx(90) → (0, 0, 3); Ry(90) → (3, 0, 0); T → (4, 2, 3).
    // (Rx applied after Ry would give (0, 3, 0) → (0, 3, 0) → (0, 0, 3) → (1, 2, 6).)
    lab::ObjectDesc o = object("cube", "red", {1, 2, 3}, {90, 90, 0}, {2, 3, 4});
    expect_near(dvec3(ref::model_matrix(o) * glm::dvec4(0, 1, 0, 1)), {4, 2, 3}, 1e-15, "M·(0,1,0)");
    // Rz last: rotation [0, 90, 90] on (0, 0, 1): Ry → (1, 0, 0); Rz → (0, 1, 0).
    o = object("cube", "red", {0, 0, 0}, {0, 90, 90});
    expect_near(dvec3(ref::model_matrix(o) * glm::dvec4(0, 0, 1, 1)), {0, 1, 0}, 1e-15, "Rz·Ry");
}

TEST(RefMatrices, LabModelMatrixAgreesWithReference) {
    // Cross-check of two independent implementations of the same convention.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> angle(-360.0f, 360.0f), pos(-10.0f, 10.0f), sc(0.1f, 3.0f);
    for (int i = 0; i < 100; ++i) {
        lab::ObjectDesc o = object("cube", "red", {pos(rng), pos(rng), pos(rng)},
                                   {angle(rng), angle(rng), angle(rng)},
                                   {sc(rng), -sc(rng), sc(rng)});
        const glm::dmat4 expected = ref::model_matrix(o);
        const glm::mat4 actual = lab::model_matrix(o);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) EXPECT_NEAR(actual[c][r], expected[c][r], 1e-4) << i;
    }
}

// ---------------------------------------------------------------------------
// Camera
// ---------------------------------------------------------------------------

TEST(RefCamera, LookAtFrame) {
    lab::CameraDesc c;
    c.position = {0, 0, 5};
    c.target = {0, 0, 0};
    const ref::Camera cam = ref::make_camera(c);
    expect_near(cam.forward, {0, 0, -1}, 0, "forward");
    expect_near(cam.right, {1, 0, 0}, 0, "right");
    expect_near(cam.up, {0, 1, 0}, 0, "up");
    // The view matrix moves the eye to the origin and the target onto −Z.
    expect_near(dvec3(cam.view() * glm::dvec4(0, 0, 5, 1)), {0, 0, 0}, 1e-15, "eye");
    expect_near(dvec3(cam.view() * glm::dvec4(0, 0, 0, 1)), {0, 0, -5}, 1e-15, "target");
    // And it is the inverse of camera_to_world.
    const glm::dmat4 id = cam.view() * cam.camera_to_world();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_NEAR(id[i][j], i == j ? 1.0 : 0.0, 1e-15);
}

TEST(RefCamera, LookStraightDownUsesMinusZAsUp) {
    // f = −Y is parallel to up = +Y: up' = sign(f·up)·Z = −Z, so the image top is
    // world −Z and the image right is f × up' = (−Y) × (−Z) = +X.
    lab::CameraDesc c;
    c.position = {0, 10, 0};
    c.target = {0, 0, 0};
    c.up = {0, 1, 0};
    const ref::Camera cam = ref::make_camera(c);
    expect_near(cam.forward, {0, -1, 0}, 0, "forward");
    expect_near(cam.right, {1, 0, 0}, 0, "right");
    expect_near(cam.up, {0, 0, -1}, 0, "up");
    // Looking straight up: sign(f·up) = +1, up' = +Z, right = (+Y) × (+Z) = +X.
    c.position = {0, -10, 0};
    const ref::Camera up_cam = ref::make_camera(c);
    expect_near(up_cam.right, {1, 0, 0}, 0, "right (looking up)");
    expect_near(up_cam.up, {0, 0, 1}, 0, "up (looking up)");
}

TEST(RefCamera, EyeEqualsTargetLooksDownMinusZ) {
    lab::CameraDesc c;
    c.position = {1, 2, 3};
    c.target = {1, 2, 3};
    const ref::Camera cam = ref::make_camera(c);
    expect_near(cam.forward, {0, 0, -1}, 0, "forward");
    expect_near(cam.right, {1, 0, 0}, 0, "right");
    expect_near(cam.up, {0, 1, 0}, 0, "up");
}

TEST(RefCamera, TransformModeAngles) {
    lab::CameraDesc c;
    c.mode = lab::CameraDesc::Mode::Transform;
    c.position = {1, 2, 3};
    ref::Camera cam = ref::make_camera(c);
    expect_near(cam.forward, {0, 0, -1}, 0, "all zero looks down -Z");
    c.yaw_deg = 90;  // positive yaw turns left: −Z turns to −X
    cam = ref::make_camera(c);
    expect_near(cam.forward, {-1, 0, 0}, 0, "yaw 90 forward");
    expect_near(cam.right, {0, 0, -1}, 0, "yaw 90 right");
    c.yaw_deg = 0;
    c.pitch_deg = 90;  // positive pitch looks up
    cam = ref::make_camera(c);
    expect_near(cam.forward, {0, 1, 0}, 0, "pitch 90 forward");
    expect_near(cam.up, {0, 0, 1}, 0, "pitch 90 up");
    c.pitch_deg = 0;
    c.roll_deg = 90;  // the camera turns CCW about its view axis: its up becomes −X
    cam = ref::make_camera(c);
    expect_near(cam.forward, {0, 0, -1}, 0, "roll 90 forward");
    expect_near(cam.up, {-1, 0, 0}, 0, "roll 90 up");
    expect_near(cam.right, {0, 1, 0}, 0, "roll 90 right");
    // Order: yaw applied last (outermost). yaw 90 then pitch 45: forward leans up
    // by 45° within the plane that contains −X.
    c.roll_deg = 0;
    c.yaw_deg = 90;
    c.pitch_deg = 45;
    cam = ref::make_camera(c);
    const double h = std::sqrt(0.5);
    expect_near(cam.forward, {-h, h, 0}, 1e-15, "yaw 90 pitch 45");
    expect_near(cam.eye, {1, 2, 3}, 0, "eye");
}

TEST(RefCamera, PrimaryRayThroughPixelCentres) {
    lab::CameraDesc c;
    c.position = {0, 0, 0};
    c.target = {0, 0, -1};
    c.fov_y_deg = 90.0f;
    const ref::Camera cam = ref::make_camera(c);
    // 8 × 4 image: aspect 2. Pixel (0, 0) centre → ndc (−7/8, +3/4) → direction
    // (−7/8 · 2, 3/4, −1) (tan 45° = 1). Row 0 is the top: +y.
    ref::Ray r = ref::primary_ray(cam, 8, 4, 0.5, 0.5);
    expect_near(r.dir, {-1.75, 0.75, -1}, 1e-15, "top-left");
    r = ref::primary_ray(cam, 8, 4, 7.5, 3.5);
    expect_near(r.dir, {1.75, -0.75, -1}, 1e-15, "bottom-right");
    r = ref::primary_ray(cam, 8, 4, 4.0, 2.0);
    expect_near(r.dir, {0, 0, -1}, 1e-15, "image centre");
}

// ---------------------------------------------------------------------------
// Triangle intersection
// ---------------------------------------------------------------------------

TEST(RefIntersect, FrontFaceHitBackFaceCulled) {
    // Triangle in z = 0, counter-clockwise seen from +Z.
    const dvec3 v0(-1, -1, 0), v1(1, -1, 0), v2(0, 1, 0);
    ref::Ray from_front{{0, 0, 5}, {0, 0, -1}};
    ref::TriangleHit h;
    ASSERT_TRUE(ref::intersect_triangle(from_front, v0, v1, v2, 0, 100, &h));
    EXPECT_DOUBLE_EQ(h.t, 5.0);
    // (0, 0) = 1/4·v0 + 1/4·v1 + 1/2·v2
    EXPECT_DOUBLE_EQ(h.b1, 0.25);
    EXPECT_DOUBLE_EQ(h.b2, 0.5);
    ref::Ray from_behind{{0, 0, -5}, {0, 0, 1}};
    EXPECT_FALSE(ref::intersect_triangle(from_behind, v0, v1, v2, 0, 100, &h));
    // Reversing the winding flips which side is the front.
    EXPECT_TRUE(ref::intersect_triangle(from_behind, v0, v2, v1, 0, 100, &h));
    // t range, and misses.
    EXPECT_FALSE(ref::intersect_triangle(from_front, v0, v1, v2, 0, 4.9, &h));
    EXPECT_FALSE(ref::intersect_triangle(from_front, v0, v1, v2, 5.1, 100, &h));
    EXPECT_FALSE(ref::intersect_triangle(ref::Ray{{2, 0, 5}, {0, 0, -1}}, v0, v1, v2, 0, 100, &h));
    // Parallel (edge-on) rays never hit.
    EXPECT_FALSE(ref::intersect_triangle(ref::Ray{{-5, 0, 0}, {1, 0, 0}}, v0, v1, v2, 0, 100, &h));
}

TEST(RefIntersect, EdgesAndVerticesCountAsInside) {
    const dvec3 v0(-1, -1, 0), v1(1, -1, 0), v2(0, 1, 0);
    ref::TriangleHit h;
    // Exactly on the bottom edge and exactly on a vertex.
    EXPECT_TRUE(ref::intersect_triangle(ref::Ray{{0, -1, 5}, {0, 0, -1}}, v0, v1, v2, 0, 100, &h));
    EXPECT_DOUBLE_EQ(h.b1 + h.b2, 0.5);  // halfway along v0 → v1: b0 = b1 = 0.5, b2 = 0
    EXPECT_TRUE(ref::intersect_triangle(ref::Ray{{0, 1, 5}, {0, 0, -1}}, v0, v1, v2, 0, 100, &h));
    EXPECT_DOUBLE_EQ(h.b2, 1.0);
}

TEST(RefIntersect, SharedEdgesAreWatertight) {
    // Two triangles sharing the edge a–b, both facing the ray origin region.
    // Rays aimed at points along the shared edge (which after rounding may lie
    // a hair to either side) must hit at least one of the two triangles.
    std::mt19937 rng(1234);
    std::uniform_real_distribution<double> u01(0.0, 1.0), coord(-3.0, 3.0);
    int misses = 0, tested = 0;
    for (int i = 0; i < 20000; ++i) {
        const dvec3 a(coord(rng), coord(rng), coord(rng) - 10.0);
        const dvec3 b(coord(rng), coord(rng), coord(rng) - 10.0);
        const dvec3 c(coord(rng), coord(rng), coord(rng) - 10.0);
        // d lies roughly opposite c across the edge a–b.
        const dvec3 mid = 0.5 * (a + b);
        const dvec3 d = mid + (mid - c) + dvec3(coord(rng), coord(rng), coord(rng)) * 0.3;
        const dvec3 origin(coord(rng), coord(rng), coord(rng) + 5.0);
        // Away from the end points, where the quad's open boundary begins.
        const double s = 0.01 + 0.98 * u01(rng);
        const ref::Ray ray{origin, (a + s * (b - a)) - origin};
        // Triangles a b c and b a d are consistently oriented (the edge is walked
        // a → b in one and b → a in the other). Which side faces the ray:
        auto facing = [&](dvec3 p, dvec3 q, dvec3 r) {
            const dvec3 n = glm::normalize(glm::cross(q - p, r - p));
            return glm::dot(glm::normalize(ray.dir), n);
        };
        const double f1 = facing(a, b, c), f2 = facing(b, a, d);
        if (std::abs(f1) < 1e-6 || std::abs(f2) < 1e-6) continue;  // (nearly) edge-on
        if ((f1 < 0) != (f2 < 0)) continue;  // a fold: seen from here, c and d overlap
        ref::TriangleHit h;
        bool hit1, hit2;
        if (f1 < 0) {  // both front-facing as given
            hit1 = ref::intersect_triangle(ray, a, b, c, 0, 1e9, &h);
            hit2 = ref::intersect_triangle(ray, b, a, d, 0, 1e9, &h);
        } else {  // both back-facing: flip both
            hit1 = ref::intersect_triangle(ray, b, a, c, 0, 1e9, &h);
            hit2 = ref::intersect_triangle(ray, a, b, d, 0, 1e9, &h);
        }
        ++tested;
        if (!hit1 && !hit2) ++misses;
    }
    EXPECT_GT(tested, 5000);
    EXPECT_EQ(misses, 0);
}

TEST(RefIntersect, SharedVertexOfAFanIsHit) {
    // Six triangles around the centre vertex, all counter-clockwise from +Z;
    // a ray exactly through the centre must hit one of them.
    const dvec3 centre(0.1, 0.2, -3.0);
    int hits = 0;
    for (int k = 0; k < 6; ++k) {
        const double a0 = k * 60.0, a1 = (k + 1) * 60.0;
        const dvec3 p0 = centre + dvec3(ref::cos_deg(a0), ref::sin_deg(a0), 0.0);
        const dvec3 p1 = centre + dvec3(ref::cos_deg(a1), ref::sin_deg(a1), 0.0);
        ref::TriangleHit h;
        if (ref::intersect_triangle(ref::Ray{{0, 0, 0}, centre}, centre, p0, p1, 0, 10, &h)) ++hits;
    }
    EXPECT_GE(hits, 1);
}

// ---------------------------------------------------------------------------
// Rendering: coverage worked out by hand
// ---------------------------------------------------------------------------

TEST(RefRender, PlaneCoverageByHand) {
    // Camera at (0,0,2) looking at the origin, fov 90°, 8×8. A 2×2 plane in z = 0
    // facing the camera spans x, y ∈ [−1, 1] at depth 2: ndc ∈ [−0.5, 0.5].
    // Pixel centres at ndc ±0.125 and ±0.375 are inside, ±0.625 outside: pixels 2..5.
    lab::Scene s = base_scene();
    s.background = {0.25f, 0.5f, 0.75f};
    look(s, {0, 0, 2}, {0, 0, 0});
    s.objects.push_back(facing_plus_z("red", {0, 0, 0}, 2.0f));
    const ref::RefImage img = ref::render_reference(s, 8, 8);
    EXPECT_EQ(pixels_of(img, 0), rect(2, 5, 2, 5));

    // Colours: albedo inside, background outside.
    expect_near(img.linear[img.index(3, 3)], {1, 0, 0}, 0, "albedo");
    expect_near(img.linear[img.index(0, 0)], {0.25, 0.5, 0.75}, 0, "background");
    EXPECT_EQ(img.triangle_id[img.index(0, 0)], -1);
    EXPECT_FALSE(img.hits[img.index(0, 0)].hit);

    // Hit data at pixel (2, 2): ndc (−0.375, +0.375) → world (−0.75, 0.75, 0), depth 2.
    // The plane's texture top-left (uv 0,0) is its model-space corner (−½, 0, −½),
    // which Rx(90°)·S(2) moves to (−1, 1, 0): u = (x + 1)/2 = 0.125, v = (1 − y)/2 = 0.125.
    const ref::Hit& h = img.hits[img.index(2, 2)];
    ASSERT_TRUE(h.hit);
    EXPECT_EQ(h.material, "red");
    EXPECT_NEAR(h.depth, 2.0, 1e-12);
    expect_near(h.position, {-0.75, 0.75, 0}, 1e-12, "position");
    expect_near(h.normal, {0, 0, 1}, 1e-7, "normal");
    expect_near(h.geometric_normal, {0, 0, 1}, 1e-12, "geometric normal");
    EXPECT_NEAR(h.uv.x, 0.125, 1e-7);
    EXPECT_NEAR(h.uv.y, 0.125, 1e-7);
    expect_near(h.view_dir, glm::normalize(dvec3(0.75, -0.75, 2)), 1e-12, "view dir");
}

TEST(RefRender, NonSquareAspect) {
    // 16×8 (aspect 2), fov 90°, camera at depth 2 from a 2×2 plane: horizontal
    // ndc = x / (2·aspect) ∈ [−0.25, 0.25], vertical ndc = y / 2 ∈ [−0.5, 0.5].
    // Columns: centres (k + 0.5)/8 − 1 → ±0.0625, ±0.1875 inside (k = 6..9).
    // Rows: centres (k + 0.5)/4 − 1 → ±0.125, ±0.375 inside (k = 2..5).
    lab::Scene s = base_scene();
    look(s, {0, 0, 2}, {0, 0, 0});
    s.objects.push_back(facing_plus_z("red", {0, 0, 0}, 2.0f));
    const ref::RefImage img = ref::render_reference(s, 16, 8);
    EXPECT_EQ(pixels_of(img, 0), rect(6, 9, 2, 5));
}

TEST(RefRender, DiagonalEdgeOfAQuadLeavesNoGap) {
    // The plane fills the whole 8×8 view (ndc ±1); its two triangles share the
    // diagonal from (−1,−1) to (1,1), which passes exactly through the centres
    // of pixels (k, 7 − k). Every pixel must be covered.
    lab::Scene s = base_scene();
    look(s, {0, 0, 1}, {0, 0, 0});
    s.objects.push_back(facing_plus_z("red", {0, 0, 0}, 2.0f));
    const ref::RefImage img = ref::render_reference(s, 8, 8);
    EXPECT_EQ(pixels_of(img, 0), rect(0, 7, 0, 7));
    std::set<int> triangles(img.triangle_id.begin(), img.triangle_id.end());
    EXPECT_EQ(triangles, (std::set<int>{0, 1}));
}

TEST(RefRender, SphereHasNoPinholes) {
    // A finely tessellated sphere: every pixel whose four neighbours show the
    // sphere must show it too (a crack between triangles would show background).
    lab::Scene s = base_scene();
    look(s, {0.3, 0.2, 1.6}, {0, 0, 0});
    s.camera.fov_y_deg = 40.0f;  // the sphere fills most of the view
    lab::ObjectDesc sphere = object("sphere", "red", {0, 0, 0});
    sphere.segments = 64;
    sphere.rings = 32;
    s.objects.push_back(sphere);
    const ref::RefImage img = ref::render_reference(s, 200, 200);
    int holes = 0;
    for (int y = 1; y < img.height - 1; ++y)
        for (int x = 1; x < img.width - 1; ++x)
            if (img.object_id[img.index(x, y)] != 0 && img.object_id[img.index(x - 1, y)] == 0 &&
                img.object_id[img.index(x + 1, y)] == 0 && img.object_id[img.index(x, y - 1)] == 0 &&
                img.object_id[img.index(x, y + 1)] == 0)
                ++holes;
    EXPECT_EQ(holes, 0);
    EXPECT_GT(pixels_of(img, 0).size(), 10000u);
}

TEST(RefRender, SphereHitData) {
    // 9×9 image: pixel (4, 4) is the exact image centre. The default UV sphere
    // (radius 0.5) has a vertex at (0, 0, 0.5) with normal +Z, facing the camera.
    lab::Scene s = base_scene();
    look(s, {0, 0, 3}, {0, 0, 0});
    s.objects.push_back(object("sphere", "blue", {0, 0, 0}));
    const ref::RefImage img = ref::render_reference(s, 9, 9);
    const ref::Hit& h = img.hits[img.index(4, 4)];
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.depth, 2.5, 1e-6);
    expect_near(h.position, {0, 0, 0.5}, 1e-6, "position");
    expect_near(h.normal, {0, 0, 1}, 1e-6, "normal");
    EXPECT_NEAR(h.uv.x, 0.5, 1e-6);  // u = 0.5 faces +Z
    EXPECT_NEAR(h.uv.y, 0.5, 1e-6);  // the equator
}

TEST(RefRender, BackFacesAreCulled) {
    // The plane's front is +Y: seen from above it is visible, from below not.
    lab::Scene s = base_scene();
    // Side 8: ±4 at depth 3 is ndc ±4/3, the whole view.
    s.objects.push_back(object("plane", "red", {0, 0, 0}, {0, 0, 0}, glm::vec3(8.0f)));
    look(s, {0, 3, 0}, {0, 0, 0});
    EXPECT_EQ(pixels_of(ref::render_reference(s, 8, 8), 0), rect(0, 7, 0, 7));
    look(s, {0, -3, 0}, {0, 0, 0});
    EXPECT_TRUE(pixels_of(ref::render_reference(s, 8, 8), 0).empty());
    // A camera inside a cube sees nothing: all its faces point away.
    lab::Scene inside = base_scene();
    inside.objects.push_back(object("cube", "red", {0, 0, 0}, {0, 0, 0}, glm::vec3(4.0f)));
    look(inside, {0, 0, 0}, {0.3, -0.2, -1});
    EXPECT_TRUE(pixels_of(ref::render_reference(inside, 16, 16), 0).empty());
}

TEST(RefRender, NegativeScaleFlipsTheFrontFace) {
    // Mirroring in X reverses the winding of the transformed triangles: the
    // plane's front now faces −Y, as the GPU's winding test sees it.
    lab::Scene s = base_scene();
    s.objects.push_back(object("plane", "red", {0, 0, 0}, {0, 0, 0}, {-8.0f, 1.0f, 8.0f}));
    look(s, {0, 3, 0}, {0, 0, 0});
    EXPECT_TRUE(pixels_of(ref::render_reference(s, 8, 8), 0).empty());
    look(s, {0, -3, 0}, {0, 0, 0});
    EXPECT_EQ(pixels_of(ref::render_reference(s, 8, 8), 0), rect(0, 7, 0, 7));
    // Two negative components mirror twice (here: a 180° turn about Y), so
    // the winding is back to normal and the front faces +Y again.
    s.objects[0].scale = {-8.0f, 1.0f, -8.0f};
    EXPECT_TRUE(pixels_of(ref::render_reference(s, 8, 8), 0).empty());  // camera still below
    look(s, {0, 3, 0}, {0, 0, 0});
    EXPECT_EQ(pixels_of(ref::render_reference(s, 8, 8), 0), rect(0, 7, 0, 7));
}

TEST(RefRender, NearerObjectWinsWhateverTheOrder) {
    // Red 2×2 plane at z = 0 (depth 2, ndc ±0.5: pixels 2..5), green 1×1 plane
    // at z = 0.5 (depth 1.5, ndc ±1/3: pixels 3..4 only, 0.375 > 1/3).
    for (int order = 0; order < 2; ++order) {
        lab::Scene s = base_scene();
        look(s, {0, 0, 2}, {0, 0, 0});
        s.objects.push_back(facing_plus_z("red", {0, 0, 0}, 2.0f));
        s.objects.push_back(facing_plus_z("green", {0, 0, 0.5f}, 1.0f));
        if (order == 1) std::swap(s.objects[0], s.objects[1]);
        const int red = order == 0 ? 0 : 1, green = 1 - red;
        const ref::RefImage img = ref::render_reference(s, 8, 8);
        std::set<std::pair<int, int>> red_px = rect(2, 5, 2, 5);
        for (auto p : rect(3, 4, 3, 4)) red_px.erase(p);
        EXPECT_EQ(pixels_of(img, green), rect(3, 4, 3, 4)) << "order " << order;
        EXPECT_EQ(pixels_of(img, red), red_px) << "order " << order;
        EXPECT_NEAR(img.hits[img.index(3, 3)].depth, 1.5, 1e-12);
    }
}

TEST(RefRender, NearAndFarPlanesClip) {
    lab::Scene s = base_scene();
    look(s, {0, 0, 2}, {0, 0, 0});
    s.objects.push_back(facing_plus_z("red", {0, 0, 0}, 2.0f));      // depth 2
    s.objects.push_back(facing_plus_z("green", {0, 0, 0.5f}, 1.0f));  // depth 1.5
    auto render = [&](float n, float f) {
        s.camera.near_plane = n;
        s.camera.far_plane = f;
        return ref::render_reference(s, 8, 8);
    };
    // Both inside [near, far].
    ref::RefImage img = render(1.0f, 3.0f);
    EXPECT_EQ(img.object_id[img.index(3, 3)], 1);
    // Near plane between them: the green plane is clipped and red shows through.
    img = render(1.75f, 3.0f);
    EXPECT_EQ(img.object_id[img.index(3, 3)], 0);
    EXPECT_EQ(pixels_of(img, 1).size(), 0u);
    // Far plane between them: only green.
    img = render(1.0f, 1.75f);
    EXPECT_EQ(pixels_of(img, 0).size(), 0u);
    EXPECT_EQ(pixels_of(img, 1), rect(3, 4, 3, 4));
    // Beyond far / before near: nothing.
    EXPECT_TRUE(pixels_of(render(2.5f, 10.0f), 0).empty());
    EXPECT_TRUE(pixels_of(render(0.1f, 1.4f), 1).empty());
    // Depth is measured along the view axis, not along the ray: the corner pixel
    // (2, 2) of the red plane has ray length 2·sqrt(1 + 2·0.375²) ≈ 2.27 but depth 2,
    // so far = 2.1 keeps every red pixel.
    img = render(1.9f, 2.1f);
    EXPECT_EQ(pixels_of(img, 0), rect(2, 5, 2, 5));
}

TEST(RefRender, TransformCameraYaw90LooksDownMinusX) {
    lab::Scene s = base_scene();
    s.camera.mode = lab::CameraDesc::Mode::Transform;
    s.camera.position = {0, 0, 0};
    s.camera.yaw_deg = 90;
    // A plane at x = −5 facing +X (Rz(−90°) turns +Y into +X), another at z = −5 facing +Z.
    s.objects.push_back(object("plane", "red", {-5, 0, 0}, {0, 0, -90}, glm::vec3(2.0f)));
    s.objects.push_back(facing_plus_z("green", {0, 0, -5}, 2.0f));
    ref::RefImage img = ref::render_reference(s, 8, 8);
    // ±1 at depth 5: ndc ±0.2 → only the centre pixels 3..4.
    EXPECT_EQ(pixels_of(img, 0), rect(3, 4, 3, 4));
    EXPECT_TRUE(pixels_of(img, 1).empty());
    // With yaw 0 it is the other way round.
    s.camera.yaw_deg = 0;
    img = ref::render_reference(s, 8, 8);
    EXPECT_TRUE(pixels_of(img, 0).empty());
    EXPECT_EQ(pixels_of(img, 1), rect(3, 4, 3, 4));
}

TEST(RefRender, TransformCameraRollTiltsImageClockwise) {
    // A unit cube at (−1, 0, −5), fov 90°, 16×16 (pixel centres ±0.0625, ±0.1875,
    // ±0.3125, ...). Its front face is at depth 4.5.
    // No roll: x ∈ [−1.5, −0.5] → ndc [−1/3, −1/9] → columns 5, 6;
    //          y ∈ [−0.5, 0.5]  → ndc ±1/9          → rows 7, 8.
    // Roll 90°: camera up = −X, right = +Y, so the cube (left of centre) moves to
    // the top: rows 5, 6, columns 7, 8 — the image turned clockwise.
    lab::Scene s = base_scene();
    s.camera.mode = lab::CameraDesc::Mode::Transform;
    s.camera.position = {0, 0, 0};
    s.objects.push_back(object("cube", "red", {-1, 0, -5}));
    EXPECT_EQ(pixels_of(ref::render_reference(s, 16, 16), 0), rect(5, 6, 7, 8));
    s.camera.roll_deg = 90;
    EXPECT_EQ(pixels_of(ref::render_reference(s, 16, 16), 0), rect(7, 8, 5, 6));
    // Pitch 90° looks up: a plane at y = 5 facing down (Rx(180°)) fills the centre.
    s.camera.roll_deg = 0;
    s.camera.pitch_deg = 90;
    s.objects[0] = object("plane", "red", {0, 5, 0}, {180, 0, 0}, glm::vec3(2.0f));
    EXPECT_EQ(pixels_of(ref::render_reference(s, 8, 8), 0), rect(3, 4, 3, 4));
}

TEST(RefRender, TopDownLookAtIsAMapView) {
    // Camera at (0, 10, 0) looking down with up = +Y: the image top is world −Z,
    // the right is +X (docs/conventions.md). Fov 90°, 16×16.
    // Cube of side 2 at (0, 0, −4): its top face (y = 1, depth 9) spans
    // z ∈ [−5, −3] → camera y = −z ∈ [3, 5] → ndc [1/3, 5/9]: row 4 (ndc 0.4375);
    // x ∈ [−1, 1] → ndc ±1/9: columns 7, 8. Its +Z face (z = −3, facing the
    // camera) spans depth 9..11 → ndc y ∈ [3/11, 1/3]: row 5 (ndc 0.3125, where
    // the depth is 3/0.3125 = 9.6 and x = ±1 gives ndc ±0.104: columns 7, 8).
    lab::Scene s = base_scene();
    look(s, {0, 10, 0}, {0, 0, 0});
    s.objects.push_back(object("cube", "red", {0, 0, -4}, {0, 0, 0}, glm::vec3(2.0f)));
    s.objects.push_back(object("cube", "green", {4, 0, 0}, {0, 0, 0}, glm::vec3(2.0f)));
    const ref::RefImage img = ref::render_reference(s, 16, 16);
    EXPECT_EQ(pixels_of(img, 0), rect(7, 8, 4, 5));
    // The +X cube likewise: top face x ∈ [3, 5] → column 11; its −X face
    // (x = 3) → ndc x ∈ [3/11, 1/3] → column 10; z ∈ [−1, 1] → rows 7, 8.
    EXPECT_EQ(pixels_of(img, 1), rect(10, 11, 7, 8));
}

TEST(RefRender, EyeEqualsTargetLooksDownMinusZ) {
    lab::Scene s = base_scene();
    look(s, {0, 0, 0}, {0, 0, 0});
    s.objects.push_back(facing_plus_z("red", {0, 0, -5}, 2.0f));
    EXPECT_EQ(pixels_of(ref::render_reference(s, 8, 8), 0), rect(3, 4, 3, 4));
}

TEST(RefRender, CustomShadeFunctionSeesHits) {
    lab::Scene s = base_scene();
    look(s, {0, 0, 2}, {0, 0, 0});
    s.objects.push_back(facing_plus_z("red", {0, 0, 0}, 2.0f));
    // Shade by depth: a later lab plugs Blinn-Phong in the same way.
    const ref::RefImage img = ref::render_reference(
        s, 8, 8, [](const lab::Scene&, const ref::Hit& h) {
            return h.hit ? dvec3(h.depth / 4.0) : dvec3(1.0, 0.0, 1.0);
        });
    expect_near(img.linear[img.index(3, 3)], dvec3(0.5), 1e-12, "depth shade");
    expect_near(img.linear[img.index(0, 0)], {1, 0, 1}, 0, "miss shade");
}

TEST(RefRender, ShadeErrorsReachTheCaller) {
    // Large enough to be rendered on several threads.
    lab::Scene s = base_scene();
    look(s, {0, 0, 2}, {0, 0, 0});
    s.objects.push_back(facing_plus_z("no such material", {0, 0, 0}, 2.0f));
    EXPECT_THROW(ref::render_reference(s, 128, 128), std::runtime_error);
}

TEST(RefRender, DeterministicAndFastEnough) {
    // A scene like the lab's default, at full HD-ish resolution. Prints the time
    // (the oracle must stay usable at 1280×720).
    lab::Scene s = base_scene();
    look(s, {0, 3, 8}, {0, 0.5, 0});
    s.camera.fov_y_deg = 60.0f;
    s.objects.push_back(object("plane", "red", {0, 0, 0}, {0, 0, 0}, glm::vec3(20.0f)));
    for (int i = 0; i < 6; ++i) {
        s.objects.push_back(object("sphere", "green", {-5.0f + 2.0f * i, 0.75f, -1.0f},
                                   glm::vec3(0.0f), glm::vec3(1.5f)));
        s.objects.push_back(object("cube", "blue", {-5.0f + 2.0f * i, 0.5f, 2.0f},
                                   {10.0f * i, 20.0f * i, 5.0f * i}));
    }
    const auto t0 = std::chrono::steady_clock::now();
    const ref::RefImage a = ref::render_reference(s, 1280, 720);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ref::SceneGeometry geometry(s);
    std::printf("[ oracle ] 1280x720, %zu triangles: %.3f s\n", geometry.triangle_count(), seconds);
    RecordProperty("oracle_seconds_1280x720", std::to_string(seconds));
    EXPECT_LT(seconds, 30.0);  // generous: sanitizer builds are much slower

    const ref::RefImage b = ref::render_reference(s, 1280, 720);
    EXPECT_EQ(a.object_id, b.object_id);
    EXPECT_EQ(a.triangle_id, b.triangle_id);
    EXPECT_EQ(ref::encode_srgb(a).rgba, ref::encode_srgb(b).rgba);
}

// ---------------------------------------------------------------------------
// sRGB
// ---------------------------------------------------------------------------

int encoded(double linear) {
    ref::RefImage img;
    img.width = img.height = 1;
    img.linear = {dvec3(linear, 0.0, 1.0)};
    img.object_id = {-1};
    img.triangle_id = {-1};
    const lab::Image8 out = ref::encode_srgb(img);
    EXPECT_EQ(out.rgba[3], 255);  // alpha
    return out.rgba[0];
}

TEST(RefSrgb, KnownValues) {
    EXPECT_EQ(encoded(0.0), 0);
    EXPECT_EQ(encoded(1.0), 255);
    // 1.055 · 0.5^(1/2.4) − 0.055 = 0.735361 → ·255 = 187.516 → 188
    EXPECT_EQ(encoded(0.5), 188);
    // Linear segment up to 0.0031308: 12.92 · 0.0031308 = 0.040450 → ·255 = 10.31 → 10
    EXPECT_EQ(encoded(0.0031308), 10);
    EXPECT_NEAR(ref::srgb_encode(0.0031308), 0.04044994, 1e-8);
    // Both pieces meet (almost) continuously at the boundary.
    EXPECT_NEAR(1.055 * std::pow(0.0031308, 1.0 / 2.4) - 0.055, 12.92 * 0.0031308, 1e-7);
    // 0.2140 → 1.055 · 0.214^(1/2.4) − 0.055 = 0.499956 → ·255 = 127.489 → 127 (not 128).
    EXPECT_EQ(encoded(0.2140), 127);
    // 128 needs linear ≥ 0.21586 (127.9999 at 0.21586 still rounds to 128).
    EXPECT_EQ(encoded(0.21586), 128);
    // 0.18 (photographic mid grey) → 0.461356 → 117.65 → 118
    EXPECT_EQ(encoded(0.18), 118);
    // Small linear values: 0.001 → 12.92 · 0.001 · 255 = 3.29 → 3
    EXPECT_EQ(encoded(0.001), 3);
    // Clamping.
    EXPECT_EQ(encoded(-0.5), 0);
    EXPECT_EQ(encoded(7.0), 255);
}

TEST(RefSrgb, EveryCodeRoundTrips) {
    // Decoding code k to linear and encoding again must give k back (the two
    // curves are written independently).
    for (int k = 0; k <= 255; ++k) EXPECT_EQ(encoded(ref::srgb_decode(k / 255.0)), k) << k;
}

// ---------------------------------------------------------------------------
// Image comparison
// ---------------------------------------------------------------------------

struct RefCompare : ::testing::Test {
    ref::RefImage reference;
    lab::Image8 expected;
    void SetUp() override {
        lab::Scene s = base_scene();
        s.background = {0.1f, 0.2f, 0.3f};
        look(s, {0, 0, 2}, {0, 0, 0});
        s.objects.push_back(facing_plus_z("red", {0, 0, 0}, 2.0f));
        reference = ref::render_reference(s, 64, 64);
        expected = ref::encode_srgb(reference);
    }
    // Plane spans ndc ±0.5 → pixels 16..47 (centres ndc (k+0.5)/32 − 1).
};

TEST_F(RefCompare, EdgeMaskIsTheBoundaryBand) {
    EXPECT_EQ(pixels_of(reference, 0), rect(16, 47, 16, 47));
    const std::vector<uint8_t> mask = ref::edge_mask(reference);
    auto at = [&](int x, int y) { return mask[reference.index(x, y)] != 0; };
    EXPECT_TRUE(at(15, 30));   // background next to the plane
    EXPECT_TRUE(at(16, 30));   // plane next to background
    EXPECT_FALSE(at(17, 30));  // plane interior
    EXPECT_FALSE(at(14, 30));  // background interior
    EXPECT_TRUE(at(47, 47));
    EXPECT_TRUE(at(48, 48));   // diagonal neighbour
    EXPECT_FALSE(at(30, 30));
    EXPECT_FALSE(at(0, 0));
    // Band of width 2 around a 32×32 square: 34² − 30² = 256 pixels.
    size_t count = 0;
    for (uint8_t m : mask) count += m;
    EXPECT_EQ(count, 34u * 34u - 30u * 30u);
}

TEST_F(RefCompare, OptionalTriangleAndGrazingEdges) {
    // The plane's two triangles meet on the diagonal from its bottom-left to
    // its top-right corner: with triangle_edges that seam joins the mask.
    ref::CompareOptions options;
    options.triangle_edges = true;
    const std::vector<uint8_t> mask = ref::edge_mask(reference, options);
    EXPECT_TRUE(mask[reference.index(31, 32)] != 0);   // on the diagonal
    EXPECT_FALSE(mask[reference.index(20, 20)] != 0);  // top-left triangle, away from the seam
    EXPECT_FALSE(mask[reference.index(40, 40)] != 0);  // bottom-right triangle
    // The plane is seen at most ~35° off its normal: a grazing threshold of
    // cos 30° < 0.82 marks none of it, cos 0 = 1 marks all of it.
    options.triangle_edges = false;
    options.grazing_cos = 0.8;
    EXPECT_FALSE(ref::edge_mask(reference, options)[reference.index(30, 30)] != 0);
    options.grazing_cos = 1.0;
    EXPECT_TRUE(ref::edge_mask(reference, options)[reference.index(30, 30)] != 0);
    EXPECT_FALSE(ref::edge_mask(reference, options)[reference.index(2, 2)] != 0);  // background
}

TEST_F(RefCompare, IdenticalImagesPass) {
    const ref::CompareResult r = ref::compare_images(expected, reference);
    EXPECT_TRUE(r.passed()) << r.describe();
    EXPECT_EQ(r.max_diff_all, 0);
    EXPECT_EQ(r.differing_pixels, 0u);
    EXPECT_EQ(r.worst_x, -1);
}

TEST_F(RefCompare, OffByOneInteriorPasses) {
    lab::Image8 actual = expected;
    actual.rgba[4 * reference.index(30, 30) + 1] += 1;
    const ref::CompareResult r = ref::compare_images(actual, reference);
    EXPECT_TRUE(r.passed()) << r.describe();
    EXPECT_EQ(r.max_diff_interior, 1);
    EXPECT_EQ(r.differing_pixels, 0u);
}

TEST_F(RefCompare, InteriorDifferenceFailsAndIsLocated) {
    lab::Image8 actual = expected;
    actual.rgba[4 * reference.index(20, 40) + 2] += 2;
    actual.rgba[4 * reference.index(5, 6) + 0] += 9;
    const ref::CompareResult r = ref::compare_images(actual, reference);
    EXPECT_FALSE(r.passed());
    EXPECT_EQ(r.max_diff_interior, 9);
    EXPECT_EQ(r.worst_x, 5);
    EXPECT_EQ(r.worst_y, 6);
    EXPECT_EQ(r.differing_pixels, 2u);
    EXPECT_NE(r.describe().find("(5, 6)"), std::string::npos) << r.describe();
}

TEST_F(RefCompare, EdgeDifferencesAreToleratedUpToAFraction) {
    // A whole silhouette column rendered as background (a coverage rounding
    // difference): 32 of 4096 pixels = 0.78% > 0.5% → fails overall, but
    // interior stays clean. Half of it (16 px = 0.39%) passes.
    lab::Image8 actual = expected;
    for (int y = 16; y < 32; ++y)
        for (int ch = 0; ch < 4; ++ch)
            actual.rgba[4 * reference.index(16, y) + ch] = expected.rgba[4 * reference.index(15, y) + ch];
    ref::CompareResult r = ref::compare_images(actual, reference);
    EXPECT_TRUE(r.passed()) << r.describe();
    EXPECT_EQ(r.max_diff_interior, 0);
    EXPECT_EQ(r.differing_pixels, 16u);
    for (int y = 32; y < 48; ++y)
        for (int ch = 0; ch < 4; ++ch)
            actual.rgba[4 * reference.index(16, y) + ch] = expected.rgba[4 * reference.index(15, y) + ch];
    r = ref::compare_images(actual, reference);
    EXPECT_FALSE(r.passed()) << r.describe();
    EXPECT_EQ(r.max_diff_interior, 0);
    EXPECT_GT(r.max_diff_all, 100);
}

TEST_F(RefCompare, AlphaAndSizeAreChecked) {
    lab::Image8 actual = expected;
    actual.rgba[4 * reference.index(30, 30) + 3] = 0;
    EXPECT_FALSE(ref::compare_images(actual, reference).passed());
    lab::Image8 small = expected;
    small.width = 32;
    const ref::CompareResult r = ref::compare_images(small, reference);
    EXPECT_TRUE(r.size_mismatch);
    EXPECT_FALSE(r.passed());
}

TEST_F(RefCompare, FailureWritesADiffImage) {
    lab::Image8 actual = expected;
    actual.rgba[4 * reference.index(30, 30)] ^= 0x80;
    const std::string path = std::string(LAB_BINARY_DIR) + "/test_output/compare_selftest_diff.png";
    std::filesystem::remove(path);
    const ref::CompareResult r = ref::compare_and_report(actual, reference, path);
    EXPECT_FALSE(r.passed());
    ASSERT_EQ(r.diff_image, path) << r.describe();
    const lab::Image8 diff = lab::read_png(path);
    EXPECT_EQ(diff.width, 3 * 64);
    EXPECT_EQ(diff.height, 64);
    // Passing comparisons write nothing.
    std::filesystem::remove(path);
    EXPECT_TRUE(ref::compare_and_report(expected, reference, path).passed());
    EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
