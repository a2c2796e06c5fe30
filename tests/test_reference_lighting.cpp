// test_reference_lighting.cpp — the oracle's lighting (tests/reference/cpu_lighting.*) against hand
// calculation: attenuation, the spot cone (both falloffs, hard edges), the normal matrix under
// non-uniform scale, the Blinn-Phong equation at a point, the stress-case rules of docs/lighting.md.
// The instructors' check of the reference; a student copy holds the reference prebuilt and leaves
// this file out (its hand calculations are lab 2's answers; docs/solutions.md).
#include "reference/cpu_lighting.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace {

constexpr double kPi = 3.14159265358979323846;
double cos_deg(double d) { return std::cos(d * kPi / 180.0); }
using Falloff = lab::LightingDesc::SpotFalloff;

// --- attenuation ---

TEST(Attenuation, HandCalculated) {
    // 1 / (1 + 0.09·2 + 0.032·4) = 1 / 1.308
    EXPECT_NEAR(ref::attenuation({1.0, 0.09, 0.032}, 2.0), 1.0 / 1.308, 1e-12);
    EXPECT_DOUBLE_EQ(ref::attenuation({1.0, 0.0, 0.0}, 123.0), 1.0);      // constant only
    EXPECT_DOUBLE_EQ(ref::attenuation({0.0, 0.0, 1.0}, 4.0), 1.0 / 16.0);  // inverse square
    EXPECT_DOUBLE_EQ(ref::attenuation({2.0, 0.0, 0.0}, 0.0), 0.5);         // d = 0: 1 / c
}

TEST(Attenuation, ZeroCoefficientsMeanNoFalloff) {
    EXPECT_DOUBLE_EQ(ref::attenuation({0.0, 0.0, 0.0}, 0.0), 1.0);
    EXPECT_DOUBLE_EQ(ref::attenuation({0.0, 0.0, 0.0}, 1e6), 1.0);
}

TEST(Attenuation, DenominatorIsClampedNotDividedByZero) {
    // A light exactly on the surface with no constant term: 1 / max(0, 1e-6) = 1e6, finite.
    EXPECT_DOUBLE_EQ(ref::attenuation({0.0, 1.0, 1.0}, 0.0), 1e6);
    EXPECT_DOUBLE_EQ(ref::attenuation({0.0, 0.0, 1.0}, 1e-4), 1e6);  // 1e-8 < 1e-6
    EXPECT_TRUE(std::isfinite(ref::attenuation({0.0, 0.0, 1e6}, 1e6)));
}

// --- spot cone ---

TEST(SpotFactor, SmoothRampHandCalculated) {
    // inner 10°, outer 20°: full inside 10°, zero beyond 20°, linear in cosθ between.
    EXPECT_DOUBLE_EQ(ref::spot_factor(10, 20, Falloff::Smooth, 1.0), 1.0);
    EXPECT_DOUBLE_EQ(ref::spot_factor(10, 20, Falloff::Smooth, cos_deg(10)), 1.0);
    EXPECT_DOUBLE_EQ(ref::spot_factor(10, 20, Falloff::Smooth, cos_deg(20)), 0.0);
    EXPECT_DOUBLE_EQ(ref::spot_factor(10, 20, Falloff::Smooth, cos_deg(25)), 0.0);
    const double mid = 0.5 * (cos_deg(10) + cos_deg(20));
    EXPECT_NEAR(ref::spot_factor(10, 20, Falloff::Smooth, mid), 0.5, 1e-12);
    // 15°: (cos15 − cos20) / (cos10 − cos20) = (0.9659258 − 0.9396926) / (0.9848078 − 0.9396926)
    EXPECT_NEAR(ref::spot_factor(10, 20, Falloff::Smooth, cos_deg(15)), 0.0262332 / 0.0451152, 1e-5);
}

TEST(SpotFactor, EqualAnglesGiveAHardEdge) {
    EXPECT_DOUBLE_EQ(ref::spot_factor(25, 25, Falloff::Smooth, cos_deg(24.999)), 1.0);
    EXPECT_DOUBLE_EQ(ref::spot_factor(25, 25, Falloff::Smooth, cos_deg(25)), 1.0);  // on the edge: lit
    EXPECT_DOUBLE_EQ(ref::spot_factor(25, 25, Falloff::Smooth, cos_deg(25.001)), 0.0);
    // A zero cone lights only its axis.
    EXPECT_DOUBLE_EQ(ref::spot_factor(0, 0, Falloff::Smooth, 1.0), 1.0);
    EXPECT_DOUBLE_EQ(ref::spot_factor(0, 0, Falloff::Smooth, cos_deg(0.01)), 0.0);
    EXPECT_DOUBLE_EQ(ref::spot_factor(0, 0, Falloff::Edge, 1.0), 1.0);
}

