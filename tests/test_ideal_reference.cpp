// test_ideal_reference.cpp — the exact shapes behind the tessellated primitives
// (reference/analytic.h, reference/ideal.h), the error figures (image_compare.h)
// and the two commands built on them, against hand-computed values.
#include "reference/analytic.h"
#include "reference/cpu_reference.h"
#include "reference/ideal.h"
#include "reference/image_compare.h"
#include "lab_runner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

namespace {

using glm::dvec3;
constexpr double kEps = 1e-12;

void expect_vec(const dvec3& got, const dvec3& want, double eps = 1e-12) {
    EXPECT_NEAR(got.x, want.x, eps);
    EXPECT_NEAR(got.y, want.y, eps);
    EXPECT_NEAR(got.z, want.z, eps);
}

constexpr double kInf = 1e30;

}  // namespace

// --- polynomial roots ---------------------------------------------------------------

TEST(AnalyticRoots, QuarticWithFourSimpleRoots) {
    // (x−1)(x−2)(x−3)(x−4) = x⁴ − 10x³ + 35x² − 50x + 24
    const double c[5] = {24, -50, 35, -10, 1};
    double r[4];
    ASSERT_EQ(ref::polynomial_roots(c, 4, -10, 10, r), 4);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(r[i], i + 1.0, kEps);
    // Only those inside the interval.
    ASSERT_EQ(ref::polynomial_roots(c, 4, 1.5, 3.5, r), 2);
    EXPECT_NEAR(r[0], 2.0, kEps);
    EXPECT_NEAR(r[1], 3.0, kEps);
}

TEST(AnalyticRoots, CloseRootsAreSeparated) {
    // (x − 1)² − 1e−12: roots 1 ± 1e−6, a nearly grazing ray.
    const double c[3] = {1.0 - 1e-12, -2.0, 1.0};
    double r[2];
    ASSERT_EQ(ref::polynomial_roots(c, 2, 0, 2, r), 2);
    EXPECT_NEAR(r[0], 1.0 - 1e-6, 1e-9);  // the rounding of 1 − 1e−12 alone moves them ~1e−11
    EXPECT_NEAR(r[1], 1.0 + 1e-6, 1e-9);
    // x⁴ − 1: ±1 (and no root where the quartic only dips towards 0).
    const double q[5] = {-1, 0, 0, 0, 1};
    double s[4];
    ASSERT_EQ(ref::polynomial_roots(q, 4, -5, 5, s), 2);
    EXPECT_NEAR(s[0], -1.0, kEps);
    EXPECT_NEAR(s[1], 1.0, kEps);
    // x² + 1e−12: no real root.
    const double none[3] = {1e-12, 0.0, 1.0};
    EXPECT_EQ(ref::polynomial_roots(none, 2, -1, 1, s), 0);
}

// --- sphere -------------------------------------------------------------------------

