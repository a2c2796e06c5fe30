// obj_model.h — Wavefront OBJ models (+ their .mtl materials), read with tinyobjloader
// (docs/meshes.md: what is accepted, how normals, crease angle and tangents are made).
#pragma once

#include "mesh.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace lab {

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

}  // namespace lab
