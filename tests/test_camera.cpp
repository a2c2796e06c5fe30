// Camera math of lab 1 against hand-computed matrices, degenerate inputs and
// the mode-switch round trip. Expected values are worked out by hand in the
// comments (see docs/conventions.md for the conventions).
#include "camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

constexpr double kEps = 1e-12;

// Camera-space coordinates of a world point.
glm::dvec3 to_camera(const Camera& c, const glm::dvec3& p) { return glm::dvec3(c.view() * glm::dvec4(p, 1.0)); }

void expect_vec(const glm::dvec3& got, const glm::dvec3& want, double eps = 1e-9) {
    EXPECT_NEAR(got.x, want.x, eps);
    EXPECT_NEAR(got.y, want.y, eps);
    EXPECT_NEAR(got.z, want.z, eps);
}

void expect_mat(const glm::dmat4& got, const glm::dmat4& want, double eps) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(got[c][r], want[c][r], eps) << "element [" << c << "][" << r << "]";
}

// The 3×3 part of a view matrix must be a rotation: orthonormal columns, det +1, all finite.
void expect_rigid(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) ASSERT_TRUE(std::isfinite(m[c][r]));
    const glm::dmat3 r(m);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(glm::length(r[i]), 1.0, 1e-9);
        for (int j = i + 1; j < 3; ++j) EXPECT_NEAR(glm::dot(r[i], r[j]), 0.0, 1e-9);
    }
    EXPECT_NEAR(glm::determinant(r), 1.0, 1e-9);
}

Camera look_at(glm::dvec3 eye, glm::dvec3 target, glm::dvec3 up = {0, 1, 0}) {
    Camera c;
    c.mode = Camera::Mode::LookAt;
    c.eye = eye;
    c.target = target;
    c.up = up;
    return c;
}

Camera transform(glm::dvec3 position, double yaw, double pitch, double roll) {
    Camera c;
    c.mode = Camera::Mode::Transform;
    c.position = position;
    c.yaw_deg = yaw;
    c.pitch_deg = pitch;
    c.roll_deg = roll;
    return c;
}

// ------------------------------------------------------------------ Look-At

TEST(LookAt, DownMinusZIsATranslation) {
    // eye (0,0,5) looking at the origin with up +Y: the camera axes are the
    // world axes, so view = T(0,0,−5).
    glm::dmat4 want(1.0);
    want[3] = glm::dvec4(0, 0, -5, 1);
    expect_mat(look_at({0, 0, 5}, {0, 0, 0}).view(), want, kEps);
}

TEST(LookAt, LookingAlongPlusX) {
    // f = +X, r = f × up = X × Y = +Z, u = r × f = Z × X = +Y.
    // World (2,0,1) → camera (r·p, u·p, −f·p) = (1, 0, −2).
    const Camera c = look_at({0, 0, 0}, {1, 0, 0});
    expect_vec(to_camera(c, {2, 0, 1}), {1, 0, -2});
    expect_vec(c.forward(), {1, 0, 0});
    expect_vec(c.right(), {0, 0, 1});
}

TEST(LookAt, TargetLandsOnTheMinusZAxisAtItsDistance) {
    const Camera c = look_at({3, 4, 5}, {-1, 2, 0.5});
    const double d = glm::length(glm::dvec3(3, 4, 5) - glm::dvec3(-1, 2, 0.5));
    expect_vec(to_camera(c, c.target), {0, 0, -d});
    expect_rigid(c.view());
}

TEST(LookAt, TopDownViewFallsBackToMinusZUp) {
    // Looking straight down with up = +Y: documented fallback up' = −Z, so the
    // image's top points to world −Z and right is +X.
    const Camera c = look_at({0, 5, 0}, {0, 0, 0});
    expect_rigid(c.view());
    expect_vec(c.forward(), {0, -1, 0});
    expect_vec(c.right(), {1, 0, 0});
    expect_vec(glm::dvec3(c.camera_to_world()[1]), {0, 0, -1});
    // A point at world −Z is above the centre of the image (camera +Y).
    EXPECT_GT(to_camera(c, {0, 0, -1}).y, 0.0);
}

