// mesh.h — CPU-side triangle meshes and the built-in primitives.
//
// Every mesh is indexed, counter-clockwise when seen from outside (the front
// face), in its own model space. The CPU reference renderer in tests/ ray-casts
// exactly these triangles, so the GPU and the oracle see the same geometry.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
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

// Recomputes every vertex tangent from the UVs (tangent.xyz along +u, w = handedness,
// see docs/meshes.md); vertices without usable UVs get any unit vector ⟂ normal.
void compute_tangents(Mesh& mesh);

// --- Wavefront OBJ models (loaded with tinyobjloader, see docs/meshes.md) ---

// One `newmtl` of the model's .mtl file.
struct ObjMaterial {
    std::string name;
    glm::vec3 albedo{0.8f};     // Kd
    glm::vec3 specular{0.0f};   // Ks
    glm::vec3 emissive{0.0f};   // Ke
    float shininess = 32.0f;    // Ns, clamped to [1, 1000]
    std::string albedo_texture;   // map_Kd resolved to a path ("" = none or file missing)
    std::string specular_texture; // map_Ks (the same)
    std::string emissive_texture; // map_Ke (the same)
};

struct LoadedModel {
    Mesh mesh;
    std::vector<ObjMaterial> materials;
    // Per triangle (indices.size() / 3 entries): index into `materials`, or −1 = none
    // (use the object's scene material).
    std::vector<int> triangle_material;
    std::vector<std::string> warnings;  // also printed to stderr as "warning: FILE: reason"
};

// Loads a .obj (+ its .mtl). Missing normals are computed with smooth shading
// except across edges sharper than `crease_deg`; `normalize` fits the model into a
// unit box (largest extent 1) centered at the origin. OBJ texture coordinates are
// flipped (v' = 1 − v) to the top-left origin used everywhere here.
// Throws std::runtime_error with one line "FILE[:LINE]: reason".
LoadedModel load_obj(const std::string& path, float crease_deg = 60.0f, bool normalize = false,
                     bool print_warnings = true);

struct ObjectDesc;
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
    std::map<std::string, LoadedModel> models_;  // [path | crease | normalize]
};

}  // namespace lab