TEST(SpotFactor, EdgeFalloffFromTheSeeds) {
    // X = 1 − (1 − cosβ) / (1 − cosα), α = outer = 30°; inner is ignored.
    for (double beta : {0.0, 5.0, 10.0, 20.0, 29.0}) {
        const double expected = 1.0 - (1.0 - cos_deg(beta)) / (1.0 - cos_deg(30));
        EXPECT_NEAR(ref::spot_factor(12, 30, Falloff::Edge, cos_deg(beta)), expected, 1e-12) << beta;
    }
    EXPECT_DOUBLE_EQ(ref::spot_factor(12, 30, Falloff::Edge, cos_deg(31)), 0.0);
}

// --- normal matrix ---

TEST(NormalMatrix, NonUniformScaleKeepsNormalsPerpendicular) {
    // S = diag(2, 1, 1): the plane x + y = 0 has normal (1, 1, 0)/√2. After scaling, its
    // points (t, −t, z) become (2t, −t, z): the plane x + 2y = 0, normal (1, 2, 0)/√5.
    // Inverse transpose: diag(1/2, 1, 1)·(1, 1, 0) = (0.5, 1, 0) ∥ (1, 2, 0). The model
    // matrix itself would give (2, 1, 0): wrong.
    const glm::dmat4 model = glm::scale(glm::dmat4(1.0), glm::dvec3(2.0, 1.0, 1.0));
    const glm::dvec3 n = glm::normalize(ref::normal_matrix(model) * glm::dvec3(1.0, 1.0, 0.0));
    EXPECT_NEAR(n.x, 1.0 / std::sqrt(5.0), 1e-12);
    EXPECT_NEAR(n.y, 2.0 / std::sqrt(5.0), 1e-12);
    EXPECT_NEAR(n.z, 0.0, 1e-12);
    // Perpendicular to the transformed tangent (1, −1, 0) → (2, −1, 0).
    EXPECT_NEAR(glm::dot(n, glm::dvec3(model * glm::dvec4(1, -1, 0, 0))), 0.0, 1e-12);
}

TEST(NormalMatrix, RotationIsItsOwnNormalMatrix) {
    const glm::dmat4 r = glm::rotate(glm::dmat4(1.0), 0.7, glm::normalize(glm::dvec3(1, 2, 3)));
    const glm::dmat3 n = ref::normal_matrix(r);
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(n[c][k], r[c][k], 1e-12);
}

TEST(NormalMatrix, RotatedNonUniformScaleAgainstHand) {
    // M = Rz(90°)·S(1, 3, 1). A normal (0, 1, 0) of the unscaled y = const plane stays the
    // plane's normal: scaled along y it is still y = const, then Rz(90°) turns +Y into −X.
    lab::ObjectDesc object;
    object.mesh = "cube";
    object.rotation_deg = {0, 0, 90};
    object.scale = {1, 3, 1};
    const glm::dvec3 n = glm::normalize(ref::normal_matrix(ref::model_matrix(object)) * glm::dvec3(0, 1, 0));
    EXPECT_NEAR(n.x, -1.0, 1e-12);
    EXPECT_NEAR(n.y, 0.0, 1e-12);
    // A 45° normal (1, 1, 0): inverse transpose gives (1, 1/3, 0), then rotated: (−1/3, 1, 0).
    const glm::dvec3 m = glm::normalize(ref::normal_matrix(ref::model_matrix(object)) * glm::dvec3(1, 1, 0));
    const glm::dvec3 expected = glm::normalize(glm::dvec3(-1.0 / 3.0, 1.0, 0.0));
    EXPECT_NEAR(glm::distance(m, expected), 0.0, 1e-12);
}

// --- the equation at a point ---

lab::Scene one_light_scene(const lab::LightDesc& light) {
    lab::Scene s;
    s.ambient.color = glm::vec3(1.0f);
    s.ambient.intensity = 0.1f;
    s.lights = {light};
    return s;
}

TEST(ShadePoint, BlinnPhongHandCalculated) {
    // N = +Y, light from straight above (L = N), eye at 45°: H = normalize(L + V).
    lab::LightDesc sun;
    sun.type = lab::LightDesc::Type::Directional;
    sun.direction = {0, -1, 0};
    sun.color = glm::vec3(1.0f);
    sun.intensity = 2.0f;
    const lab::Scene scene = one_light_scene(sun);
    lab::MaterialDesc m;
    m.albedo = glm::vec3(0.5f);
    m.specular = glm::vec3(0.25f);
    m.shininess = 4.0f;
    m.emissive = glm::vec3(0.01f, 0.0f, 0.0f);
    const glm::dvec3 N(0, 1, 0), V = glm::normalize(glm::dvec3(1, 1, 0));
    // N·H = cos 22.5°; spec = cos⁴(22.5°) = ((1 + cos45°)/2)² = 0.7286...
    const double spec = std::pow((1.0 + std::sqrt(0.5)) / 2.0, 2.0);
    const double expected = 0.1 * 0.5 + 2.0 * (0.5 * 1.0 + 0.25 * spec);
    const glm::dvec3 c = ref::shade_point(scene, m, glm::dvec3(0.0), N, V, glm::dvec3(1, 0, 0));
    EXPECT_NEAR(c.r, expected + double(0.01f), 1e-7);
    EXPECT_NEAR(c.g, expected, 1e-7);
}

