// Camera math of lab 1 against the CPU reference's camera (tests/reference/cpu_reference.h, built
// from docs/conventions.md), degenerate inputs and the mode-switch round trip. The expected
// matrices and axes come from the reference, not from this file: a student copy holds the
// reference prebuilt (docs/solutions.md). The controls (Controls.*) are checked on positions and
// distances worked out by hand for given drags and wheel steps. Every value the lab computes goes
// through LAB_PROBE (probe.h): the class grader judges it in a process that runs no student code.
#include "camera.h"

#include "probe.h"
#include "reference/cpu_reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

constexpr double kEps = 1e-12;

// Camera-space coordinates of a world point.
glm::dvec3 to_camera(const Camera& c, const glm::dvec3& p) { return glm::dvec3(LAB_PROBE(c.view()) * glm::dvec4(p, 1.0)); }

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

// The reference's camera for the same pose, and the checks against it.
ref::Camera reference_of(const Camera& c) {
    return c.mode == Camera::Mode::LookAt ? ref::look_at_camera(c.eye, c.target, c.up)
                                          : ref::transform_camera(c.position, c.yaw_deg, c.pitch_deg, c.roll_deg);
}

// The lab's view matrix and axes are the reference's, to `eps` relative to the pose's magnitude.
void expect_reference_pose(const Camera& c, double eps = 1e-9) {
    const ref::Camera r = reference_of(c);
    double magnitude = 1.0;
    for (int i = 0; i < 3; ++i) magnitude = std::max(magnitude, std::abs(r.eye[i]));
    expect_mat(LAB_PROBE(c.view()), r.view(), eps * magnitude);
    expect_vec(LAB_PROBE(c.forward()), r.forward, eps);
    expect_vec(LAB_PROBE(c.right()), r.right, eps);
    expect_vec(glm::dvec3(LAB_PROBE(c.camera_to_world())[1]), r.up, eps);
    expect_vec(LAB_PROBE(c.world_position()), r.eye, eps * magnitude);
}

// ------------------------------------------------------------------ Look-At

TEST(LookAt, DownMinusZIsATranslation) { expect_reference_pose(look_at({0, 0, 5}, {0, 0, 0})); }

TEST(LookAt, LookingAlongPlusX) { expect_reference_pose(look_at({0, 0, 0}, {1, 0, 0})); }

TEST(LookAt, TargetLandsOnTheMinusZAxisAtItsDistance) {
    const Camera c = look_at({3, 4, 5}, {-1, 2, 0.5});
    expect_reference_pose(c);
    expect_rigid(LAB_PROBE(c.view()));
}

// Looking straight down or up along `up`: the fallbacks docs/conventions.md documents.
TEST(LookAt, TopDownViewFallsBackToMinusZUp) {
    const Camera c = look_at({0, 5, 0}, {0, 0, 0});
    expect_rigid(LAB_PROBE(c.view()));
    expect_reference_pose(c);
}

TEST(LookAt, BottomUpViewFallsBackToPlusZUp) {
    const Camera c = look_at({0, -5, 0}, {0, 0, 0});
    expect_rigid(LAB_PROBE(c.view()));
    expect_reference_pose(c);
}

TEST(LookAt, UpAlongZAndViewAlongZUsesX) {
    const Camera c = look_at({0, 0, 5}, {0, 0, 0}, {0, 0, 1});
    expect_rigid(LAB_PROBE(c.view()));
    expect_reference_pose(c);
}

TEST(LookAt, EyeEqualsTargetLooksDownMinusZ) {
    const Camera c = look_at({1, 2, 3}, {1, 2, 3});
    expect_rigid(LAB_PROBE(c.view()));
    expect_reference_pose(c);
}

TEST(LookAt, ZeroUpVectorStaysFinite) {
    const Camera c = look_at({0, 1, 5}, {0, 0, 0}, {0, 0, 0});
    expect_rigid(LAB_PROBE(c.view()));
}

