// caster_detail.h — casters at the detail the map resolves (README "Casters at the detail the map
// resolves"). A map texel covers a patch of the caster; an outline that moves by less than half a
// texel changes no texel's depth test by more than its own rounding. So the shadow pass may draw a
// built-in shape with fewer segments and rings than the camera's pass, as long as the coarser
// mesh stays within half a texel of the true surface at the caster's distance from the light.
// On lavapipe the map pays for every triangle (vertex work and binning): swlike's map costs
// 27.9 ms with its spheres and torus at 128 × 64, 7.7 ms at 32 × 16 (docs/performance.md).
//
// The levels are made once, when the scene is loaded (coarser_levels(), surface_error()); each map
// render picks one per caster (pick_level() with half_texel()): arithmetic, no new meshes.
#pragma once

#include "light_frustum.h"
#include "mesh.h"
#include "scene.h"

#include <cstdint>
#include <vector>

// The tessellations of `object` (a built-in shape with segments and rings: sphere, torus,
// cylinder, cone, icosphere) that the shadow pass may draw instead of its own: segments (an
// icosphere's level) and rings halved, step by step, down to the fewest the shape allows. Its own
// tessellation is not among them. Other meshes (plane, cube, icosahedron, OBJ models): none.
std::vector<lab::ObjectDesc> coarser_levels(const lab::ObjectDesc& object);

// The largest distance, in the shape's own units (it fits in [−0.5, 0.5]³), between `mesh`'s
// triangles and the true surface of the built-in shape `name`: sampled on each triangle at its
// corners and on a barycentric grid inside (the deepest point of a chord, an edge's middle or a
// face's centre, is among them for these tessellations).
double surface_error(const std::string& name, const lab::Mesh& mesh);

// Half the world size of the map's smallest texel at `caster`, for a map drawn with `used`
// texels per side: a directional map's texels are all alike (frustum.texel / used); a perspective
// map's texel at distance r spans r × its angle, and that angle is smallest at the map's corners
// (a texel at image-plane offset (t, t), t = tan of the half field of view, subtends
// √(1 + t²) / (1 + 2t²) of the centre's: 0.47 on a cube face), at the caster's nearest point.
double half_texel(const LightFrustum& frustum, uint32_t used, const lab::Box& caster);

// The coarsest level that holds: errors[k] (object units) × scale ≤ tolerance, errors[0] being
// the caster's own mesh, always allowed. Returns the index into errors.
size_t pick_level(const std::vector<double>& errors, double scale, double tolerance);
