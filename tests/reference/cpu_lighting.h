// cpu_lighting.h — lab 2's lighting equation in double precision, for the CPU reference.
//
// Written from docs/lighting.md, not from the shaders: the same equation, the same
// documented numerical-safety rules, independent code. make_lighting_shader() returns a
// ShadeFn for ref::render_reference() that evaluates the scene's shading model:
//   * Phong (per pixel): the equation at the hit point with the interpolated normal;
//   * flat: the equation at the hit point with the triangle's geometric normal;
//   * Gouraud: the equation at the triangle's three vertices, interpolated with the hit's
//     barycentric weights (world-space barycentrics = the GPU's perspective-correct ones).
#pragma once

#include "reference/cpu_reference.h"

#include <glm/glm.hpp>

#include <functional>
#include <memory>

namespace ref {

// --- the pieces (unit-tested against hand calculation) ---

// A point or spot light's falloff at distance d with the scene's coefficients k (docs/lighting.md,
// "attenuation"), with its documented numerical-safety rule.
double attenuation(const glm::dvec3& k, double d);

// The spot cone factor for cos_theta = cos(angle between the spot axis and the ray to the point),
// for either falloff docs/lighting.md defines (smooth, and the seeds' edge), hard edges included.
double spot_factor(double inner_deg, double outer_deg, lab::LightingDesc::SpotFalloff falloff, double cos_theta);
// The same factor from the pair lab 2's lights.cpp packs for the shader (spot_cone): `cone` as
// that file's comment defines it. The lab's packing test compares the two.
double packed_spot_factor(const glm::dvec2& cone, double cos_theta);

// The matrix that takes object-space normals to world space for `model` (normals stay
// perpendicular to their surfaces under non-uniform scale).
glm::dmat3 normal_matrix(const glm::dmat4& model);

// The equation at one surface point: emissive + ambient·albedo + Σ radiance·reflectance.
// N and V unit; tangent = the interpolated world tangent (only Ward uses it). Sets *bad when an
// intermediate is NaN or infinite (it never should be).
// Lab 4: `visibility`, if given, is called for every light with cast_shadows that reaches the point
// (reflectance > 0) and returns the fraction of its light that arrives (cpu_shadow.h).
using LightVisibility = std::function<double(const lab::LightDesc& light)>;
glm::dvec3 shade_point(const lab::Scene& scene, const lab::MaterialDesc& material, const glm::dvec3& P,
                       const glm::dvec3& N, const glm::dvec3& V, const glm::dvec3& tangent, bool* bad = nullptr,
                       const LightVisibility* visibility = nullptr);

// A ShadeFn for the scene's lighting model and shading model (scene.lighting). It keeps
// the scene's meshes for vertex normals and tangents; it is safe to call from many threads.
ShadeFn make_lighting_shader(const lab::Scene& scene);

// A ShadeFn like make_lighting_shader() but with another shading model (for the
// "flat / Gouraud vs per-pixel Phong" comparison).
ShadeFn make_lighting_shader(const lab::Scene& scene, lab::LightingDesc::Shading shading);

// A number that changes wherever the reference picture has a *designed* discontinuity at
// the hit: toon band and highlight thresholds, hard spot edges, the N·L = 0 terminator of
// a specular highlight. Tests put it into RefImage::object_id so the edge mask also covers
// those lines (a float GPU and a double reference may round them to different sides).
int discontinuity_key(const lab::Scene& scene, const Hit& hit);

}  // namespace ref
