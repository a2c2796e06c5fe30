// ideal.h — the ground truth a tessellation approximates: the scene with its curved
// primitives replaced by their exact surfaces (reference/analytic.h).
//
// Spheres, icospheres, cylinders, cones and tori are intersected analytically in
// their model space (the world ray mapped by the inverse model matrix, so the ray
// parameter stays the view depth) and carry their exact normals; the plane, the
// cube and the icosahedron are exact as triangles, and OBJ models stay triangles
// (there is nothing more exact to compare them with). Used by `lab_reference
// --ideal` and the time-against-error sweeps (bench/tradeoff.py).
#pragma once

#include "reference/analytic.h"
#include "reference/cpu_reference.h"

#include <memory>
#include <vector>

namespace ref {

class IdealGeometry {
public:
    explicit IdealGeometry(const lab::Scene& scene);
    ~IdealGeometry();
    IdealGeometry(const IdealGeometry&) = delete;
    IdealGeometry& operator=(const IdealGeometry&) = delete;

    // Nearest front-facing hit with t (view depth) in [t_min, t_max], over the exact
    // shapes and the remaining triangles. Analytic hits set Hit::analytic and Hit::tangent.
    bool trace(const Ray& ray, double t_min, double t_max, Hit* hit) const;

    TraceFn tracer() const;

private:
    struct Object {
        int object_id;
        Shape shape;
        glm::dmat4 model, inverse;
        glm::dmat3 normal_matrix;
        int facing;  // −1 when the model matrix mirrors (negative determinant): the inside shows
    };
    std::vector<Object> shapes_;
    std::vector<int> triangle_object_ids_;        // triangles_'s object index → the scene's
    std::unique_ptr<lab::Scene> triangle_scene_;  // the objects that stay triangles
    std::unique_ptr<SceneGeometry> triangles_;
};

// Lab 2's lighting at the ideal surface: per pixel, with the exact normal (and tangent) on the
// analytic shapes and the interpolated normal on triangles, whatever scene.lighting.shading says
// — the truth flat and Gouraud shading approximate. `scene` must be the one traced.
ShadeFn make_ideal_lighting_shader(const lab::Scene& scene);

}  // namespace ref
