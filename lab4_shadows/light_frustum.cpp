#include "light_frustum.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// Perspective maps: the near plane is never closer than this fraction of the far plane (depth
// precision falls with far / near: at 1000 a 32-bit float map still resolves far·1e-3). A caster
// closer to the light than that is not lost: the shadow pass clamps its depth to 0 (depth clamp).
constexpr double kMinNearRatio = 1e-3;
// Far planes sit this far beyond the farthest caster (a margin for the depth bias).
constexpr double kFarMargin = 1.5;

glm::dvec3 unit_or_down(const glm::dvec3& v) {
    const double len = glm::length(v);
    return len > 1e-12 ? v / len : glm::dvec3(0.0, -1.0, 0.0);
}

// Vulkan's framebuffer Y points down: flip, as the camera does, so that triangles keep their
// winding (counter-clockwise = front) in the 2D maps. The whole y row of the projection flips
// (y_clip = −(row 1 · p)): an off-centre orthographic box has a y translation in p[3][1] too.
glm::dmat4 flip_y(glm::dmat4 p) {
    for (int column = 0; column < 4; ++column) p[column][1] *= -1.0;
    return p;
}

// Near and far of a perspective map, from the casters alone. Far lies just beyond the farthest
// caster: a receiver farther away needs no depth in the map, the lookup clamps its depth to 1,
// where a texel without a caster still reads "lit" (the map is cleared to 1). Near is the nearest
// caster (`distance` of a box: the smallest depth any of its points has in the map), but never
// below far · kMinNearRatio.
template <typename Near, typename Far>
void fit_depth(const std::vector<Box>& casters, Near near_of, Far far_of, double& n, double& f) {
    f = 0.0;
    n = kInf;
    for (const Box& b : casters) {
        f = std::max(f, far_of(b));
        n = std::min(n, near_of(b));
    }
    if (!(f > 0.0)) f = n = 1.0;  // no caster: an empty map, any planes do
    f *= kFarMargin;
    n = std::clamp(n * 0.99, f * kMinNearRatio, f * 0.5);
}

// A box seen from a point light at `light`: the smallest and the largest distance along a cube
// face's axis that its points have (each point on the face it falls in): what the six faces' near
// and far planes must hold. A box around the light: nearest 0.
struct CubeReach {
    double nearest = 0.0, farthest = 0.0;
};
CubeReach cube_reach(const Box& b, const glm::dvec3& light) {
    CubeReach r;
    for (int i = 0; i < 3; ++i) {
        // The box's span on axis i relative to the light, seen from the + side and from the − side.
        const double plus_lo = b.lo[i] - light[i], plus_hi = b.hi[i] - light[i];
        const double minus_lo = light[i] - b.hi[i], minus_hi = light[i] - b.lo[i];
        r.nearest = std::max({r.nearest, plus_lo, minus_lo});
        r.farthest = std::max({r.farthest, plus_lo, minus_hi, plus_hi, minus_lo});
    }
    return r;
}

// A view matrix's up vector for a camera looking along `direction`: world +Y, unless the
// direction is (nearly) ±Y itself, where cross(direction, up) would vanish: then +Z.
glm::dvec3 up_for(const glm::dvec3& direction) {
    return std::abs(unit_or_down(direction).y) > 0.999 ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(0.0, 1.0, 0.0);
}
}  // namespace

glm::dmat4 LightFrustum::world_to_clip(const glm::dmat4& relative) const { return relative * glm::translate(glm::dmat4(1.0), -origin); }

double LightFrustum::depth_of_texels(const Box& caster, double texels) const {
    if (!perspective) return texels * texel / (far_plane - near_plane);  // orthographic: depth is linear
    // Perspective: not linear; the step is largest where the caster comes nearest the light, so it
    // is taken at the caster's nearest z, its distance along the face's or spot's axis (a spot's:
    // clip w, smallest at a corner of the box).
    double z = kInf;
    if (cube) {
        z = cube_reach(caster, origin).nearest;
    } else {
        for (int corner = 0; corner < 8; ++corner) {
            const glm::dvec3 p(corner & 1 ? caster.hi.x : caster.lo.x, corner & 2 ? caster.hi.y : caster.lo.y,
                               corner & 4 ? caster.hi.z : caster.lo.z);
            z = std::min(z, (view_projection * glm::dvec4(p - origin, 1.0)).w);
        }
    }
    z = std::max(z, near_plane);  // nearer: drawn at depth 0 (depth clamp)
    return depth_b() * texels * texel / z;
}