TEST(LookAt, BottomUpViewFallsBackToPlusZUp) {
    const Camera c = look_at({0, -5, 0}, {0, 0, 0});
    expect_rigid(c.view());
    expect_vec(glm::dvec3(c.camera_to_world()[1]), {0, 0, 1});
}

TEST(LookAt, UpAlongZAndViewAlongZUsesX) {
    const Camera c = look_at({0, 0, 5}, {0, 0, 0}, {0, 0, 1});
    expect_rigid(c.view());
    expect_vec(c.forward(), {0, 0, -1});
}

TEST(LookAt, EyeEqualsTargetLooksDownMinusZ) {
    const Camera c = look_at({1, 2, 3}, {1, 2, 3});
    expect_rigid(c.view());
    expect_vec(c.forward(), {0, 0, -1});
    expect_vec(c.world_position(), {1, 2, 3});
}

TEST(LookAt, ZeroUpVectorStaysFinite) {
    const Camera c = look_at({0, 1, 5}, {0, 0, 0}, {0, 0, 0});
    expect_rigid(c.view());
}

TEST(LookAt, HugeAndTinyCoordinates) {
    for (double scale : {1e-9, 1e-4, 1.0, 1e4, 1e9}) {
        SCOPED_TRACE(scale);
        const glm::dvec3 eye = glm::dvec3(1, 2, 3) * scale;
        const glm::dvec3 target = eye + glm::dvec3(0, 0, -1) * scale;
        const Camera c = look_at(eye, target);
        expect_rigid(c.view());
        expect_vec(c.forward(), {0, 0, -1});
        const glm::dvec3 t = to_camera(c, target);
        EXPECT_NEAR(t.z / scale, -1.0, 1e-6);
        // The float matrix the GPU receives is finite too.
        const glm::mat4 f(c.view());
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) EXPECT_TRUE(std::isfinite(f[i][j]));
    }
    // Eye and target 1e-12 apart at 1e6: still a valid basis.
    expect_rigid(look_at({1e6, 1e6, 1e6}, {1e6 + 1e-6, 1e6, 1e6}).view());
}

// ---------------------------------------------------------------- Transform

TEST(Transform, ZeroAnglesLookDownMinusZ) {
    glm::dmat4 want(1.0);
    want[3] = glm::dvec4(-1, -2, -3, 1);
    const Camera c = transform({1, 2, 3}, 0, 0, 0);
    expect_mat(c.view(), want, kEps);
    expect_vec(c.forward(), {0, 0, -1});
}

TEST(Transform, Yaw90LooksDownMinusX) {
    // Ry(90°) maps −Z to −X (counter-clockwise about +Y seen from above).
    const Camera c = transform({0, 0, 0}, 90, 0, 0);
    expect_vec(c.forward(), {-1, 0, 0});
    expect_vec(to_camera(c, {-5, 0, 0}), {0, 0, -5});
    expect_vec(c.right(), {0, 0, -1});
}

TEST(Transform, PositivePitchLooksUp) {
    // Rx(θ)·(0,0,−1) = (0, sin θ, −cos θ).
    const Camera c = transform({0, 0, 0}, 0, 30, 0);
    expect_vec(c.forward(), {0, 0.5, -std::sqrt(3.0) / 2.0});
}

TEST(Transform, RollTurnsTheImage) {
    // Rz(90°): camera right (+X) becomes world +Y, camera up becomes world −X.
    const Camera c = transform({0, 0, 0}, 0, 0, 90);
    expect_vec(c.right(), {0, 1, 0});
    expect_vec(glm::dvec3(c.camera_to_world()[1]), {-1, 0, 0});
    expect_vec(c.forward(), {0, 0, -1});
}

