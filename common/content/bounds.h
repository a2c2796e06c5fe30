// bounds.h — axis-aligned bounding boxes in double precision: around a mesh, moved by a
// transform, grown to hold more, how far one reaches from the eye (every lab draws the nearest
// objects first), against a cone (lab 4 fits its shadow maps to the objects' boxes and skips the
// objects outside a spot light's cone).
#pragma once

#include "mesh.h"

#include <glm/glm.hpp>

namespace lab {

struct Box {
    glm::dvec3 lo{0.0};
    glm::dvec3 hi{0.0};

    // lo = +∞, hi = −∞: holds nothing, and grows to exactly the first point or box added.
    static Box empty();
    void add(const glm::dvec3& p);
    void add(const Box& b);
};

// The box around a mesh's vertex positions (a mesh without vertices: the point box at the origin).
Box mesh_bounds(const Mesh& mesh);
// The box around `box`'s eight corners moved by `m` (an affine transform, e.g. a model or view matrix).
Box transformed(const Box& box, const glm::dmat4& m);

// How far in front of the camera a world-space box reaches: the largest view-space depth (−z, the
// camera looks down −z) of its eight corners. Its order is a draw order: nearest first, and what
// reaches far back (a floor, the walls of a room) last.
double far_depth(const Box& world_box, const glm::dmat4& view);

// Can a point of `box` lie inside the cone from `apex` along the unit vector `axis` with the given
// half-angle? Tested with the box's bounding sphere: false is certain, true may not be. A
// half-angle of 89° or more counts as everything (the test below needs a cone narrower than 90°).
bool touches_cone(const Box& box, const glm::dvec3& apex, const glm::dvec3& axis, double half_angle_deg);

}  // namespace lab