double LightFrustum::depth_a() const { return far_plane / (far_plane - near_plane); }
double LightFrustum::depth_b() const { return far_plane * near_plane / (far_plane - near_plane); }

bool uses_cube_map(const lab::LightDesc& light) {
    return light.type == lab::LightDesc::Type::Point ||
           (light.type == lab::LightDesc::Type::Spot && light.outer_deg > kWidestSpotMapDeg);
}

LightFrustum fit_directional(const glm::dvec3& direction, const std::vector<Box>& casters, const std::vector<Box>& receivers) {
    const glm::dvec3 d = unit_or_down(direction);
    Box all = Box::empty();
    for (const Box& b : receivers) all.add(b);
    if (receivers.empty()) all = {glm::dvec3(-1.0), glm::dvec3(1.0)};
    LightFrustum f;
    f.origin = 0.5 * (all.lo + all.hi);
    const glm::dmat4 view = glm::lookAtRH(f.origin - d, f.origin, up_for(d));  // looks along −z = d

    // Light space: x, y across the beam, z towards the light.
    Box c = Box::empty(), r = Box::empty();
    for (const Box& b : casters) c.add(lab::transformed(b, view));
    for (const Box& b : receivers) r.add(lab::transformed(b, view));
    if (casters.empty()) c = r;
    // EXERCISE directional_box: the orthographic box in light space (x, y across the beam, z towards the light): across the beam, where can a caster (box c) shadow a receiver (box r)? Along it, from which depth to which must the map hold depths? Keep a box that is empty in some axis valid. Two constants you cannot derive (the instructors' pictures assume them; the tests in a copy pass without them): along the beam, the box reaches beyond the farthest caster by (kFarMargin − 1) × the casters' own depth extent (box c's size in z); and the finished box is widened by 1e-4 × the length of the receivers' bounding-box diagonal (`all`) on both sides of every axis. Read this lab's README "Two passes" and kFarMargin above; test_light_frustum.cpp says what the box must hold. Wrong: shadows cut off at an edge or missing far from the origin, or coarse blocky shadows (a box much larger than needed). Checked by LightFrustum.OffCentreDirectionalBoxHoldsItsCasters, Lab4Stress.DirectionalLightOverCastersFarFromTheOrigin.
    // STUB: glm::dvec3 lo(-1.0), hi(1.0);  // a fixed 2-unit box round the scene's centre
    // Across the beam: only where a caster can shadow a receiver (both boxes overlap); a receiver
    // outside is lit anyway (outside the map = lit). Along it: from the caster nearest the light
    // to a little beyond the farthest caster (farther receivers: depth clamped to 1, see fit_depth).
    const double margin = (kFarMargin - 1.0) * (c.hi.z - c.lo.z);
    glm::dvec3 lo(std::max(c.lo.x, r.lo.x), std::max(c.lo.y, r.lo.y), c.lo.z - margin);
    glm::dvec3 hi(std::min(c.hi.x, r.hi.x), std::min(c.hi.y, r.hi.y), c.hi.z);
    const double size = std::max({glm::length(all.hi - all.lo), 1e-6});
    for (int i = 0; i < 3; ++i) {
        if (!(hi[i] > lo[i])) hi[i] = lo[i] = 0.5 * (lo[i] + hi[i]);  // empty: no caster over a receiver
        lo[i] -= 1e-4 * size;
        hi[i] += 1e-4 * size;
    }
    // END EXERCISE
    f.near_plane = -hi.z;  // view space looks down −z
    f.far_plane = -lo.z;
    f.view_projection = flip_y(glm::orthoRH_ZO(lo.x, hi.x, lo.y, hi.y, f.near_plane, f.far_plane)) * view *
                        glm::translate(glm::dmat4(1.0), f.origin);
    f.texel = std::max(hi.x - lo.x, hi.y - lo.y);
    return f;
}

