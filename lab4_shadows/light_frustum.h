// light_frustum.h — lab 4: where each light's shadow map looks, in double precision.
//  * directional: an orthographic box along the light, fitted tightly to the casters and the
//    receivers in light space, so the map's texels are spent where there is geometry;
//  * spot: a perspective frustum covering the outer cone;
//  * point: six 90° frusta, one per cube face.
// Near and far planes are fitted to the objects too: depth precision is spent between them.
#pragma once

#include "bounds.h"
#include "scene.h"

#include <glm/glm.hpp>

#include <array>
#include <vector>

using lab::Box;  // an axis-aligned bounding box in world space

// The light's map as the shaders use it: (world − origin) → the map's clip space; for a point
// light the six faces (+X, −X, +Y, −Y, +Z, −Z); near/far; world size of one texel at distance 1
// (perspective) or anywhere (orthographic), for a map of 1 texel.
// Why an origin: the shaders work in float. A scene 10⁴ units from the world's origin has
// positions good to ~10⁻³, and world → clip would subtract such numbers inside the matrix
// product; relative to the light (or the fitted box's centre) the numbers stay small.
struct LightFrustum {
    glm::dvec3 origin{0.0};              // the light (spot, point); the fitted box's centre (directional)
    glm::dmat4 view_projection{1.0};     // directional, spot
    std::array<glm::dmat4, 6> faces{};   // point
    double near_plane = 0.0, far_plane = 1.0;
    double texel = 1.0;
    bool perspective = false, cube = false;  // spot, point: a perspective depth along the axis

    // World → clip, for the shadow pass (composed in double, then used in float).
    glm::dmat4 world_to_clip(const glm::dmat4& relative) const;
    // How much the map's depth changes along the light over `texels` texels' world size (`texel`
    // times that, times the distance for perspective maps) at the nearest point of `caster`: the
    // depth bias's upper bound (shadow_maps.cpp).
    double depth_of_texels(const Box& caster, double texels) const;
    // Perspective maps: the two constants, from the near and far planes, of the depth the map
    // stores for a point at a given distance along its axis — the lookup's params.y and params.z
    // (shadows.glsl), from which exercise cube_face_depth computes that depth.
    double depth_a() const;
    double depth_b() const;
};

// `casters`: the objects the map holds (the shadow pass's casters_for: those that can shadow a
// receiver, in a spot's cone); `receivers`: every object. Perspective maps need only the casters:
// their depth range ends just beyond the farthest one.
LightFrustum fit_directional(const glm::dvec3& direction, const std::vector<Box>& casters, const std::vector<Box>& receivers);
LightFrustum fit_spot(const glm::dvec3& position, const glm::dvec3& direction, double outer_deg, const std::vector<Box>& casters);
// A point light's cube; also a spot light's when its cone is too wide for one map.
LightFrustum fit_point(const glm::dvec3& position, const std::vector<Box>& casters);

// Spot lights with an outer angle above this get a cube map, as point lights do: one perspective
// map would need a field of view of twice the outer angle (180° at 90°: impossible), and its
// texels at the cone's edge grow as 1/cos² of the angle (4× the centre's at 60°).
constexpr double kWidestSpotMapDeg = 60.0;
bool uses_cube_map(const lab::LightDesc& light);

// Where the ray a + t·d, t in [0, t_max], first enters `box`: that t (0 when a is inside it), or −1
// when it misses (the slab test: the t where it is between each pair of planes, intersected).
double ray_entry(const glm::dvec3& a, const glm::dvec3& d, const Box& box, double t_max);

// Can anything inside box `caster` shadow anything inside box `receiver`? False only when it
// cannot; a caster that shadows no receiver is left out of the fit, so that a big floor under
// everything does not spread the map's texels over itself. Directional light (`direction`: the
// way the light travels): the caster's box swept along the light misses the receiver's box. A
// light at `position`: the box around the receiver and the light misses the caster's box.
bool can_shadow(const Box& caster, const Box& receiver, const glm::dvec3& direction);
bool can_shadow_from(const Box& caster, const Box& receiver, const glm::dvec3& position);

// Can a caster inside `box` throw a shadow in the spot light's cone (lab::touches_cone)? A caster
// outside never changes the map.
bool in_spot_cone(const Box& box, const glm::dvec3& position, const glm::dvec3& direction, double outer_deg);
