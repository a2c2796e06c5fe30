// test_bounds.cpp — common/content/bounds.h: boxes around meshes, moved by transforms, grown, how
// far they reach from the eye, against a cone; every expected value worked out by hand.
#include "bounds.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace {

void expect_box(const lab::Box& b, glm::dvec3 lo, glm::dvec3 hi, double tolerance = 0.0) {
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(b.lo[i], lo[i], tolerance) << "lo[" << i << "]";
        EXPECT_NEAR(b.hi[i], hi[i], tolerance) << "hi[" << i << "]";
    }
}

TEST(Bounds, EmptyBoxTakesExactlyTheFirstPointOrBox) {
    lab::Box b = lab::Box::empty();
    EXPECT_TRUE(std::isinf(b.lo.x) && b.lo.x > 0 && std::isinf(b.hi.x) && b.hi.x < 0);
    b.add(glm::dvec3(1, -2, 3));
    expect_box(b, {1, -2, 3}, {1, -2, 3});
    b.add(glm::dvec3(-1, 5, 3));
    expect_box(b, {-1, -2, 3}, {1, 5, 3});
    lab::Box c = lab::Box::empty();
    c.add(lab::Box{{0, 0, 0}, {2, 2, 2}});
    c.add(lab::Box{{-3, 1, 1}, {-2, 1.5, 4}});
    expect_box(c, {-3, 0, 0}, {2, 2, 4});
}

TEST(Bounds, MeshBoundsAreItsVertexPositions) {
    lab::Mesh m;
    for (glm::vec3 p : {glm::vec3(0.5f, -1, 2), glm::vec3(-0.25f, 3, 2), glm::vec3(0, 0, -7)}) {
        lab::Vertex v{};
        v.position = p;
        m.vertices.push_back(v);
    }
    expect_box(lab::mesh_bounds(m), {-0.25, -1, -7}, {0.5, 3, 2});
    // The unit cube (docs/meshes.md: edge 1 around the origin).
    expect_box(lab::mesh_bounds(lab::make_cube()), glm::dvec3(-0.5), glm::dvec3(0.5));
    // No vertices: the point box at the origin, never ±∞.
    expect_box(lab::mesh_bounds(lab::Mesh{}), glm::dvec3(0.0), glm::dvec3(0.0));
}

TEST(Bounds, TransformedBoxHoldsTheMovedCorners) {
    const lab::Box unit{glm::dvec3(-1, -2, -3), glm::dvec3(1, 2, 3)};
    // Scale 2 in x, then move by (10, 0, −1): x ∈ [8, 12], z ∈ [−4, 2].
    const glm::dmat4 m = glm::scale(glm::translate(glm::dmat4(1.0), glm::dvec3(10, 0, -1)), glm::dvec3(2, 1, 1));
    expect_box(lab::transformed(unit, m), {8, -2, -4}, {12, 2, 2});
    // 90° about Y: (x, y, z) → (z, y, −x): x ∈ [−3, 3], z ∈ [−1, 1].
    const glm::dmat4 r = glm::rotate(glm::dmat4(1.0), glm::radians(90.0), glm::dvec3(0, 1, 0));
    expect_box(lab::transformed(unit, r), {-3, -2, -1}, {3, 2, 1}, 1e-12);
    // 45° about Z: the box [−1, 1]² grows to ±√2 in x and y.
    const lab::Box square{glm::dvec3(-1, -1, 0), glm::dvec3(1, 1, 0)};
    const glm::dmat4 q = glm::rotate(glm::dmat4(1.0), glm::radians(45.0), glm::dvec3(0, 0, 1));
    expect_box(lab::transformed(square, q), {-std::sqrt(2.0), -std::sqrt(2.0), 0}, {std::sqrt(2.0), std::sqrt(2.0), 0}, 1e-12);
}

TEST(Bounds, FarDepthIsTheFarthestCornerAlongTheViewDirection) {
    // Looking down −z from (0, 0, 5): view-space depth is 5 − z, so the box z ∈ [−1, 1] reaches 6.
    const glm::dmat4 ahead = glm::lookAt(glm::dvec3(0, 0, 5), glm::dvec3(0), glm::dvec3(0, 1, 0));
    EXPECT_NEAR(lab::far_depth(lab::Box{glm::dvec3(-1), glm::dvec3(1)}, ahead), 6.0, 1e-12);
    // A box behind the eye reaches no depth in front of it: negative.
    EXPECT_NEAR(lab::far_depth(lab::Box{glm::dvec3(-1, -1, 7), glm::dvec3(1, 1, 9)}, ahead), -2.0, 1e-12);
    // From (0, 2, 5) towards the origin, d = (0, −2, −5)/√29: a depth is (corner − eye)·d. The unit
    // cube's farthest corner (·, −0.5, −0.5) is at (2·2.5 + 5·5.5)/√29 = 32.5/√29; a 12 × 12 floor
    // at y = 0 reaches (·, 0, −6), at (2·2 + 5·11)/√29 = 59/√29. So the floor, which holds the
    // cube's footprint and more, is drawn after it.
    const glm::dmat4 above = glm::lookAt(glm::dvec3(0, 2, 5), glm::dvec3(0), glm::dvec3(0, 1, 0));
    const lab::Box cube{glm::dvec3(-0.5), glm::dvec3(0.5)};
    const lab::Box floor{glm::dvec3(-6, 0, -6), glm::dvec3(6, 0, 6)};
    EXPECT_NEAR(lab::far_depth(cube, above), 32.5 / std::sqrt(29.0), 1e-12);
    EXPECT_NEAR(lab::far_depth(floor, above), 59.0 / std::sqrt(29.0), 1e-12);
    // The eye inside a room: its far wall still counts, 5 + 10 = 15 away.
    EXPECT_NEAR(lab::far_depth(lab::Box{glm::dvec3(-10), glm::dvec3(10)}, ahead), 15.0, 1e-12);
}

TEST(Bounds, ConeTouchesBoxesWithinItsAngle) {
    // A 30° cone from the origin along +X; a box of half-size 0.1 (bounding radius √0.03 ≈ 0.173).
    const glm::dvec3 apex(0.0), axis(1, 0, 0);
    const auto box_at = [](glm::dvec3 c) { return lab::Box{c - 0.1, c + 0.1}; };
    EXPECT_TRUE(lab::touches_cone(box_at({5, 0, 0}), apex, axis, 30.0)) << "on the axis";
    EXPECT_TRUE(lab::touches_cone(box_at({5, 2.5, 0}), apex, axis, 30.0)) << "26.6° off the axis";
    EXPECT_FALSE(lab::touches_cone(box_at({5, 5, 0}), apex, axis, 30.0)) << "45° off the axis";
    EXPECT_FALSE(lab::touches_cone(box_at({-5, 0, 0}), apex, axis, 30.0)) << "behind the apex";
    EXPECT_TRUE(lab::touches_cone(box_at({0.05, 0.05, 0}), apex, axis, 30.0)) << "the apex inside the box";
    // 45° off the axis at distance √50: the sphere's centre is √50 · sin(15°) ≈ 1.83 outside a 30° cone.
    const lab::Box big{glm::dvec3(5 - 1.9, 5 - 1.9, -1.9), glm::dvec3(5 + 1.9, 5 + 1.9, 1.9)};  // radius 1.9·√3 ≈ 3.29
    EXPECT_TRUE(lab::touches_cone(big, apex, axis, 30.0)) << "a large box reaches into the cone";
    EXPECT_TRUE(lab::touches_cone(box_at({-5, 0, 0}), apex, axis, 89.0)) << "89° or more: everything";
}

}  // namespace
