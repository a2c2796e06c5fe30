// mesh.h — CPU-side triangle meshes: the Vertex/Mesh types, tangents from UVs, and the
// mesh a scene object names (a built-in primitive or an .obj file).
//
// Every mesh is indexed, counter-clockwise when seen from outside (the front
// face), in its own model space. The CPU reference renderer in tests/ ray-casts
// exactly these triangles, so the GPU and the oracle see the same geometry.
//
// The shapes themselves are in primitives.h, the OBJ loader in obj_model.h; both are
// included at the end of this file, so "mesh.h" alone still gives everything.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace lab {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
    glm::vec4 tangent;  // xyz = tangent along +u, w = bitangent sign
};

struct Mesh {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  // 3 per triangle
};

// Recomputes every vertex tangent from the UVs (tangent.xyz along +u, w = handedness,
// see docs/meshes.md); vertices without usable UVs get any unit vector ⟂ normal.
void compute_tangents(Mesh& mesh);

struct ObjectDesc;
struct LoadedModel;  // obj_model.h

// The mesh an object names: a primitive name ("plane", "cube", "sphere",
// "icosahedron", "icosphere", "cylinder", "cone", "torus"; segments / rings of
// 0 pick the defaults) or, when mesh_path is set, an .obj file. Throws
// std::runtime_error with a one-line message for unknown names / bad files.
Mesh make_mesh(const ObjectDesc& object);

// The same, for all objects of one scene: each model file is read once, however many
// objects (or .mtl material parts) use it. Keep one for one scene build, then drop it.
class MeshLibrary {
public:
    Mesh mesh(const ObjectDesc& object);

private:
    // [path | crease | normalize]. Held by pointer so that this header needs only the
    // declaration of LoadedModel (obj_model.h itself includes this header for Mesh).
    std::map<std::string, std::shared_ptr<const LoadedModel>> models_;
};

}  // namespace lab

// After Mesh is defined: both need it, and callers that include only "mesh.h" use them.
#include "obj_model.h"   // load_obj, LoadedModel, ObjMaterial
#include "primitives.h"  // make_plane, make_cube, make_sphere, ...
