// analytic.h — the exact shapes the built-in curved primitives approximate.
//
// A tessellated sphere is a polyhedron inscribed in the sphere of radius 0.5:
// what it *should* look like is the sphere itself. These functions intersect a
// ray with the exact surfaces of docs/meshes.md, in the primitive's own model
// space (size 1, centred at the origin):
//
//   sphere / icosphere  radius 0.5
//   cylinder            radius 0.5, y ∈ [−0.5, 0.5], flat caps at y = ±0.5
//   cone                apex (0, 0.5, 0), base radius 0.5 at y = −0.5, flat base cap
//   torus               around +Y in XZ, major radius R = 0.35, tube radius r = 0.15:
//                       (|p|² + R² − r²)² = 4R²(x² + z²), a quartic in the ray parameter
//
// Each returns the nearest hit with t in [t_min, t_max] whose outward normal
// faces the ray (dot(d, n) < 0, "front face", what back-face culling keeps);
// `facing = −1` asks for the inside instead (a mirrored model matrix flips the
// winding of the triangles, so the GPU then keeps the inner side).
//
// The ray is o + t·d with any non-zero d (not necessarily unit): t is returned
// in the units of d, so a world-space ray mapped into model space by the
// inverse model matrix keeps its parameter (the view depth).
#pragma once

#include <glm/glm.hpp>

#include <string>

namespace ref {

enum class Shape { None, Sphere, Cylinder, Cone, Torus };

// The exact shape behind a built-in mesh name ("sphere", "icosphere", ...);
// Shape::None for meshes that are exact already (plane, cube, icosahedron) or models.
Shape analytic_shape(const std::string& mesh_name);

struct ShapeHit {
    double t = 0.0;
    glm::dvec3 position{0.0};  // model space
    glm::dvec3 normal{0.0};    // model space, unit, outward
    glm::dvec3 tangent{0.0};   // model space, unit, along +u (docs/meshes.md)
    glm::dvec2 uv{0.0};        // the primitive's documented UV layout
    int part = 0;              // 0 = curved side, 1 = top cap, 2 = bottom cap
};

bool intersect_shape(Shape shape, const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max,
                     int facing, ShapeHit* hit);

// The pieces, exposed for the unit tests.
bool intersect_sphere(const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max, int facing,
                      ShapeHit* hit);
bool intersect_cylinder(const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max, int facing,
                        ShapeHit* hit);
bool intersect_cone(const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max, int facing,
                    ShapeHit* hit);
bool intersect_torus(const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max, int facing,
                     ShapeHit* hit);

// Real roots of c[0] + c[1]·x + … + c[n]·xⁿ (n ≤ 4, c[n] ≠ 0) in [lo, hi], ascending.
// Root isolation by the derivatives (between two neighbouring roots of p′ the
// polynomial is monotonic, so a sign change brackets exactly one root, found by
// bisection to full precision). A double root (a ray grazing a surface) shows as
// a derivative root where p is zero or changes sign; it is reported once.
// Returns the number of roots written to roots[] (at most n).
int polynomial_roots(const double* c, int n, double lo, double hi, double* roots);

}  // namespace ref