TEST(LookAt, HugeAndTinyCoordinates) {
    for (double scale : {1e-9, 1e-4, 1.0, 1e4, 1e9}) {
        SCOPED_TRACE(scale);
        const glm::dvec3 eye = glm::dvec3(1, 2, 3) * scale;
        const glm::dvec3 target = eye + glm::dvec3(0, 0, -1) * scale;
        const Camera c = look_at(eye, target);
        expect_rigid(LAB_PROBE(c.view()));
        expect_reference_pose(c, 1e-6);
        // The target lies on the view axis at its distance.
        const glm::dvec3 t = to_camera(c, target);
        EXPECT_NEAR(glm::length(t) / scale, 1.0, 1e-6);
        // The float matrix the GPU receives is finite too.
        const glm::mat4 f(LAB_PROBE(c.view()));
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) EXPECT_TRUE(std::isfinite(f[i][j]));
    }
    // Eye and target 1e-12 apart at 1e6: still a valid basis.
    expect_rigid(LAB_PROBE(look_at({1e6, 1e6, 1e6}, {1e6 + 1e-6, 1e6, 1e6}).view()));
}

// ---------------------------------------------------------------- Transform

TEST(Transform, ZeroAnglesLookDownMinusZ) { expect_reference_pose(transform({1, 2, 3}, 0, 0, 0)); }

TEST(Transform, Yaw90LooksDownMinusX) { expect_reference_pose(transform({0, 0, 0}, 90, 0, 0)); }

TEST(Transform, PositivePitchLooksUp) { expect_reference_pose(transform({0, 0, 0}, 0, 30, 0)); }

TEST(Transform, RollTurnsTheImage) { expect_reference_pose(transform({0, 0, 0}, 0, 0, 90)); }

// All three angles at once: the order the rotations apply in matters.
TEST(Transform, AllThreeAnglesAtOnce) { expect_reference_pose(transform({0, 0, 0}, 90, 30, 45)); }

TEST(Transform, PitchAtPlusMinus90StaysRigid) {
    for (double pitch : {-90.0, 90.0}) {
        const Camera c = transform({1, 2, 3}, 37, pitch, -12);
        expect_rigid(LAB_PROBE(c.view()));
        expect_reference_pose(c);
    }
}

TEST(Transform, HugePositions) {
    const Camera c = transform({1e9, -1e9, 1e9}, 10, 20, 30);
    expect_rigid(LAB_PROBE(c.view()));
    expect_reference_pose(c, 1e-9);
}

// --------------------------------------------------------------- Projection

TEST(Projection, MatchesTheReference) {
    for (const double fov : {90.0, 60.0, 20.0})
        for (const double aspect : {2.0, 1.0, 0.5}) {
            Camera c;
            c.fov_y_deg = fov;
            c.near_plane = 0.5;
            c.far_plane = 10.0;
            ref::Camera r;
            r.fov_y_deg = fov;
            r.near_plane = 0.5;
            r.far_plane = 10.0;
            SCOPED_TRACE(testing::Message() << "fov " << fov << ", aspect " << aspect << ", near 0.5, far 10");
            expect_mat(LAB_PROBE(c.projection(aspect)), ref::projection(r, aspect), kEps);
        }
}

// -------------------------------------------------------------- Mode switch

