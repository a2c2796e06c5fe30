#include "map_footprint.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace {
constexpr int kColumns = 33, kRows = 19;  // the grid of rays: every 40 pixels of a 1280×720 picture

glm::dvec3 unproject(const glm::dmat4& clip_to_world, const glm::dvec3& ndc) {
    const glm::dvec4 p = clip_to_world * glm::dvec4(ndc, 1.0);
    return glm::dvec3(p) / p.w;
}

// A map's view: (world − origin) → clip, and back.
struct MapView {
    glm::dmat4 relative, back;
};

// The width of one texel at world point `p` of a map of one texel (2 units of normalized device
// coordinates) through `view`; 0 when p is outside the map.
double texel_at(const MapView& view, const glm::dvec3& origin, const glm::dvec3& p) {
    const glm::dvec4 clip = view.relative * glm::dvec4(p - origin, 1.0);
    if (!(clip.w > 0.0)) return 0.0;
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    if (std::abs(ndc.x) > 1.0 || std::abs(ndc.y) > 1.0) return 0.0;
    // A step of h across the map, scaled to the whole map's 2: exact for an orthographic map, the
    // local width for a perspective one.
    constexpr double h = 1e-3;
    return glm::length(unproject(view.back, ndc + glm::dvec3(h, 0.0, 0.0)) - unproject(view.back, ndc)) * (2.0 / h);
}
}  // namespace

std::vector<ViewSample> sample_view(const glm::dmat4& world_to_clip, uint32_t width, uint32_t height,
                                    const std::vector<Box>& receivers) {
    std::vector<ViewSample> samples;
    if (width == 0 || height == 0) return samples;
    const glm::dmat4 back = glm::inverse(world_to_clip);
    for (int row = 0; row < kRows; ++row) {
        for (int column = 0; column < kColumns; ++column) {
            // Pixel centres from the first to the last, in normalized device coordinates.
            const double x = (0.5 + (width - 1.0) * column / (kColumns - 1.0)) / width * 2.0 - 1.0;
            const double y = (0.5 + (height - 1.0) * row / (kRows - 1.0)) / height * 2.0 - 1.0;
            const glm::dvec3 near = unproject(back, {x, y, 0.0}), far = unproject(back, {x, y, 1.0});
            double t = std::numeric_limits<double>::infinity();
            int hit = -1;
            for (size_t i = 0; i < receivers.size(); ++i)
                if (const double e = ray_entry(near, far - near, receivers[i], 1.0); e >= 0.0 && e < t) {
                    t = e;
                    hit = int(i);
                }
            if (!std::isfinite(t)) continue;
            const glm::dvec3 p = near + (far - near) * t;
            // One pixel up at p's depth: its width there.
            const glm::dvec4 clip = world_to_clip * glm::dvec4(p, 1.0);
            const double depth = clip.z / clip.w;
            const double pixel = glm::length(unproject(back, {x, y + 2.0 / height, depth}) - p);
            // The pixels half way to the next samples, if they show the same surface.
            const double reach = pixel * 0.5 * std::hypot((width - 1.0) / (kColumns - 1.0), (height - 1.0) / (kRows - 1.0));
            if (pixel > 0.0 && std::isfinite(pixel)) samples.push_back({p, pixel, reach, hit});
        }
    }
    return samples;
}

double texels_needed(const LightFrustum& f, const std::vector<ViewSample>& samples,
                     const std::vector<FootprintCaster>& casters, const glm::dvec3& light, bool directional) {
    std::vector<MapView> views;  // the 2D map, or the cube's six faces
    for (size_t k = 0; k < (f.cube ? f.faces.size() : 1); ++k) {
        const glm::dmat4& m = f.cube ? f.faces[k] : f.view_projection;
        views.push_back({m, glm::inverse(m)});
    }
    double most = 0.0;
    for (const ViewSample& s : samples) {
        // Can a caster shadow this sample, or a pixel within its reach? (A ray to the light that
        // passes within `reach` of a box meets the box grown by reach: for a point light the rays
        // from two points `reach` apart are nowhere farther apart than that.)
        const bool shadowed = std::any_of(casters.begin(), casters.end(), [&](const FootprintCaster& c) {
            if (c.receiver == s.receiver && !c.shadows_itself) return false;
            const Box grown{c.box.lo - s.reach, c.box.hi + s.reach};
            return directional ? ray_entry(s.point, -light, grown, std::numeric_limits<double>::infinity()) >= 0.0
                               : ray_entry(light, s.point - light, grown, 1.0) >= 0.0;
        });
        if (!shadowed) continue;
        double texel = 0.0;  // a cube: the face whose view holds the point (on an edge between two, the wider texel)
        for (const MapView& view : views) texel = std::max(texel, texel_at(view, f.origin, s.point));
        most = std::max(most, texel / s.pixel);
    }
    return kTexelsPerPixel * most;
}

uint32_t footprint_resolution(double texels, uint32_t resolution, uint32_t drawn) {
    if (drawn > 0 && drawn <= resolution && texels <= drawn && texels > drawn / std::sqrt(2.0)) return drawn;
    uint32_t size = resolution;  // down the quarter octaves while the next one still holds the texels
    for (int k = 1;; ++k) {
        const uint32_t next = std::max(kFewestTexels, 8 * uint32_t(std::ceil(resolution * std::exp2(-0.25 * k) / 8.0)));
        if (next >= size || next < texels) break;
        size = next;
    }
    return std::min(size, resolution);
}
