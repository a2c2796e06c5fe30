// test_light_frustum.cpp — lab 4's light frusta (lab4_shadows/light_frustum.cpp), by hand: where
// the casters land in each map, which planes the depth gets, which objects count as casters.
// Each case is one a centred, modest scene hides. Each fitted frustum is the lab's value (LAB_PROBE,
// probe.h): the class grader judges it in a process that runs no student code.
#include "light_frustum.h"
#include "probe.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace {

Box box(glm::dvec3 lo, glm::dvec3 hi) { return Box{lo, hi}; }

// The clip-space point (x, y, z / w) of world point p in a 2D map.
glm::dvec3 in_map(const LightFrustum& f, const glm::dvec3& p) {
    const glm::dvec4 c = f.world_to_clip(f.view_projection) * glm::dvec4(p, 1.0);
    return glm::dvec3(c) / c.w;
}

void expect_inside(const LightFrustum& f, const Box& b, const char* what) {
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 corner(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
        const glm::dvec3 q = in_map(f, corner);
        EXPECT_TRUE(std::abs(q.x) <= 1.0 && std::abs(q.y) <= 1.0 && q.z >= 0.0 && q.z <= 1.0)
            << what << ": corner " << i << " lands at " << q.x << ", " << q.y << ", " << q.z;
    }
}

// A directional light over casters 300 units from the origin. Before the fix only p[1][1] was
// negated, so the box's y translation pointed at the mirror image of the casters: none in the map.
TEST(LightFrustum, OffCentreDirectionalBoxHoldsItsCasters) {
    const Box caster = box({300, 40, -120}, {302, 43, -118});
    const Box floor = box({280, 39, -140}, {320, 39, -100});
    const LightFrustum f = LAB_PROBE(fit_directional({-0.3, -1.0, 0.2}, {caster}, {caster, floor}));
    expect_inside(f, caster, "caster");
    // The caster's top is nearer to the light (smaller depth) than its bottom.
    EXPECT_LT(in_map(f, {301, 43, -119}).z, in_map(f, {301, 40, -119}).z);
    // Its matrix is relative to an origin near the scene: small numbers in float.
    EXPECT_LT(glm::length(f.origin - glm::dvec3(300, 39, -120)), 40.0);
    // Across the beam the box is the size of what can be shadowed here, a few units, not the
    // 40-unit floor: a map spread over the whole floor gives the caster's shadow a few texels
    // (coarse, blocky shadows).
    EXPECT_LT(f.texel, 10.0) << "the box's larger side across the beam";
}

// y up in the map is y up in the light's view: a point above the box's centre (as the light
// sees it) has a smaller framebuffer y (Vulkan's y points down), as the camera does.
TEST(LightFrustum, TheWholeYRowFlips) {
    const Box caster = box({10, 0, 10}, {12, 2, 12});
    const LightFrustum f = LAB_PROBE(fit_directional({0, 0, -1}, {caster}, {caster}));  // looking along −z: +y is up
    EXPECT_LT(in_map(f, {11, 1.9, 11}).y, in_map(f, {11, 0.1, 11}).y);
    expect_inside(f, caster, "caster");
}

// A point light 2 units above a 3000-unit floor with a caster 1 unit below it. The floor shadows
// nothing (everything is above it), so it is no caster; far ends just beyond the caster, near
// sits in front of it. Before: far reached the floor's corner (~2100), near = far·1e-3 ≈ 2.1:
// the caster (depth 0.8 … 1.2) was clipped away.
TEST(LightFrustum, CasterBesideTheLightOverAHugeFloor) {
    const glm::dvec3 light(0, 2, 0);
    const Box floor = box({-1500, 0, -1500}, {1500, 0, 1500});
    const Box caster = box({-0.2, 0.8, -0.2}, {0.2, 1.2, 0.2});
    EXPECT_FALSE(can_shadow_from(floor, caster, light));
    EXPECT_TRUE(can_shadow_from(caster, floor, light));
    const LightFrustum f = LAB_PROBE(fit_point(light, {caster}));
    EXPECT_LE(f.near_plane, 0.8);   // the caster's nearest depth in the map (0.8)
    EXPECT_GE(f.far_plane, 1.2);    // its farthest
    EXPECT_LE(f.far_plane, 1.2 * 1.5 + 1e-12);
    // A spot pointing down the same way: the same caster is inside its depth range.
    const LightFrustum s = LAB_PROBE(fit_spot(light, {0, -1, 0}, 40, {caster}));
    expect_inside(s, box({-0.1, 0.8, -0.1}, {0.1, 1.2, 0.1}), "caster under the spot");
}

