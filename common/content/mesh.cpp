// mesh.cpp — tangents from UVs, and the mesh a scene object names: make_mesh and
// MeshLibrary pick a primitive (primitives.cpp) or load an .obj (obj_model.cpp).
//
// Tangent convention (docs/meshes.md): tangent.xyz points along +u; the bitangent is
// B = tangent.w · cross(N, T) and points towards the image top (−v, like glTF and
// OpenGL-style normal maps). A texture that is not mirrored therefore has w = +1.
#include "mesh.h"

#include "obj_text.h"
#include "scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace lab {

// ---------------------------------------------------------------------------
// Tangent frames from UVs.
// ---------------------------------------------------------------------------
void compute_tangents(Mesh& mesh) {
    // Inside a triangle the position is linear in (u, v):
    //     P − P0 = (u − u0)·∂P/∂u + (v − v0)·∂P/∂v.
    // With edges e1 = P1 − P0, e2 = P2 − P0 and their UV differences
    // (du1, dv1), (du2, dv2) this is a 2×2 linear system; solving it gives
    //     ∂P/∂u = ( dv2·e1 − dv1·e2) / det,   ∂P/∂v = (−du2·e1 + du1·e2) / det,
    //     det = du1·dv2 − du2·dv1.
    // The tangent is the direction of ∂P/∂u; the "image up" direction is −∂P/∂v.
    // Each vertex averages the directions of its triangles weighted by their area,
    // then the tangent is made perpendicular to the normal (Gram–Schmidt) and
    // w records whether (T, cross(N, T)) matches image-up (+1) or is mirrored (−1).
    std::vector<glm::vec3> tsum(mesh.vertices.size(), glm::vec3(0.0f));
    std::vector<glm::vec3> usum(mesh.vertices.size(), glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
        const Vertex &v0 = mesh.vertices[i0], &v1 = mesh.vertices[i1], &v2 = mesh.vertices[i2];
        const glm::vec3 e1 = v1.position - v0.position, e2 = v2.position - v0.position;
        const glm::vec2 d1 = v1.uv - v0.uv, d2 = v2.uv - v0.uv;
        const float det = d1.x * d2.y - d2.x * d1.y;
        const float area = 0.5f * glm::length(glm::cross(e1, e2));
        if (std::abs(det) < 1e-12f || !(area > 0.0f)) continue;  // no usable UV mapping here
        const glm::vec3 dpdu = (d2.y * e1 - d1.y * e2) / det;
        const glm::vec3 dpdv = (-d2.x * e1 + d1.x * e2) / det;
        const float lu = glm::length(dpdu), lv = glm::length(dpdv);
        if (!(lu > 0.0f) || !(lv > 0.0f) || !std::isfinite(lu) || !std::isfinite(lv)) continue;
        for (uint32_t i : {i0, i1, i2}) {
            tsum[i] += area * dpdu / lu;
            usum[i] -= area * dpdv / lv;
        }
    }
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        Vertex& v = mesh.vertices[i];
        const glm::vec3 n = v.normal;
        glm::vec3 t = tsum[i] - n * glm::dot(n, tsum[i]);  // remove the part along the normal
        if (glm::length(t) < 1e-6f * glm::length(tsum[i]) || glm::length(t) < 1e-20f) {
            // No UVs here: any unit vector perpendicular to the normal will do.
            // Cross with the axis least aligned with n (never parallel to it).
            const glm::vec3 a = std::abs(n.x) < 0.6f ? glm::vec3(1, 0, 0)
                              : std::abs(n.y) < 0.6f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
            t = glm::cross(a, n);
        }
        t = glm::normalize(t);
        const float w = glm::dot(glm::cross(n, t), usum[i]) < 0.0f ? -1.0f : 1.0f;
        v.tangent = glm::vec4(t, w);
    }
}

Mesh make_mesh(const ObjectDesc& object) {
    MeshLibrary library;
    return library.mesh(object);
}

Mesh MeshLibrary::mesh(const ObjectDesc& object) {
    if (!object.mesh_path.empty()) {
        std::string ext = std::filesystem::path(object.mesh_path).extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        if (ext != ".obj") detail::fail(object.mesh_path, 0, "unsupported model format (only .obj)");
        // A model split into one object per .mtl material is read once. Its warnings were
        // printed when the scene loader split it; a whole model prints them here.
        const std::string key = object.mesh_path + "|" + std::to_string(object.crease_deg) + "|" +
                                std::to_string(object.normalize);
        auto it = models_.find(key);
        if (it == models_.end()) {
            const bool split = object.obj_material != ObjectDesc::kAllTriangles;
            auto model = std::make_shared<const LoadedModel>(
                load_obj(object.mesh_path, object.crease_deg, object.normalize, !split));
            it = models_.emplace(key, std::move(model)).first;
        }
        const LoadedModel& model = *it->second;
        if (object.obj_material == ObjectDesc::kAllTriangles) return model.mesh;
        if (object.obj_material < -1 || object.obj_material >= int(model.materials.size()))
            detail::fail(object.mesh_path, 0, "no material number " + std::to_string(object.obj_material));
        // Keep only the triangles of one .mtl material (see expand_model_materials in scene.cpp).
        Mesh part;
        part.vertices = model.mesh.vertices;
        for (size_t t = 0; t < model.triangle_material.size(); ++t)
            if (model.triangle_material[t] == object.obj_material)
                part.indices.insert(part.indices.end(), model.mesh.indices.begin() + long(3 * t),
                                    model.mesh.indices.begin() + long(3 * t + 3));
        return part;
    }
    // 0 = the primitive's default tessellation (see docs/meshes.md).
    const auto pick = [](int value, int fallback) { return value > 0 ? value : fallback; };
    const std::string& name = object.mesh;
    if (name == "plane") return make_plane();
    if (name == "cube") return make_cube();
    if (name == "sphere") return make_sphere(pick(object.segments, 32), pick(object.rings, 16));
    if (name == "icosahedron") return make_icosahedron();
    if (name == "icosphere") return make_icosphere(pick(object.segments, 2));
    if (name == "cylinder") return make_cylinder(pick(object.segments, 32), pick(object.rings, 1));
    if (name == "cone") return make_cone(pick(object.segments, 32), pick(object.rings, 1));
    if (name == "torus") return make_torus(pick(object.segments, 48), pick(object.rings, 16));
    throw std::runtime_error(name + ": unknown mesh (expected plane, cube, sphere, icosahedron, icosphere, "
                                    "cylinder, cone, torus or an .obj file)");
}

}  // namespace lab
