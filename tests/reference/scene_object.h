// scene_object.h — the one helper the CPU-reference tests build scene objects with.
//
// The arguments come in the order of the model matrix, T · R · S (lab::model_matrix in
// common/content/scene.cpp, ref::model_matrix here): position, then rotation, then scale — so a
// call reads like the matrix it makes, and every test passes its vectors in the same places.
#pragma once

#include "scene.h"

#include <glm/glm.hpp>

#include <string>

namespace ref {

// An object of `mesh` ("plane", "cube", "sphere", ...) with `material`, scaled by `scale`, then
// rotated by `rotation_deg` (about X, then Y, then Z, as in a scene file), then moved to `position`.
inline lab::ObjectDesc object(const std::string& mesh, const std::string& material, glm::vec3 position,
                              glm::vec3 rotation_deg = glm::vec3(0.0f), glm::vec3 scale = glm::vec3(1.0f)) {
    lab::ObjectDesc o;
    o.mesh = mesh;
    o.material = material;
    o.position = position;
    o.rotation_deg = rotation_deg;
    o.scale = scale;
    return o;
}

}  // namespace ref