TEST(ShadePoint, PointLightAttenuatedAndSpotCut) {
    lab::LightDesc bulb;
    bulb.type = lab::LightDesc::Type::Point;
    bulb.position = {0, 2, 0};
    bulb.attenuation = {1, 0.5, 0.25};  // d = 2: 1 / (1 + 1 + 1) = 1/3
    lab::Scene scene = one_light_scene(bulb);
    scene.ambient.intensity = 0.0f;
    lab::MaterialDesc m;
    m.albedo = glm::vec3(0.9f);
    const glm::dvec3 N(0, 1, 0), V(0, 1, 0);
    EXPECT_NEAR(ref::shade_point(scene, m, glm::dvec3(0.0), N, V, {}).g, double(0.9f) / 3.0, 1e-7);
    // The same as a spot aimed 30° away from the point with a 20° cone: nothing.
    scene.lights[0].type = lab::LightDesc::Type::Spot;
    scene.lights[0].direction = glm::vec3(std::sin(kPi / 6), -std::cos(kPi / 6), 0.0);
    scene.lights[0].inner_deg = 10.0f;
    scene.lights[0].outer_deg = 20.0f;
    EXPECT_EQ(ref::shade_point(scene, m, glm::dvec3(0.0), N, V, {}).g, 0.0);
}

TEST(ShadePoint, StressCasesStayFinite) {
    using Model = lab::LightingDesc::Model;
    lab::LightDesc on_surface;
    on_surface.type = lab::LightDesc::Type::Point;
    on_surface.position = {0, 0, 0};  // d = 0
    on_surface.attenuation = {0, 0, 1};
    on_surface.intensity = 1e6f;
    lab::Scene scene = one_light_scene(on_surface);
    lab::MaterialDesc m;
    m.specular = glm::vec3(1.0f);
    for (float shininess : {0.0f, 1.0f, 10000.0f})
        for (int model = 0; model <= int(Model::Ward); ++model) {
            scene.lighting.model = Model(model);
            m.shininess = shininess;
            m.roughness = 0.0f;
            m.minnaert_k = 0.0f;
            bool bad = false;
            // V = −N (the eye below the surface) and a tangent parallel to N are allowed too.
            for (const glm::dvec3& V : {glm::dvec3(0, 1, 0), glm::dvec3(0, -1, 0), glm::dvec3(1, 0, 0)}) {
                const glm::dvec3 c = ref::shade_point(scene, m, glm::dvec3(0.0), glm::dvec3(0, 1, 0), V,
                                                      glm::dvec3(0, 1, 0), &bad);
                EXPECT_FALSE(bad) << "model " << model << " shininess " << shininess;
                EXPECT_TRUE(std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b));
            }
        }
    // The light on the surface lights it fully (L = N): albedo · 1e6 / 1e-6-clamped denominator.
    scene.lighting.model = Model::Lambert;
    m.albedo = glm::vec3(0.5f);
    scene.ambient.intensity = 0.0f;
    EXPECT_NEAR(ref::shade_point(scene, m, glm::dvec3(0.0), glm::dvec3(0, 1, 0), glm::dvec3(0, 1, 0), {}).r,
                0.5 * 1e6 * 1e6, 1.0);
}

TEST(ShadePoint, ShininessZeroIsAFullHighlightWhereLit) {
    // pow(x, 0) = 1 even for x = 0: GLSL leaves pow(0, 0) undefined, the lab defines it.
    lab::LightDesc sun;
    sun.type = lab::LightDesc::Type::Directional;
    sun.direction = {-1, -1, 0};  // L = (1, 1, 0)/√2
    lab::Scene scene = one_light_scene(sun);
    scene.ambient.intensity = 0.0f;
    lab::MaterialDesc m;
    m.albedo = glm::vec3(0.0f);
    m.specular = glm::vec3(0.5f);
    m.shininess = 0.0f;
    // Any view direction: the highlight term is 1 wherever N·L > 0.
    const glm::dvec3 N(0, 1, 0);
    EXPECT_NEAR(ref::shade_point(scene, m, glm::dvec3(0.0), N, glm::dvec3(-1, 0, 0), {}).r, 0.5, 1e-12);
    sun.direction = {0, 1, 0};  // from below: N·L < 0, no highlight at all
    scene.lights = {sun};
    EXPECT_EQ(ref::shade_point(scene, m, glm::dvec3(0.0), N, glm::dvec3(0, 1, 0), {}).r, 0.0);
}

}  // namespace