TEST(Transform, RotationOrderIsYawPitchRoll) {
    // C = Ry(90)·Rx(30)·Rz(r): the forward axis ignores roll and is
    // Ry(90)·(0, ½, −√3/2) = (−√3/2, ½, 0).
    const Camera c = transform({0, 0, 0}, 90, 30, 45);
    expect_vec(c.forward(), {-std::sqrt(3.0) / 2.0, 0.5, 0.0});
    // The camera's right: Ry(90)·Rx(30)·Rz(45)·X = Ry(90)·Rx(30)·(c45, s45, 0)
    // = Ry(90)·(c45, s45·c30, s45·s30) = (s45·s30, s45·c30, −c45).
    const double s = std::sqrt(0.5);
    expect_vec(c.right(), {s * 0.5, s * std::sqrt(3.0) / 2.0, -s});
}

TEST(Transform, PitchAtPlusMinus90StaysRigid) {
    for (double pitch : {-90.0, 90.0}) {
        const Camera c = transform({1, 2, 3}, 37, pitch, -12);
        expect_rigid(c.view());
        expect_vec(c.forward(), {0, pitch > 0 ? 1.0 : -1.0, 0});
    }
}

TEST(Transform, HugePositions) {
    const Camera c = transform({1e9, -1e9, 1e9}, 10, 20, 30);
    expect_rigid(c.view());
    expect_vec(to_camera(c, c.position + c.forward() * 2.0), {0, 0, -2}, 1e-6);
}

// --------------------------------------------------------------- Projection

TEST(Projection, MatchesTheHandFormula) {
    Camera c;
    c.fov_y_deg = 90.0;
    c.near_plane = 0.5;
    c.far_plane = 10.0;
    const glm::dmat4 p = c.projection(2.0);
    // f = 1/tan(45°) = 1: x scale f/aspect = 0.5, y scale −f (Vulkan Y flip).
    EXPECT_NEAR(p[0][0], 0.5, kEps);
    EXPECT_NEAR(p[1][1], -1.0, kEps);
    // Depth: z = −near → 0, z = −far → 1 (w = −z).
    const auto depth = [&](double z) {
        const glm::dvec4 clip = p * glm::dvec4(0, 0, z, 1);
        return clip.z / clip.w;
    };
    EXPECT_NEAR(depth(-0.5), 0.0, kEps);
    EXPECT_NEAR(depth(-10.0), 1.0, kEps);
    // A point above the view axis has negative clip Y: it lands in the top half of the image.
    const glm::dvec4 up = p * glm::dvec4(0, 1, -2, 1);
    EXPECT_LT(up.y / up.w, 0.0);
}

// -------------------------------------------------------------- Mode switch

TEST(ModeSwitch, KeepsThePoseExactly) {
    std::mt19937 rng(1234);
    std::uniform_real_distribution<double> coord(-50.0, 50.0), angle(-180.0, 180.0), pitch(-90.0, 90.0);
    for (int trial = 0; trial < 200; ++trial) {
        Camera c = trial % 2 ? look_at({coord(rng), coord(rng), coord(rng)}, {coord(rng), coord(rng), coord(rng)})
                             : transform({coord(rng), coord(rng), coord(rng)}, angle(rng), pitch(rng), angle(rng));
        const glm::dmat4 original = c.view();
        for (int i = 0; i < 50; ++i) {  // many switches back and forth
            const glm::dmat4 before = c.view();
            c.set_mode(c.mode == Camera::Mode::LookAt ? Camera::Mode::Transform : Camera::Mode::LookAt);
            expect_mat(c.view(), before, 1e-9);
        }
        expect_mat(c.view(), original, 1e-8);
    }
}