TEST(AnalyticSphere, HeadOnHit) {
    ref::ShapeHit h;
    ASSERT_TRUE(ref::intersect_sphere({0, 0, 5}, {0, 0, -1}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 4.5, kEps);
    expect_vec(h.normal, {0, 0, 1});
    EXPECT_NEAR(h.uv.x, 0.5, kEps);  // u = 0.5 faces +Z
    EXPECT_NEAR(h.uv.y, 0.5, kEps);  // the equator
    expect_vec(h.tangent, {1, 0, 0});  // +u runs counter-clockwise seen from above: +X at +Z
    // A longer direction vector: t in its units.
    ASSERT_TRUE(ref::intersect_sphere({0, 0, 5}, {0, 0, -2}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 2.25, kEps);
}

TEST(AnalyticSphere, GrazingAndInside) {
    ref::ShapeHit h;
    // 1e−4 inside the silhouette: z = √(0.25 − 0.4999²) = 0.0099995.
    ASSERT_TRUE(ref::intersect_sphere({0.4999, 0, 5}, {0, 0, -1}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 5.0 - std::sqrt(0.25 - 0.4999 * 0.4999), 1e-12);
    EXPECT_FALSE(ref::intersect_sphere({0.5001, 0, 5}, {0, 0, -1}, 0, kInf, 1, &h));
    // From the centre only the inside faces the ray: culled, unless the inside is asked for.
    EXPECT_FALSE(ref::intersect_sphere({0, 0, 0}, {0, 0, -1}, 0, kInf, 1, &h));
    ASSERT_TRUE(ref::intersect_sphere({0, 0, 0}, {0, 0, -1}, 0, kInf, -1, &h));
    EXPECT_NEAR(h.t, 0.5, kEps);
    // The near/far interval.
    EXPECT_FALSE(ref::intersect_sphere({0, 0, 5}, {0, 0, -1}, 0, 4.4, 1, &h));
    // The north pole: v = 0.
    ASSERT_TRUE(ref::intersect_sphere({0, 3, 0}, {0, -1, 0}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 2.5, kEps);
    EXPECT_NEAR(h.uv.y, 0.0, kEps);
}

// --- cylinder -----------------------------------------------------------------------

TEST(AnalyticCylinder, SideAndCaps) {
    ref::ShapeHit h;
    ASSERT_TRUE(ref::intersect_cylinder({0, 0.4, 5}, {0, 0, -1}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 4.5, kEps);
    expect_vec(h.normal, {0, 0, 1});
    EXPECT_EQ(h.part, 0);
    EXPECT_NEAR(h.uv.y, 0.1, kEps);  // v = 0.5 − y from the top rim
    // Top cap from above: planar UVs u = 0.5 + x, v = 0.5 + z.
    ASSERT_TRUE(ref::intersect_cylinder({0.2, 5, 0.1}, {0, -1, 0}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 4.5, kEps);
    expect_vec(h.normal, {0, 1, 0});
    EXPECT_EQ(h.part, 1);
    EXPECT_NEAR(h.uv.x, 0.7, kEps);
    EXPECT_NEAR(h.uv.y, 0.6, kEps);
    // Bottom cap from below: seen from below the image top is at +Z (v = 0.5 − z).
    ASSERT_TRUE(ref::intersect_cylinder({0.2, -5, 0.1}, {0, 1, 0}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 4.5, kEps);
    expect_vec(h.normal, {0, -1, 0});
    EXPECT_EQ(h.part, 2);
    EXPECT_NEAR(h.uv.y, 0.4, kEps);
    // Oblique through the top cap: from (0, 2, 2) towards (0, 0.5, 0.3): crosses y = 0.5 at z = 0.3.
    ASSERT_TRUE(ref::intersect_cylinder({0, 2, 2}, {0, -1.5, -1.7}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 1.0, kEps);
    EXPECT_EQ(h.part, 1);
    // Misses: beside it, above it along the axis direction, and just past the rim.
    EXPECT_FALSE(ref::intersect_cylinder({0.6, 5, 0}, {0, -1, 0}, 0, kInf, 1, &h));
    EXPECT_FALSE(ref::intersect_cylinder({0, 0.51, 5}, {0, 0, -1}, 0, kInf, 1, &h));
}

// --- cone ---------------------------------------------------------------------------

TEST(AnalyticCone, SideApexAndBase) {
    ref::ShapeHit h;
    // At y = 0 the radius is 0.25; the normal is ∝ (0, 0.5, 1) (docs/meshes.md).
    ASSERT_TRUE(ref::intersect_cone({0, 0, 5}, {0, 0, -1}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 4.75, kEps);
    expect_vec(h.normal, glm::normalize(dvec3(0, 0.5, 1)));
    EXPECT_NEAR(h.uv.y, 0.5, kEps);  // v from the apex (0) to the rim (1)
    // Straight down onto the apex.
    ASSERT_TRUE(ref::intersect_cone({0, 5, 0}, {0, -1, 0}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 4.5, 1e-9);
    // Straight up onto the base.
    ASSERT_TRUE(ref::intersect_cone({0.1, -5, 0.2}, {0, 1, 0}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 4.5, kEps);
    expect_vec(h.normal, {0, -1, 0});
    EXPECT_EQ(h.part, 2);
    // Above the apex the other nappe of x² + z² = (0.5 − y)²/4 is not part of the cone.
    EXPECT_FALSE(ref::intersect_cone({0, 0.6, 5}, {0, 0, -1}, 0, kInf, 1, &h));
    // Past the slant: at y = 0 a ray at x = 0.26 misses.
    EXPECT_FALSE(ref::intersect_cone({0.26, 0, 5}, {0, 0, -1}, 0, kInf, 1, &h));
}

// --- torus --------------------------------------------------------------------------
// R = 0.35, r = 0.15: in the plane z = 0 the torus is the two circles of radius 0.15
// around (±0.35, 0); in y = 0 it is the ring 0.2 ≤ √(x² + z²) ≤ 0.5.

TEST(AnalyticTorus, AlongADiameter) {
    ref::ShapeHit h;
    ASSERT_TRUE(ref::intersect_torus({-5, 0, 0}, {1, 0, 0}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 4.5, 1e-12);
    expect_vec(h.normal, {-1, 0, 0});
    EXPECT_NEAR(h.uv.y, 0.25, 1e-12);  // the outside of the tube
    EXPECT_NEAR(h.uv.x, 0.25, 1e-12);  // −X is a quarter turn from −Z
    // The next front face is the inner wall of the far side, x = 0.2.
    ASSERT_TRUE(ref::intersect_torus({-5, 0, 0}, {1, 0, 0}, 4.6, kInf, 1, &h));
    EXPECT_NEAR(h.t, 5.2, 1e-12);
    expect_vec(h.normal, {-1, 0, 0});
    EXPECT_NEAR(h.uv.y, 0.75, 1e-12);  // the inside of the tube
}

TEST(AnalyticTorus, OnTheAxisAndThroughTheTube) {
    ref::ShapeHit h;
    // Down the axis: through the hole.
    EXPECT_FALSE(ref::intersect_torus({0, 5, 0}, {0, -1, 0}, 0, kInf, 1, &h));
    EXPECT_FALSE(ref::intersect_torus({0, -5, 0}, {0, 1, 0}, 0, kInf, 1, &h));
    // Along the axis, but off it by less than R − r = 0.2: still the hole.
    EXPECT_FALSE(ref::intersect_torus({0.19, 5, 0}, {0, -1, 0}, 0, kInf, 1, &h));
    // Down through the tube's centre circle: the top of the tube, v = 0.
    ASSERT_TRUE(ref::intersect_torus({0, 5, 0.35}, {0, -1, 0}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 4.85, 1e-12);
    expect_vec(h.normal, {0, 1, 0});
    EXPECT_NEAR(h.uv.y, 0.0, 1e-9);
}

TEST(AnalyticTorus, GrazingRays) {
    ref::ShapeHit h;
    // Just under the top of the tube: x = −0.35 − √(0.15² − 0.1499²).
    ASSERT_TRUE(ref::intersect_torus({-5, 0.1499, 0}, {1, 0, 0}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 5.0 - 0.35 - std::sqrt(0.0225 - 0.1499 * 0.1499), 1e-10);
    EXPECT_FALSE(ref::intersect_torus({-5, 0.1501, 0}, {1, 0, 0}, 0, kInf, 1, &h));
    // Just inside the outer equator: z = −√(0.25 − 0.4999²).
    ASSERT_TRUE(ref::intersect_torus({0.4999, 0, -5}, {0, 0, 1}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 5.0 - std::sqrt(0.25 - 0.4999 * 0.4999), 1e-10);
    EXPECT_FALSE(ref::intersect_torus({0.5001, 0, -5}, {0, 0, 1}, 0, kInf, 1, &h));
    // Grazing the inner equator from the hole side: x = 0.1999 passes 6.3e−3 through the
    // hole, so the tube is left at z = −√(0.04 − x²) and entered again at z = +√(0.04 − x²).
    const double x = 0.1999, gap = std::sqrt(0.04 - x * x);
    ASSERT_TRUE(ref::intersect_torus({x, 0, -5}, {0, 0, 1}, 0, kInf, 1, &h));
    EXPECT_NEAR(h.t, 5.0 - std::sqrt(0.25 - x * x), 1e-10);
    ASSERT_TRUE(ref::intersect_torus({x, 0, -5}, {0, 0, 1}, 4.9, kInf, 1, &h));
    EXPECT_NEAR(h.t, 5.0 + gap, 1e-9);
    expect_vec(h.normal, dvec3(-x, 0, -gap) / 0.2, 1e-7);  // pointing back into the hole
    // x = 0.2001 never reaches the hole: one chord, no second front face.
    EXPECT_FALSE(ref::intersect_torus({0.2001, 0, -5}, {0, 0, 1}, 4.9, kInf, 1, &h));
}

TEST(AnalyticTorus, AgreesWithMarchingOnRandomRays) {
    // The nearest front hit must lie on the surface, and a fine march along the ray must
    // not find the inside of the torus before it.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    auto inside = [](const dvec3& p) {
        const double rho = std::hypot(p.x, p.z);
        return (rho - 0.35) * (rho - 0.35) + p.y * p.y < 0.15 * 0.15;
    };
    int hits = 0;
    for (int i = 0; i < 400; ++i) {
        const dvec3 o = 3.0 * glm::normalize(dvec3(u(rng), u(rng), u(rng)));
        const dvec3 target(0.5 * u(rng), 0.2 * u(rng), 0.5 * u(rng));
        const dvec3 d = target - o;
        ref::ShapeHit h;
        if (!ref::intersect_torus(o, d, 0, kInf, 1, &h)) {
            for (int k = 0; k <= 4000; ++k) ASSERT_FALSE(inside(o + (k / 2000.0) * d)) << "missed ray " << i;
            continue;
        }
        ++hits;
        const dvec3 p = o + h.t * d;
        const double rho = std::hypot(p.x, p.z);
        EXPECT_NEAR((rho - 0.35) * (rho - 0.35) + p.y * p.y, 0.0225, 1e-10);
        for (int k = 0; k < 2000; ++k) {
            const double t = h.t * k / 2000.0;
            ASSERT_FALSE(inside(o + t * d)) << "ray " << i << " enters the torus at t = " << t << " < " << h.t;
        }
    }
    EXPECT_GT(hits, 100);
}

// --- the ideal scene ----------------------------------------------------------------

namespace {
lab::Scene one_object_scene(const std::string& mesh, glm::vec3 scale) {
    lab::Scene s;
    s.camera.position = {0, 0, 5};
    s.camera.target = {0, 0, 0};
    s.materials["m"] = lab::MaterialDesc{};
    lab::ObjectDesc o;
    o.mesh = mesh;
    o.material = "m";
    o.scale = scale;
    s.objects.push_back(o);
    return s;
}
}  // namespace

TEST(IdealGeometry, ModelMatrixKeepsTheDepth) {
    const lab::Scene s = one_object_scene("sphere", {2, 2, 2});
    const ref::IdealGeometry g(s);
    const ref::Camera cam = ref::make_camera(s.camera);
    const ref::Ray ray = ref::primary_ray(cam, 2, 2, 1.0, 1.0);  // through the image centre
    ref::Hit hit;
    ASSERT_TRUE(g.trace(ray, 0.01, 100, &hit));
    EXPECT_TRUE(hit.analytic);
    EXPECT_NEAR(hit.depth, 4.0, 1e-12);  // radius 0.5 · 2
    expect_vec(hit.normal, {0, 0, 1});
    // Squashed in z: the hit moves, the normal stays along z.
    const lab::Scene flat = one_object_scene("sphere", {1, 1, 0.5});
    const ref::IdealGeometry g2(flat);
    ASSERT_TRUE(g2.trace(ray, 0.01, 100, &hit));
    EXPECT_NEAR(hit.depth, 4.75, 1e-12);
    expect_vec(hit.normal, {0, 0, 1});
}

TEST(IdealGeometry, MirroredObjectShowsItsInsideLikeTheRasteriser) {
    // A negative scale flips the triangles' winding: back-face culling then keeps the
    // far, inner side. The ideal shape does the same.
    const lab::Scene s = one_object_scene("sphere", {-1, 1, 1});
    const ref::IdealGeometry ideal(s);
    const ref::SceneGeometry triangles(s);
    const ref::Ray ray = ref::primary_ray(ref::make_camera(s.camera), 2, 2, 1.0, 1.0);
    ref::Hit a, b;
    ASSERT_TRUE(ideal.trace(ray, 0.01, 100, &a));
    ASSERT_TRUE(triangles.trace(ray, 0.01, 100, &b));
    EXPECT_NEAR(a.depth, 5.5, 1e-12);
    EXPECT_NEAR(b.depth, 5.5, 1e-6);
}

TEST(IdealGeometry, MixesShapesAndTriangles) {
    lab::Scene s = one_object_scene("cube", {1, 1, 1});  // object 0: triangles, front at z = 0.5
    lab::ObjectDesc torus = s.objects[0];
    torus.mesh = "torus";
    torus.position = {0, 0, 1};  // object 1: in front of the cube, the ray goes through its hole
    torus.rotation_deg = {90, 0, 0};
    s.objects.push_back(torus);
    const ref::IdealGeometry g(s);
    const ref::Camera cam = ref::make_camera(s.camera);
    ref::Hit hit;
    ASSERT_TRUE(g.trace(ref::primary_ray(cam, 2, 2, 1.0, 1.0), 0.01, 100, &hit));
    EXPECT_EQ(hit.object_id, 0);
    EXPECT_FALSE(hit.analytic);
    EXPECT_NEAR(hit.depth, 4.5, 1e-9);
    // A ray through the tube (x = 0.35 at z = 1: the camera ray aimed at (0.35, 0, 1)).
    ref::Ray ray;
    ray.origin = {0, 0, 5};
    ray.dir = {0.35 / 4.0, 0, -1};
    ASSERT_TRUE(g.trace(ray, 0.01, 100, &hit));
    EXPECT_EQ(hit.object_id, 1);
    EXPECT_TRUE(hit.analytic);
    // It meets the tube's front (z = 1 + 0.15 along the ray's line near x = 0.35 − …):
    // the point lies on the torus and in front of its centre plane.
    const dvec3 p = hit.position - dvec3(0, 0, 1);
    const double rho = std::hypot(p.x, p.y);  // rotated 90° about X: the torus lies in XY
    EXPECT_NEAR((rho - 0.35) * (rho - 0.35) + p.z * p.z, 0.0225, 1e-10);
    EXPECT_GT(p.z, 0.0);
}

TEST(IdealGeometry, FineTessellationConvergesToTheIdealSilhouettes) {
    // Every curved primitive at 256 segments against its exact shape: the object
    // seen at each pixel may differ only along silhouettes (a ring of ≲ 1 pixel).
    lab::Scene s = lab::load_scene(std::string(LAB_SOURCE_DIR) + "/tests/scenes/lab1_all_primitives.json");
    for (lab::ObjectDesc& o : s.objects) {
        if (o.mesh == "icosphere") o.segments = 6;
        else if (o.mesh == "sphere" || o.mesh == "torus") o.segments = 256, o.rings = 128;
        else if (o.mesh == "cylinder" || o.mesh == "cone") o.segments = 256, o.rings = 1;
    }
    const int w = 200, h = 120;
    const ref::RefImage tess = ref::render_reference(s, w, h);
    const ref::IdealGeometry ideal(s);
    const ref::RefImage exact = ref::render_with(s, w, h, ref::shade_unlit, ideal.tracer());
    size_t differ = 0, covered = 0;
    for (size_t i = 0; i < tess.object_id.size(); ++i) {
        differ += tess.object_id[i] != exact.object_id[i];
        covered += exact.object_id[i] > 0;  // not the floor or the background
    }
    EXPECT_GT(covered, size_t(w * h / 10));
    EXPECT_LT(differ, size_t(w * h / 500)) << differ << " pixels see another object";
    // And a coarse tessellation is visibly different (the test can fail).
    for (lab::ObjectDesc& o : s.objects)
        if (o.mesh == "sphere" || o.mesh == "torus" || o.mesh == "cylinder" || o.mesh == "cone")
            o.segments = 6, o.rings = 3;
    const ref::RefImage coarse = ref::render_reference(s, w, h);
    size_t coarse_differ = 0;
    for (size_t i = 0; i < coarse.object_id.size(); ++i) coarse_differ += coarse.object_id[i] != exact.object_id[i];
    EXPECT_GT(coarse_differ, 5 * differ + 50);
}

TEST(IdealGeometry, SupersamplingAveragesCoverage) {
    // A sphere edge-on at a pixel: 4×4 samples give a mix of object and background.
    lab::Scene s = one_object_scene("sphere", {1, 1, 1});
    s.background = {0, 0, 0};
    s.materials["m"].albedo = {1, 1, 1};
    const ref::IdealGeometry g(s);
    const ref::RefImage one = ref::render_with(s, 32, 32, ref::shade_unlit, g.tracer(), 1);
    const ref::RefImage four = ref::render_with(s, 32, 32, ref::shade_unlit, g.tracer(), 4);
    double sum_one = 0, sum_four = 0;
    int partial = 0;
    for (size_t i = 0; i < one.linear.size(); ++i) {
        sum_one += one.linear[i].x;
        sum_four += four.linear[i].x;
        partial += four.linear[i].x > 0.0 && four.linear[i].x < 1.0;
        EXPECT_TRUE(four.linear[i].x == 0.0 || four.linear[i].x == 1.0 || (four.linear[i].x * 16.0) == std::round(four.linear[i].x * 16.0));
    }
    EXPECT_GT(partial, 10);  // the rim: about 2π · 2.8 pixels
    // Covered area: π·0.5² over the image plane's area at depth 5 (2·5·tan 30°)²:
    // 0.7854 / 33.33 · 1024 pixels ≈ 24.1 pixels; 16 samples a pixel estimate it closely.
    const double plane = 2.0 * 5.0 * std::tan(30.0 * 3.14159265358979323846 / 180.0);
    const double expected = 3.14159265358979323846 * 0.25 / (plane * plane) * 1024.0;
    EXPECT_NEAR(sum_four, expected, 1.0);
    EXPECT_NEAR(sum_one, expected, 6.0);
}

// --- error figures ------------------------------------------------------------------

TEST(ErrorFigures, Ciede2000MatchesSharmasTable) {
    // Sharma, Wu & Dalal (2005), test pairs 1–3 and 7.
    EXPECT_NEAR(ref::ciede2000({50, 2.6772, -79.7751}, {50, 0, -82.7485}), 2.0425, 1e-4);
    EXPECT_NEAR(ref::ciede2000({50, 3.1571, -77.2803}, {50, 0, -82.7485}), 2.8615, 1e-4);
    EXPECT_NEAR(ref::ciede2000({50, 2.8361, -74.0200}, {50, 0, -82.7485}), 3.4412, 1e-4);
    EXPECT_NEAR(ref::ciede2000({50, 0, 0}, {50, -1, 2}), 2.3669, 1e-4);
    EXPECT_EQ(ref::ciede2000({30, 10, -5}, {30, 10, -5}), 0.0);
}

TEST(ErrorFigures, SrgbToLab) {
    const uint8_t white[3] = {255, 255, 255}, black[3] = {0, 0, 0}, red[3] = {255, 0, 0};
    expect_vec(ref::srgb8_to_lab(white), {100, 0, 0}, 2e-3);
    expect_vec(ref::srgb8_to_lab(black), {0, 0, 0}, 1e-9);
    expect_vec(ref::srgb8_to_lab(red), {53.24, 80.09, 67.20}, 0.02);  // the usual sRGB red
}

TEST(ErrorFigures, StatsByHand) {
    // Four pixels: equal, 1 off, 3 off (green), 10 off (blue).
    lab::Image8 a{4, 1, std::vector<uint8_t>(16, 100)}, b = a;
    b.rgba[4] = 101;
    b.rgba[9] = 97;
    b.rgba[14] = 110;
    const ref::ErrorStats s = ref::error_stats(a, b);
    EXPECT_EQ(s.pixels, 4u);
    EXPECT_DOUBLE_EQ(s.mean_abs, (0 + 1 + 3 + 10) / 4.0);
    EXPECT_EQ(s.max_abs, 10);
    EXPECT_DOUBLE_EQ(s.p99_abs, 10.0);
    EXPECT_DOUBLE_EQ(s.share_over_2, 0.5);
    EXPECT_GT(s.mean_de, 0.0);
    // Masking the worst pixel.
    const ref::ErrorStats m = ref::error_stats(a, b, {0, 0, 0, 1});
    EXPECT_EQ(m.masked, 1u);
    EXPECT_EQ(m.max_abs, 3);
    EXPECT_DOUBLE_EQ(m.mean_abs, 4.0 / 3.0);
    EXPECT_THROW(ref::error_stats(a, lab::Image8{2, 1, std::vector<uint8_t>(8, 0)}), std::invalid_argument);
}

TEST(ErrorFigures, ColourEdgeMask) {
    // A 5×5 image, black with a white right half from column 3: columns 2…4 touch the edge.
    lab::Image8 img{5, 5, std::vector<uint8_t>(100, 0)};
    for (int y = 0; y < 5; ++y)
        for (int x = 3; x < 5; ++x)
            for (int c = 0; c < 3; ++c) img.rgba[(y * 5 + x) * 4 + c] = 255;
    const std::vector<uint8_t> m = ref::colour_edge_mask(img);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 5; ++x) EXPECT_EQ(m[y * 5 + x], (x == 2 || x == 3) ? 1 : 0) << x << "," << y;
}

// --- the commands -------------------------------------------------------------------

namespace {
const std::string kTools = std::string(LAB_BINARY_DIR) + "/tests";
const std::string kOut = std::string(LAB_BINARY_DIR) + "/test_output/tools";
}  // namespace

TEST(ReferenceTool, IdealRenderAndCompare) {
    const std::string scene = std::string(LAB_SOURCE_DIR) + "/tests/scenes/lab1_all_primitives.json";
    const std::string ideal = kOut + "/ideal.png", tess = kOut + "/tess.png", heat = kOut + "/heat.png";
    std::filesystem::create_directories(kOut);
    const std::string common = "--lab lab1_camera --scene " + quoted(scene) + " --width 160 --height 90 ";
    RunResult r = run_lab(kTools + "/lab_reference", common + "--ideal --out " + quoted(ideal), kOut + "/ref1.log");
    ASSERT_EQ(r.exit_code, 0) << r.log;
    r = run_lab(kTools + "/lab_reference", common + "--out " + quoted(tess), kOut + "/ref2.log");
    ASSERT_EQ(r.exit_code, 0) << r.log;
    // The same picture against itself: all zero.
    r = run_lab(kTools + "/lab_compare", quoted(ideal) + " " + quoted(ideal), kOut + "/cmp0.log");
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_NE(r.log.find("mean_abs=0.0000 p99_abs=0.0 max_abs=0 over_2=0.0000% mean_de2000=0.0000"),
              std::string::npos)
        << r.log;
    // The scene's coarse meshes (a 12×6 sphere, a 7-sided cylinder, a 9×5 torus) differ.
    r = run_lab(kTools + "/lab_compare", quoted(ideal) + " " + quoted(tess) + " --heatmap " + quoted(heat),
                kOut + "/cmp1.log");
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.log.find("max_abs=0 "), std::string::npos) << r.log;
    EXPECT_TRUE(std::filesystem::exists(heat));
    // The error is at the silhouettes: masking the edges removes most of it.
    r = run_lab(kTools + "/lab_compare", quoted(ideal) + " " + quoted(tess) + " --mask edges", kOut + "/cmp2.log");
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.log.find("masked=0\n"), std::string::npos) << r.log;
}

TEST(ReferenceTool, BadInputIsOneLineAndExitCode2) {
    std::filesystem::create_directories(kOut);
    const std::string scene = std::string(LAB_SOURCE_DIR) + "/tests/scenes/lab1_invalid.json";
    const std::string out = kOut + "/never.png";
    std::filesystem::remove(out);
    RunResult r = run_lab(kTools + "/lab_reference",
                          "--lab lab1_camera --scene " + quoted(scene) + " --width 8 --height 8 --out " + quoted(out),
                          kOut + "/bad1.log");
    EXPECT_EQ(r.exit_code, 2) << r.log;
    EXPECT_NE(r.log.find("lab1_invalid.json"), std::string::npos) << r.log;
    EXPECT_FALSE(std::filesystem::exists(out));
    r = run_lab(kTools + "/lab_reference", "--lab lab9 --scene x --width 8 --height 8 --out y", kOut + "/bad2.log");
    EXPECT_EQ(r.exit_code, 2) << r.log;
    EXPECT_NE(r.log.find("unknown lab 'lab9'"), std::string::npos) << r.log;
    // Lab 3's truth is the supersampled texture (--supersample N), not exact shapes.
    r = run_lab(kTools + "/lab_reference", "--lab lab3_textures --scene x --width 8 --height 8 --ideal --out y",
                kOut + "/bad4.log");
    EXPECT_EQ(r.exit_code, 2) << r.log;
    EXPECT_NE(r.log.find("--ideal: not available for lab3_textures"), std::string::npos) << r.log;
    r = run_lab(kTools + "/lab_compare", quoted(kOut + "/missing.png") + " " + quoted(kOut + "/missing.png"),
                kOut + "/bad3.log");
    EXPECT_EQ(r.exit_code, 2) << r.log;
    EXPECT_NE(r.log.find("missing.png"), std::string::npos) << r.log;
}
