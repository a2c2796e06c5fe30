#include "caster_detail.h"

#include <algorithm>
#include <cmath>

namespace {
// The tessellation a scene object has (0 in the scene: the shape's default, mesh.cpp).
int own_segments(const lab::ObjectDesc& o) {
    if (o.segments > 0) return o.segments;
    return o.mesh == "torus" ? 48 : o.mesh == "icosphere" ? 2 : 32;
}
int own_rings(const lab::ObjectDesc& o) {
    if (o.rings > 0) return o.rings;
    return o.mesh == "torus" ? 16 : o.mesh == "sphere" ? 16 : 1;
}

// Distance from p (the shape's own units) to the true surface of `name`.
double distance_to(const std::string& name, const glm::dvec3& p) {
    const double radial = std::sqrt(p.x * p.x + p.z * p.z);
    if (name == "sphere" || name == "icosphere") return std::abs(glm::length(p) - 0.5);
    if (name == "torus") return std::abs(std::sqrt((radial - 0.35) * (radial - 0.35) + p.y * p.y) - 0.15);
    // Cylinder and cone (their side; a cap's triangles lie in its disc, see surface_error()): a
    // circle at each height (radius 0.5, or the cone's 0.25 − y / 2), straight along the height.
    const double rho = name == "cone" ? 0.25 - 0.5 * p.y : 0.5;
    return std::abs(radial - rho);
}
}  // namespace

std::vector<lab::ObjectDesc> coarser_levels(const lab::ObjectDesc& object) {
    const std::string& name = object.mesh;
    std::vector<lab::ObjectDesc> levels;
    if (!object.mesh_path.empty()) return levels;
    const bool sides_only = name == "cylinder" || name == "cone";  // bands along a straight side change no outline
    int fewest_segments = 3, fewest_rings = 1;
    if (name == "sphere") fewest_rings = 2;
    else if (name == "torus") fewest_rings = 3;
    else if (name == "icosphere") fewest_segments = 1;  // its subdivision level (0 would mean "the default")
    else if (!sides_only) return levels;                // plane, cube, icosahedron: nothing coarser
    const int s = own_segments(object), r = sides_only ? 1 : own_rings(object);
    int last_s = s, last_r = own_rings(object);
    for (int k = name == "icosphere" ? 1 : 0; k < 16; ++k) {
        lab::ObjectDesc level = object;
        level.segments = name == "icosphere" ? std::max(fewest_segments, s - k)
                                             : std::max(fewest_segments, (s + (1 << k) - 1) >> k);
        level.rings = name == "icosphere" ? 0 : std::max(fewest_rings, (r + (1 << k) - 1) >> k);
        if (level.segments == last_s && (name == "icosphere" || level.rings == last_r)) {
            if (level.segments == fewest_segments && level.rings <= fewest_rings) break;
            continue;  // k = 0 for a cylinder or cone with one band: its own mesh
        }
        last_s = level.segments;
        last_r = level.rings;
        levels.push_back(level);
    }
    return levels;
}

double surface_error(const std::string& name, const lab::Mesh& mesh) {
    constexpr int kGrid = 4;  // barycentric steps along each edge: corners, quarters of edges, inside
    double worst = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::dvec3 a(mesh.vertices[mesh.indices[t]].position), b(mesh.vertices[mesh.indices[t + 1]].position),
            c(mesh.vertices[mesh.indices[t + 2]].position);
        // A cylinder's or cone's cap: flat (one y), inside the true disc; its rim's error is the side's.
        if ((name == "cylinder" || name == "cone") && a.y == b.y && b.y == c.y) continue;
        for (int i = 0; i <= kGrid; ++i)
            for (int j = 0; i + j <= kGrid; ++j) {
                const double u = double(i) / kGrid, v = double(j) / kGrid;
                worst = std::max(worst, distance_to(name, a + u * (b - a) + v * (c - a)));
            }
        worst = std::max(worst, distance_to(name, (a + b + c) / 3.0));
    }
    return worst;
}

double half_texel(const LightFrustum& frustum, uint32_t used, const lab::Box& caster) {
    const double texel = frustum.texel / double(std::max(1u, used));
    if (!frustum.perspective) return 0.5 * texel;
    const glm::dvec3 nearest = glm::clamp(frustum.origin, caster.lo, caster.hi);
    const double r = glm::length(nearest - frustum.origin);
    const double t = 0.5 * frustum.texel;  // tan of the half field of view (a 1-texel map spans 2t at distance 1)
    return 0.5 * r * texel * std::sqrt(1.0 + t * t) / (1.0 + 2.0 * t * t);
}

size_t pick_level(const std::vector<double>& errors, double scale, double tolerance) {
    // Against the caster's own mesh (what the camera sees, and the reference): the level's
    // distance to the true surface plus the own mesh's.
    for (size_t k = errors.size(); k-- > 1;)
        if ((errors[k] + errors[0]) * scale <= tolerance) return k;
    return 0;
}