LightFrustum fit_spot(const glm::dvec3& position, const glm::dvec3& direction, double outer_deg, const std::vector<Box>& casters) {
    const glm::dvec3 d = unit_or_down(direction);
    LightFrustum f;
    f.origin = position;
    const glm::dmat4 view = glm::lookAtRH(glm::dvec3(0.0), d, up_for(d));  // relative to the light
    // The cone plus 2 % of its width, so that PCF taps at its edge stay inside the map (a margin
    // in proportion: a narrow, far spot keeps its texels small).
    const double half_tan = std::max(std::tan(glm::radians(std::clamp(outer_deg, 0.0, kWidestSpotMapDeg))) * 1.02, 1e-3);
    const double fov = 2.0 * std::atan(half_tan);
    // A box's depth along the axis: −z in view space.
    const glm::dmat4 world_view = view * glm::translate(glm::dmat4(1.0), -position);
    fit_depth(casters, [&](const Box& b) { return -lab::transformed(b, world_view).hi.z; },
              [&](const Box& b) { return -lab::transformed(b, world_view).lo.z; }, f.near_plane, f.far_plane);
    f.view_projection = flip_y(glm::perspectiveRH_ZO(fov, 1.0, f.near_plane, f.far_plane)) * view;
    f.texel = 2.0 * half_tan;
    f.perspective = true;
    return f;
}

LightFrustum fit_point(const glm::dvec3& position, const std::vector<Box>& casters) {
    // The casters' reach over the six faces bounds the near and far planes.
    LightFrustum f;
    f.origin = position;
    fit_depth(casters, [&](const Box& b) { return cube_reach(b, position).nearest; },
              [&](const Box& b) { return cube_reach(b, position).farthest; }, f.near_plane, f.far_plane);
    // The cube faces in Vulkan's order, with the up vectors that make each face's image what a
    // cube sampler reads for that direction (the OpenGL convention; both APIs put row 0 at t = 0).
    // These views mirror the picture (a cube map is seen from inside): counter-clockwise
    // triangles come out clockwise, so the translucent pass culls the other way (shadow_maps.cpp).
    const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const glm::dvec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    const glm::dmat4 projection = glm::perspectiveRH_ZO(glm::radians(90.0), 1.0, f.near_plane, f.far_plane);
    for (int i = 0; i < 6; ++i) f.faces[i] = projection * glm::lookAtRH(glm::dvec3(0.0), axes[i], ups[i]);
    f.texel = 2.0;
    f.perspective = f.cube = true;
    return f;
}

double ray_entry(const glm::dvec3& a, const glm::dvec3& d, const Box& box, double t_max) {
    double t0 = 0.0, t1 = t_max;
    for (int i = 0; i < 3; ++i) {
        if (std::abs(d[i]) < 1e-300) {
            if (a[i] < box.lo[i] || a[i] > box.hi[i]) return -1.0;  // parallel to the slab and outside it
            continue;
        }
        const double u = (box.lo[i] - a[i]) / d[i], v = (box.hi[i] - a[i]) / d[i];
        t0 = std::max(t0, std::min(u, v));
        t1 = std::min(t1, std::max(u, v));
    }
    return t0 <= t1 ? t0 : -1.0;
}

bool can_shadow(const Box& caster, const Box& receiver, const glm::dvec3& direction) {
    // The swept caster {c + t·d, t ≥ 0} meets the receiver exactly when the ray t·d (t ≥ 0) meets
    // the Minkowski difference receiver − caster = [R.lo − C.hi, R.hi − C.lo].
    return ray_entry(glm::dvec3(0.0), unit_or_down(direction), Box{receiver.lo - caster.hi, receiver.hi - caster.lo}, kInf) >= 0.0;
}

bool can_shadow_from(const Box& caster, const Box& receiver, const glm::dvec3& position) {
    // Every shadow ray runs from a receiver point to the light, inside the box around both.
    Box rays = receiver;
    rays.add(Box{position, position});
    for (int i = 0; i < 3; ++i)
        if (rays.hi[i] < caster.lo[i] || caster.hi[i] < rays.lo[i]) return false;
    return true;
}

bool in_spot_cone(const Box& box, const glm::dvec3& position, const glm::dvec3& direction, double outer_deg) {
    return lab::touches_cone(box, position, unit_or_down(direction), outer_deg + 1.0);  // a degree of margin
}