TEST(ModeSwitch, DegeneratePosesSurvive) {
    std::vector<Camera> poses = {
        look_at({0, 5, 0}, {0, 0, 0}),          // top-down fallback
        look_at({1, 1, 1}, {1, 1, 1}),          // eye == target
        transform({0, 0, 0}, 30, 90, 10),        // gimbal lock
        transform({0, 0, 0}, -170, -90, 120),
        transform({1e6, 0, -1e6}, 179.9, 0, -179.9),
    };
    for (Camera& c : poses) {
        const glm::dmat4 original = c.view();
        // Relative tolerance: a translation of 1e6 carries ~1e-10 of double
        // rounding per switch; float (what the GPU gets) resolves only 6e-8 of it.
        double magnitude = 1.0;
        for (int i = 0; i < 4; ++i) magnitude = std::max(magnitude, std::abs(original[3][i]));
        for (int i = 0; i < 20; ++i) {
            c.set_mode(c.mode == Camera::Mode::LookAt ? Camera::Mode::Transform : Camera::Mode::LookAt);
            expect_rigid(c.view());
            expect_mat(c.view(), original, 1e-10 * magnitude);
        }
    }
}

TEST(ModeSwitch, LookAtKeepsItsTargetDistance) {
    Camera c = look_at({0, 0, 7}, {0, 0, 0});
    c.set_mode(Camera::Mode::Transform);
    c.set_mode(Camera::Mode::LookAt);
    EXPECT_NEAR(glm::length(c.eye - c.target), 7.0, 1e-12);
}

// ----------------------------------------------------------------- Controls

TEST(Controls, OrbitKeepsTheDistanceAndTarget) {
    Camera c = look_at({3, 2, 4}, {0.5, 0, 0});
    const double d = glm::length(c.eye - c.target);
    for (int i = 0; i < 100; ++i) {
        c.rotate(7.0, i % 2 ? 13.0 : -9.0);
        EXPECT_NEAR(glm::length(c.eye - c.target), d, 1e-9);
        expect_vec(to_camera(c, c.target), {0, 0, -d}, 1e-9);
    }
}

TEST(Controls, OrbitStopsShortOfThePoles) {
    Camera c = look_at({0, 0, 5}, {0, 0, 0});
    c.rotate(0.0, -500.0);  // try to go far over the top
    const double polar = std::acos(glm::dot(glm::normalize(c.eye - c.target), glm::dvec3(0, 1, 0)));
    EXPECT_NEAR(polar * 180.0 / 3.14159265358979323846, 1.0, 1e-9);
    expect_rigid(c.view());
}

TEST(Controls, ZoomIsExponentialAndClamped) {
    Camera c = look_at({0, 0, 10}, {0, 0, 0});
    c.zoom(1.0);
    EXPECT_NEAR(glm::length(c.eye - c.target), 9.0, 1e-12);
    c.zoom(-2.0);
    EXPECT_NEAR(glm::length(c.eye - c.target), 9.0 / 0.81, 1e-12);
    c.zoom(1e4);
    EXPECT_NEAR(glm::length(c.eye - c.target), 1e-3, 1e-15);
    expect_rigid(c.view());
}

TEST(Controls, MoveTranslatesWithoutTurning) {
    Camera c = look_at({0, 1, 5}, {0, 0, 0});
    const glm::dvec3 f = c.forward();
    c.move({1, 2, 3});
    expect_vec(c.forward(), f);
    expect_vec(c.eye, {1, 3, 8});
    Camera t = transform({0, 0, 0}, 10, 20, 30);
    t.move({-1, 0, 0});
    expect_vec(t.position, {-1, 0, 0});
}

TEST(Controls, TransformPitchIsClampedByTheMouse) {
    Camera c = transform({0, 0, 0}, 0, 80, 0);
    c.rotate(0, 30);
    EXPECT_DOUBLE_EQ(c.pitch_deg, 89.0);
    c.rotate(400, 0);  // yaw wraps into (−180, 180]
    EXPECT_NEAR(c.yaw_deg, 40.0, 1e-12);
}

}  // namespace
