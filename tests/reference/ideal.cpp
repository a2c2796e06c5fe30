// ideal.cpp — exact curved primitives for the reference (see ideal.h).
#include "reference/ideal.h"

#include "reference/cpu_lighting.h"

#include <stdexcept>

namespace ref {

IdealGeometry::IdealGeometry(const lab::Scene& scene) : triangle_scene_(std::make_unique<lab::Scene>(scene)) {
    triangle_scene_->objects.clear();
    for (size_t o = 0; o < scene.objects.size(); ++o) {
        const lab::ObjectDesc& object = scene.objects[o];
        const Shape shape = object.mesh_path.empty() ? analytic_shape(object.mesh) : Shape::None;
        if (shape == Shape::None) {
            triangle_scene_->objects.push_back(object);
            triangle_object_ids_.push_back(static_cast<int>(o));
            continue;
        }
        Object s;
        s.object_id = static_cast<int>(o);
        s.shape = shape;
        s.model = ref::model_matrix(object);
        const double det = glm::determinant(glm::dmat3(s.model));
        if (det == 0.0) continue;  // a flat (zero-scale) object shows nothing, like its triangles
        s.inverse = glm::inverse(s.model);
        s.normal_matrix = glm::transpose(glm::inverse(glm::dmat3(s.model)));
        s.facing = det > 0.0 ? 1 : -1;
        shapes_.push_back(s);
    }
    triangles_ = std::make_unique<SceneGeometry>(*triangle_scene_);
}

IdealGeometry::~IdealGeometry() = default;

bool IdealGeometry::trace(const Ray& ray, double t_min, double t_max, Hit* out) const {
    Hit best;
    double best_t = t_max;
    if (triangles_->triangle_count() > 0 && triangles_->trace(ray, t_min, best_t, &best)) {
        best.object_id = triangle_object_ids_[static_cast<size_t>(best.object_id)];
        best_t = best.depth;
    }
    for (const Object& s : shapes_) {
        // The model-space ray: the same points, so the same parameter t (the view depth).
        const glm::dvec3 o(s.inverse * glm::dvec4(ray.origin, 1.0));
        const glm::dvec3 d(s.inverse * glm::dvec4(ray.dir, 0.0));
        ShapeHit h;
        if (!intersect_shape(s.shape, o, d, t_min, best_t, s.facing, &h)) continue;
        // Ties go to the lower object index, like the triangle tracer.
        if (best.hit && h.t == best_t && best.object_id < s.object_id) continue;
        best = Hit{};
        best.hit = true;
        best.analytic = true;
        best.object_id = s.object_id;
        best.triangle_id = h.part;
        best.depth = h.t;
        best.position = ray.origin + h.t * ray.dir;
        best.normal = glm::normalize(s.normal_matrix * h.normal);
        best.geometric_normal = best.normal;
        best.uv = h.uv;
        best.tangent = glm::normalize(glm::dmat3(s.model) * h.tangent);
        best_t = h.t;
    }
    if (best.hit && out) *out = best;
    return best.hit;
}

TraceFn IdealGeometry::tracer() const {
    return [this](const Ray& ray, double t_min, double t_max, Hit* hit) { return trace(ray, t_min, t_max, hit); };
}

ShadeFn make_ideal_lighting_shader(const lab::Scene& scene) {
    // Triangles (plane, cube, icosahedron, models): per-pixel shading with their own normals.
    const ShadeFn triangles = make_lighting_shader(scene, lab::LightingDesc::Shading::Phong);
    const glm::dvec3 eye = make_camera(scene.camera).eye;
    return [triangles, eye](const lab::Scene& s, const Hit& hit) -> glm::dvec3 {
        if (!hit.hit || !hit.analytic) return triangles(s, hit);
        const auto it = s.materials.find(hit.material);
        if (it == s.materials.end()) throw std::runtime_error("ideal: unknown material '" + hit.material + "'");
        const glm::dvec3 to_eye = eye - hit.position;
        const glm::dvec3 V = glm::length(to_eye) > 0.0 ? glm::normalize(to_eye) : hit.normal;
        return shade_point(s, it->second, hit.position, hit.normal, V, hit.tangent);
    };
}

}  // namespace ref