TEST(ModeSwitch, KeepsThePoseExactly) {
    std::mt19937 rng(1234);
    std::uniform_real_distribution<double> coord(-50.0, 50.0), angle(-180.0, 180.0), pitch(-90.0, 90.0);
    for (int trial = 0; trial < 200; ++trial) {
        Camera c = trial % 2 ? look_at({coord(rng), coord(rng), coord(rng)}, {coord(rng), coord(rng), coord(rng)})
                             : transform({coord(rng), coord(rng), coord(rng)}, angle(rng), pitch(rng), angle(rng));
        // The pose starts as the reference's: with look_at and transform still stubs both cameras
        // ignore every angle, and the round trip below would be exact whatever mode_switch does.
        SCOPED_TRACE(testing::Message() << "trial " << trial);
        expect_reference_pose(c);
        if (HasFailure()) return;
        const glm::dmat4 original = LAB_PROBE(c.view());
        for (int i = 0; i < 50; ++i) {  // many switches back and forth
            const glm::dmat4 before = LAB_PROBE(c.view());
            LAB_PROBE_UPDATE(c, c.set_mode(c.mode == Camera::Mode::LookAt ? Camera::Mode::Transform : Camera::Mode::LookAt));
            expect_mat(LAB_PROBE(c.view()), before, 1e-9);
        }
        expect_mat(LAB_PROBE(c.view()), original, 1e-8);
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
        // Each pose starts as the reference's (see KeepsThePoseExactly): stubbed cameras that
        // ignore the angles would make the round trip trivially exact.
        expect_reference_pose(c);
        if (HasFailure()) return;
        const glm::dmat4 original = LAB_PROBE(c.view());
        // Relative tolerance: a translation of 1e6 carries ~1e-10 of double
        // rounding per switch; float (what the GPU gets) resolves only 6e-8 of it.
        double magnitude = 1.0;
        for (int i = 0; i < 4; ++i) magnitude = std::max(magnitude, std::abs(original[3][i]));
        for (int i = 0; i < 20; ++i) {
            LAB_PROBE_UPDATE(c, c.set_mode(c.mode == Camera::Mode::LookAt ? Camera::Mode::Transform : Camera::Mode::LookAt));
            expect_rigid(LAB_PROBE(c.view()));
            expect_mat(LAB_PROBE(c.view()), original, 1e-10 * magnitude);
        }
    }
}

TEST(ModeSwitch, LookAtKeepsItsTargetDistance) {
    Camera c = look_at({0, 0, 7}, {0, 0, 0});
    LAB_PROBE_UPDATE(c, c.set_mode(Camera::Mode::Transform));
    LAB_PROBE_UPDATE(c, c.set_mode(Camera::Mode::LookAt));
    EXPECT_NEAR(glm::length(c.eye - c.target), 7.0, 1e-12);
}

// ----------------------------------------------------------------- Controls

TEST(Controls, OrbitKeepsTheDistanceAndTarget) {
    Camera c = look_at({3, 2, 4}, {0.5, 0, 0});
    const double d = glm::length(c.eye - c.target);
    for (int i = 0; i < 100; ++i) {
        LAB_PROBE_UPDATE(c, c.rotate(7.0, i % 2 ? 13.0 : -9.0));
        EXPECT_NEAR(glm::length(c.eye - c.target), d, 1e-9);
        expect_vec(to_camera(c, c.target), {0, 0, -d}, 1e-9);
    }
}

TEST(Controls, OrbitStopsShortOfThePoles) {
    // Far over the top (looking down), then far under the bottom (looking up): 1° from +Y, 1° from −Y.
    for (const double pitch : {-500.0, 500.0}) {
        Camera c = look_at({0, 0, 5}, {0, 0, 0});
        LAB_PROBE_UPDATE(c, c.rotate(0.0, pitch));
        const double polar = std::acos(glm::dot(glm::normalize(c.eye - c.target), glm::dvec3(0, 1, 0)));
        EXPECT_NEAR(polar * 180.0 / 3.14159265358979323846, pitch < 0.0 ? 1.0 : 179.0, 1e-9) << "pitch " << pitch;
        EXPECT_NEAR(glm::length(c.eye - c.target), 5.0, 1e-12);
    }
}

