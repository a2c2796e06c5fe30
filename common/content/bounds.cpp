#include "bounds.h"

#include <cmath>
#include <limits>

namespace lab {

Box Box::empty() {
    const double inf = std::numeric_limits<double>::infinity();
    return {glm::dvec3(inf), glm::dvec3(-inf)};
}

void Box::add(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
}

void Box::add(const Box& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
}

Box mesh_bounds(const Mesh& mesh) {
    if (mesh.vertices.empty()) return Box{};
    Box box = Box::empty();
    for (const Vertex& v : mesh.vertices) box.add(glm::dvec3(v.position));
    return box;
}

bool touches_cone(const Box& box, const glm::dvec3& apex, const glm::dvec3& axis, double half_angle_deg) {
    const double angle = glm::radians(half_angle_deg);
    if (angle >= glm::radians(89.0)) return true;
    const glm::dvec3 centre = 0.5 * (box.lo + box.hi);
    const double radius = 0.5 * glm::length(box.hi - box.lo);
    const glm::dvec3 v = centre - apex;
    if (glm::length(v) <= radius) return true;  // the apex is inside the sphere
    const double along = glm::dot(v, axis);
    const double across = glm::length(v - along * axis);
    // Signed distance from the sphere's centre to the cone's surface (positive outside).
    return along >= -radius && across * std::cos(angle) - along * std::sin(angle) <= radius;
}

Box transformed(const Box& box, const glm::dmat4& m) {
    Box out = Box::empty();
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 corner(i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y, i & 4 ? box.hi.z : box.lo.z);
        out.add(glm::dvec3(m * glm::dvec4(corner, 1.0)));
    }
    return out;
}

double far_depth(const Box& world_box, const glm::dmat4& view) {
    return -transformed(world_box, view).lo.z;  // the corner with the most negative view-space z
}

}  // namespace lab
