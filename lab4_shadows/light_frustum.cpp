#include "light_frustum.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// Perspective maps: the near plane is never closer than this fraction of the far plane (depth
// precision falls with far / near: at 1000 a 32-bit float map still resolves far·1e-3).
constexpr double kMinNearRatio = 1e-3;

glm::dvec3 unit_or_down(const glm::dvec3& v) {
    const double len = glm::length(v);
    return len > 1e-12 ? v / len : glm::dvec3(0.0, -1.0, 0.0);
}

// Vulkan's framebuffer Y points down: flip, as the camera does, so that triangles keep their
// winding (counter-clockwise = front) in the 2D maps.
glm::dmat4 flip_y(glm::dmat4 p) {
    p[1][1] *= -1.0;
    return p;
}

// Near and far of a perspective map: far reaches the farthest receiver, near the nearest caster
// (`distance` of a box: the smallest depth any of its points has in the map), but never below
// far · kMinNearRatio (a caster closer than that, e.g. with the light inside it, is clipped).
template <typename Near, typename Far>
void fit_depth(const std::vector<Box>& casters, const std::vector<Box>& receivers, Near near_of, Far far_of,
               double& n, double& f) {
    f = 1e-3;
    for (const Box& b : receivers) f = std::max(f, far_of(b));
    for (const Box& b : casters) f = std::max(f, far_of(b));
    n = kInf;
    for (const Box& b : casters) n = std::min(n, near_of(b));
    n = std::clamp(n * 0.99, f * kMinNearRatio, f * 0.5);
    f *= 1.01;
}

// A view matrix's up vector for a camera looking along `direction`: world +Y, unless the
// direction is (nearly) ±Y itself, where cross(direction, up) would vanish: then +Z.
glm::dvec3 up_for(const glm::dvec3& direction) {
    return std::abs(unit_or_down(direction).y) > 0.999 ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(0.0, 1.0, 0.0);
}
}  // namespace

LightFrustum fit_directional(const glm::dvec3& direction, const std::vector<Box>& casters, const std::vector<Box>& receivers) {
    const glm::dvec3 d = unit_or_down(direction);
    Box all = Box::empty();
    for (const Box& b : receivers) all.add(b);
    if (receivers.empty()) all = {glm::dvec3(-1.0), glm::dvec3(1.0)};
    const glm::dvec3 centre = 0.5 * (all.lo + all.hi);
    const glm::dmat4 view = glm::lookAtRH(centre - d, centre, up_for(d));  // looks along −z = d

    // Light space: x, y across the beam, z towards the light.
    Box c = Box::empty(), r = Box::empty();
    for (const Box& b : casters) c.add(lab::transformed(b, view));
    for (const Box& b : receivers) r.add(lab::transformed(b, view));
    if (casters.empty()) c = r;
    // Across the beam: only where a caster can shadow a receiver (both boxes overlap); a receiver
    // outside is lit anyway (outside the map = lit). Along it: from the caster nearest the light
    // to the farthest receiver.
    glm::dvec3 lo(std::max(c.lo.x, r.lo.x), std::max(c.lo.y, r.lo.y), std::min(r.lo.z, c.lo.z));
    glm::dvec3 hi(std::min(c.hi.x, r.hi.x), std::min(c.hi.y, r.hi.y), c.hi.z);
    const double size = std::max({glm::length(all.hi - all.lo), 1e-6});
    for (int i = 0; i < 3; ++i) {
        if (!(hi[i] > lo[i])) hi[i] = lo[i] = 0.5 * (lo[i] + hi[i]);  // empty: no caster over a receiver
        lo[i] -= 1e-4 * size;
        hi[i] += 1e-4 * size;
    }
    LightFrustum f;
    f.near_plane = -hi.z;  // view space looks down −z
    f.far_plane = -lo.z;
    f.view_projection = flip_y(glm::orthoRH_ZO(lo.x, hi.x, lo.y, hi.y, f.near_plane, f.far_plane)) * view;
    f.texel = std::max(hi.x - lo.x, hi.y - lo.y);
    return f;
}

LightFrustum fit_spot(const glm::dvec3& position, const glm::dvec3& direction, double outer_deg,
                      const std::vector<Box>& casters, const std::vector<Box>& receivers) {
    const glm::dvec3 d = unit_or_down(direction);
    const glm::dmat4 view = glm::lookAtRH(position, position + d, up_for(d));
    // The cone plus a degree, so that PCF taps at its edge stay inside the map.
    const double fov = glm::radians(std::clamp(2.0 * outer_deg + 1.0, 1.0, 170.0));
    std::vector<Box> in_cone;
    for (const Box& b : casters)
        if (in_spot_cone(b, position, d, outer_deg)) in_cone.push_back(b);
    // A box's depth along the axis: −z in view space.
    LightFrustum f;
    fit_depth(in_cone, receivers, [&](const Box& b) { return -lab::transformed(b, view).hi.z; },
              [&](const Box& b) { return -lab::transformed(b, view).lo.z; }, f.near_plane, f.far_plane);
    f.view_projection = flip_y(glm::perspectiveRH_ZO(fov, 1.0, f.near_plane, f.far_plane)) * view;
    f.texel = 2.0 * std::tan(fov / 2.0);
    return f;
}

LightFrustum fit_point(const glm::dvec3& position, const std::vector<Box>& casters, const std::vector<Box>& receivers) {
    // A point's depth in the face it falls in is its largest |coordinate| relative to the light,
    // so a box's nearest depth is its Chebyshev distance from the light, its farthest depth at
    // most its farthest corner.
    const auto nearest = [&](const Box& b) {
        const glm::dvec3 gap = glm::max(glm::max(b.lo - position, position - b.hi), glm::dvec3(0.0));
        return std::max({gap.x, gap.y, gap.z});
    };
    const auto farthest = [&](const Box& b) {
        const glm::dvec3 far = glm::max(glm::abs(b.lo - position), glm::abs(b.hi - position));
        return std::max({far.x, far.y, far.z});
    };
    LightFrustum f;
    fit_depth(casters, receivers, nearest, farthest, f.near_plane, f.far_plane);
    // The cube faces in Vulkan's order, with the up vectors that make each face's image what a
    // cube sampler reads for that direction (the OpenGL convention; both APIs put row 0 at t = 0).
    // These views mirror the picture (a cube map is seen from inside): counter-clockwise
    // triangles come out clockwise, so the translucent pass culls the other way (shadow_maps.cpp).
    const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const glm::dvec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    const glm::dmat4 projection = glm::perspectiveRH_ZO(glm::radians(90.0), 1.0, f.near_plane, f.far_plane);
    for (int i = 0; i < 6; ++i) f.faces[i] = projection * glm::lookAtRH(position, position + axes[i], ups[i]);
    f.texel = 2.0;
    return f;
}

bool in_spot_cone(const Box& box, const glm::dvec3& position, const glm::dvec3& direction, double outer_deg) {
    return lab::touches_cone(box, position, unit_or_down(direction), outer_deg + 1.0);  // a degree of margin
}
