// light_frustum.h — lab 4: where each light's shadow map looks, in double precision.
//  * directional: an orthographic box along the light, fitted tightly to the casters and the
//    receivers in light space, so the map's texels are spent where there is geometry;
//  * spot: a perspective frustum covering the outer cone;
//  * point: six 90° frusta, one per cube face.
// Near and far planes are fitted to the objects too: depth precision is spent between them.
#pragma once

#include "bounds.h"

#include <glm/glm.hpp>

#include <array>
#include <vector>

using lab::Box;  // an axis-aligned bounding box in world space

// The light's map as the shaders use it: world → the map's clip space; for a point light the
// six faces (+X, −X, +Y, −Y, +Z, −Z); near/far of the perspective maps; world size of one
// texel at distance 1 (perspective) or anywhere (orthographic), for a map of 1 texel.
struct LightFrustum {
    glm::dmat4 view_projection{1.0};     // directional, spot
    std::array<glm::dmat4, 6> faces{};   // point
    double near_plane = 0.0, far_plane = 1.0;
    double texel = 1.0;
};

// `receivers`: every object; `casters`: the objects with cast_shadows.
LightFrustum fit_directional(const glm::dvec3& direction, const std::vector<Box>& casters, const std::vector<Box>& receivers);
LightFrustum fit_spot(const glm::dvec3& position, const glm::dvec3& direction, double outer_deg,
                      const std::vector<Box>& casters, const std::vector<Box>& receivers);
LightFrustum fit_point(const glm::dvec3& position, const std::vector<Box>& casters, const std::vector<Box>& receivers);

// Can a caster inside `box` throw a shadow in the spot light's cone (lab::touches_cone)? A caster
// outside never changes the map.
bool in_spot_cone(const Box& box, const glm::dvec3& position, const glm::dvec3& direction, double outer_deg);