// The directional test sweeps the caster's box along the light: a floor under everything casts
// on nothing; a box above it casts on it; a box beside the beam does not.
TEST(LightFrustum, WhatACasterCanShadow) {
    const Box floor = box({-5000, 0, -5000}, {5000, 0, 5000});
    const Box cube = box({0, 1, 0}, {1, 2, 1});
    EXPECT_FALSE(can_shadow(floor, cube, {0.3, -1, 0.2}));
    EXPECT_TRUE(can_shadow(cube, floor, {0.3, -1, 0.2}));
    EXPECT_FALSE(can_shadow(cube, box({10, 1, 0}, {11, 2, 1}), {0, -1, 0}));   // beside, light straight down
    EXPECT_TRUE(can_shadow(cube, box({10, 0, 0}, {11, 0.5, 1}), {1, -0.1, 0}));  // grazing light reaches it
    EXPECT_FALSE(can_shadow(cube, box({10, 0, 0}, {11, 0.5, 1}), {-1, -0.1, 0}));  // … not from the other side
    EXPECT_FALSE(can_shadow(cube, box({0, 1, 5}, {1, 2, 6}), {1, 0, 0}));          // parallel, outside the slab
}

// Spot cones wider than 120° (outer above 60°) get a cube map; up to 90° (a 180° cone, the
// widest the format allows) the whole cone is shadowed. A 60° spot's map reaches its edge.
TEST(LightFrustum, WideSpotsUseCubeMaps) {
    lab::LightDesc spot;
    spot.type = lab::LightDesc::Type::Spot;
    spot.outer_deg = 89.0f;  // a 178° cone
    EXPECT_TRUE(uses_cube_map(spot));
    spot.outer_deg = 60.0f;
    EXPECT_FALSE(uses_cube_map(spot));
    lab::LightDesc point;
    point.type = lab::LightDesc::Type::Point;
    EXPECT_TRUE(uses_cube_map(point));
    const Box caster = box({-0.1, -2.1, -0.1}, {0.1, -1.9, 0.1});
    const LightFrustum f = LAB_PROBE(fit_spot({0, 0, 0}, {0, -1, 0}, 60.0, {caster}));
    // A point 59.5° off the axis, 2 units down: inside the map.
    const double a = glm::radians(59.5);
    const glm::dvec3 q = in_map(f, {2.0 * std::tan(a), -2.0, 0.0});
    EXPECT_LT(std::abs(q.x) + std::abs(q.y), 1.0);
}

// The depth bias's bound (shadow_maps.cpp): depth_of_texels is the map's depth change over that
// many texels' world size along the light, at the caster's nearest point, for every kind of map.
// The bound sets how far a device's bias can move a caster, so it must be that step and no other.
TEST(LightFrustum, DepthOfTexelsIsTheDepthStepAtTheCastersNearestPoint) {
    const double texels = 1.0 / 2048.0;
    const auto depth = [](const glm::dmat4& world_to_clip, const glm::dvec3& p) {
        const glm::dvec4 c = world_to_clip * glm::dvec4(p, 1.0);
        return c.z / c.w;
    };
    // Spot straight down from (0, 5, 0): the caster's nearest point 2.9 along the axis.
    const Box slab = box({-0.5, 1.9, -0.5}, {0.5, 2.1, 0.5});
    const LightFrustum spot = LAB_PROBE(fit_spot({0, 5, 0}, {0, -1, 0}, 40.0, {slab}));
    const double step = texels * spot.texel * 2.9;
    const glm::dmat4 s = spot.world_to_clip(spot.view_projection);
    EXPECT_NEAR(spot.depth_of_texels(slab, texels), depth(s, {0, 5 - 2.9 - step, 0}) - depth(s, {0, 5 - 2.9, 0}), 1e-3 * spot.depth_of_texels(slab, texels));
    // Point light at the origin, the caster 4 … 5 along +X: face 0, depth along x from 4.
    const Box side = box({4, -1, -1}, {5, 1, 1});
    const LightFrustum point = LAB_PROBE(fit_point({0, 0, 0}, {side}));
    const glm::dmat4 x = point.world_to_clip(point.faces[0]);
    EXPECT_NEAR(point.depth_of_texels(side, texels), depth(x, {4 + texels * point.texel * 4, 0, 0}) - depth(x, {4, 0, 0}),
                1e-3 * point.depth_of_texels(side, texels));
    // Directional down −Y: depth is linear, one step anywhere.
    const LightFrustum sun = LAB_PROBE(fit_directional({0, -1, 0}, {slab}, {slab, box({-5, -0.1, -5}, {5, 0, 5})}));
    const glm::dmat4 d = sun.world_to_clip(sun.view_projection);
    EXPECT_NEAR(sun.depth_of_texels(slab, texels), depth(d, {0, 1.0 - texels * sun.texel, 0}) - depth(d, {0, 1.0, 0}),
                1e-6);
    // Twice the texels, twice the step; a caster twice as far, half the step (perspective).
    EXPECT_NEAR(point.depth_of_texels(side, 2 * texels), 2 * point.depth_of_texels(side, texels), 1e-12);
    const Box farther = box({8, -1, -1}, {9, 1, 1});
    EXPECT_NEAR(point.depth_of_texels(farther, texels), 0.5 * point.depth_of_texels(side, texels), 1e-9);
}

}  // namespace
