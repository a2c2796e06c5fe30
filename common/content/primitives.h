// primitives.h — the built-in shapes a scene names by "mesh" (docs/meshes.md has their
// dimensions, default tessellations and UV layouts). All are centred at the origin and fit
// in [−0.5, 0.5]³.
#pragma once

#include "mesh.h"

namespace lab {

// 1×1 in XZ at y = 0, centered, normal +Y.
Mesh make_plane();
// Side 1, centered; per-face normals (24 vertices).
Mesh make_cube();
// Radius 0.5, centered; UV sphere with `segments` around Y and `rings` pole to pole.
Mesh make_sphere(int segments = 32, int rings = 16);
// Regular icosahedron, circumradius 0.5, 20 flat faces (60 vertices).
Mesh make_icosahedron();
// Icosahedron subdivided `level` times (each level splits every triangle into 4:
// 20·4^level triangles), projected onto the sphere of radius 0.5, smooth normals.
// level is clamped to 0..7.
Mesh make_icosphere(int level = 2);
// Radius 0.5, height 1 along Y (y ∈ [−0.5, 0.5]), capped; `rings` = bands along the height.
Mesh make_cylinder(int segments = 32, int rings = 1);
// Base radius 0.5 at y = −0.5, apex at y = +0.5, capped; `rings` = bands along the height.
Mesh make_cone(int segments = 32, int rings = 1);
// In the XZ plane around +Y: major radius 0.35, minor (tube) radius 0.15.
// `segments` around Y, `rings` around the tube.
Mesh make_torus(int segments = 48, int rings = 16);

}  // namespace lab
