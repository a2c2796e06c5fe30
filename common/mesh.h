// mesh.h — CPU-side triangle meshes and the built-in primitives.
//
// Every mesh is indexed, counter-clockwise when seen from outside (the front
// face), in its own model space. The CPU reference renderer in tests/ ray-casts
// exactly these triangles, so the GPU and the oracle see the same geometry.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
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
Mesh make_sphere(int segments = 48, int rings = 24);

struct ObjectDesc;
// The mesh an object names: a primitive name or a model file. Throws
// std::runtime_error with a one-line message for unknown names / bad files.
Mesh make_mesh(const ObjectDesc& object);

}  // namespace lab