// Worked by hand: where the eye must be after each drag. A positive yaw turns the view left and a
// positive pitch looks up, as in Transform mode.
TEST(Controls, OrbitMovesTheEyeAsWorkedByHand) {
    Camera c = look_at({0, 0, 5}, {0, 0, 0});
    LAB_PROBE_UPDATE(c, c.rotate(90.0, 0.0));  // looking along -Z, a quarter turn left: along -X
    expect_vec(c.eye, {5, 0, 0});
    LAB_PROBE_UPDATE(c, c.rotate(0.0, 30.0));  // 30° up: the eye 30° below the equator, 120° from +Y
    expect_vec(c.eye, {4.330127018922193, -2.5, 0});
    expect_vec(c.target, {0, 0, 0});

    // Another target and up = +Z; -45° looks down.
    Camera z = look_at({6, 2, 3}, {1, 2, 3}, {0, 0, 1});
    LAB_PROBE_UPDATE(z, z.rotate(90.0, 0.0));
    expect_vec(z.eye, {1, 7, 3});
    LAB_PROBE_UPDATE(z, z.rotate(0.0, -45.0));
    expect_vec(z.eye, {1, 2 + 3.5355339059327378, 3 + 3.5355339059327378});
}

// Stress: the same drags at 10⁶ and 10⁻³ from the target keep the distance to 1e-12 of it, and
// an eye on the target (no sphere to move on) stays put, finite.
TEST(Controls, OrbitAtHugeAndTinyDistances) {
    for (const double d : {1e6, 1e-3}) {
        Camera c = look_at({0, 0.5 * d, d}, {0, 0, 0});
        const double distance = glm::length(c.eye - c.target);
        for (int i = 0; i < 50; ++i) LAB_PROBE_UPDATE(c, c.rotate(23.0, i % 2 ? 17.0 : -11.0));
        EXPECT_NEAR(glm::length(c.eye - c.target), distance, 1e-12 * distance) << "distance " << d;
    }
    Camera same = look_at({1, 2, 3}, {1, 2, 3});
    LAB_PROBE_UPDATE(same, same.rotate(30.0, 20.0));
    expect_vec(same.eye, {1, 2, 3}, 0.0);
}

TEST(Controls, ZoomIsExponentialAndClamped) {
    Camera c = look_at({0, 0, 10}, {0, 0, 0});
    LAB_PROBE_UPDATE(c, c.zoom(1.0));
    EXPECT_NEAR(glm::length(c.eye - c.target), 9.0, 1e-12);
    LAB_PROBE_UPDATE(c, c.zoom(-2.0));
    EXPECT_NEAR(glm::length(c.eye - c.target), 9.0 / 0.81, 1e-12);
    LAB_PROBE_UPDATE(c, c.zoom(1e4));
    EXPECT_NEAR(glm::length(c.eye - c.target), 1e-3, 1e-15);
    expect_rigid(LAB_PROBE(c.view()));
}

TEST(Controls, MoveTranslatesWithoutTurning) {
    Camera c = look_at({0, 1, 5}, {0, 0, 0});
    const glm::dvec3 f = LAB_PROBE(c.forward());
    LAB_PROBE_UPDATE(c, c.move({1, 2, 3}));
    expect_vec(LAB_PROBE(c.forward()), f);
    expect_vec(c.eye, {1, 3, 8});
    Camera t = transform({0, 0, 0}, 10, 20, 30);
    LAB_PROBE_UPDATE(t, t.move({-1, 0, 0}));
    expect_vec(t.position, {-1, 0, 0});
}

TEST(Controls, TransformPitchIsClampedByTheMouse) {
    Camera c = transform({0, 0, 0}, 0, 80, 0);
    LAB_PROBE_UPDATE(c, c.rotate(0, 30));
    EXPECT_DOUBLE_EQ(c.pitch_deg, 89.0);
    LAB_PROBE_UPDATE(c, c.rotate(400, 0));  // yaw wraps into (−180, 180]
    EXPECT_NEAR(c.yaw_deg, 40.0, 1e-12);
}

}  // namespace
