// image_compare.cpp — GPU PNG vs CPU reference (see image_compare.h).
#include "reference/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace ref {

std::vector<uint8_t> edge_mask(const RefImage& reference, const CompareOptions& options) {
    const int w = reference.width, h = reference.height;
    std::vector<uint8_t> mask(static_cast<size_t>(w) * h, 0);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const size_t i = static_cast<size_t>(y) * w + x;
            bool edge = false;
            // Any neighbour (3×3, clipped at the image border) seeing another object?
            for (int dy = -1; dy <= 1 && !edge; ++dy) {
                for (int dx = -1; dx <= 1 && !edge; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                    const size_t j = static_cast<size_t>(ny) * w + nx;
                    if (reference.object_id[j] != reference.object_id[i]) edge = true;
                    if (options.triangle_edges &&
                        reference.triangle_id[j] != reference.triangle_id[i])
                        edge = true;
                }
            }
            if (!edge && options.grazing_cos > 0.0 && i < reference.hits.size() &&
                reference.hits[i].hit) {
                const Hit& hit = reference.hits[i];
                const double c = std::abs(glm::dot(hit.geometric_normal, hit.view_dir));
                if (c < options.grazing_cos) edge = true;
            }
            mask[i] = edge ? 1 : 0;
        }
    }
    return mask;
}

bool CompareResult::passed() const {
    return !size_mismatch && max_diff_interior <= tolerance &&
           fraction_differing <= max_fraction_allowed;
}

std::string CompareResult::describe() const {
    std::ostringstream s;
    if (size_mismatch) {
        s << "image size differs from the reference (" << width << "x" << height << " expected)";
        return s.str();
    }
    const size_t total = static_cast<size_t>(width) * height;
    s << (passed() ? "PASS" : "FAIL") << " " << width << "x" << height << ", tolerance "
      << tolerance << "/255\n";
    s << "  away from edges: max |diff| = " << max_diff_interior << "/255 ("
      << interior_differing << " pixels beyond tolerance)";
    if (worst_x >= 0) {
        s << ", worst at (" << worst_x << ", " << worst_y << "): expected rgba("
          << int(worst_expected[0]) << "," << int(worst_expected[1]) << ","
          << int(worst_expected[2]) << "," << int(worst_expected[3]) << ") got rgba("
          << int(worst_actual[0]) << "," << int(worst_actual[1]) << "," << int(worst_actual[2])
          << "," << int(worst_actual[3]) << ")";
    }
    s << "\n  everywhere: max |diff| = " << max_diff_all << "/255, " << differing_pixels << " of "
      << total << " pixels differ (" << 100.0 * fraction_differing << "%, allowed "
      << 100.0 * max_fraction_allowed << "%); edge mask " << edge_pixels << " pixels";
    if (!diff_image.empty()) s << "\n  diff image: " << diff_image;
    return s.str();
}

CompareResult compare_images(const lab::Image8& actual, const RefImage& reference,
                             const CompareOptions& options) {
    CompareResult r;
    r.width = reference.width;
    r.height = reference.height;
    r.tolerance = options.tolerance;
    r.max_fraction_allowed = options.max_fraction_differing;
    const size_t total = static_cast<size_t>(reference.width) * reference.height;
    if (actual.width != reference.width || actual.height != reference.height ||
        actual.rgba.size() != total * 4) {
        r.size_mismatch = true;
        return r;
    }
    const lab::Image8 expected = encode_srgb(reference);
    r.edge_mask = edge_mask(reference, options);
    for (size_t i = 0; i < total; ++i) {
        int diff = 0;
        for (int ch = 0; ch < 4; ++ch)
            diff = std::max(diff, std::abs(int(actual.rgba[4 * i + ch]) -
                                           int(expected.rgba[4 * i + ch])));
        const bool edge = r.edge_mask[i] != 0;
        if (edge) ++r.edge_pixels;
        r.max_diff_all = std::max(r.max_diff_all, diff);
        if (diff > options.tolerance) ++r.differing_pixels;
        if (!edge) {
            if (diff > options.tolerance) ++r.interior_differing;
            if (diff > r.max_diff_interior) {
                r.max_diff_interior = diff;
                r.worst_x = static_cast<int>(i % reference.width);
                r.worst_y = static_cast<int>(i / reference.width);
                for (int ch = 0; ch < 4; ++ch) {
                    r.worst_expected[ch] = expected.rgba[4 * i + ch];
                    r.worst_actual[ch] = actual.rgba[4 * i + ch];
                }
            }
        }
    }
    r.fraction_differing = total ? static_cast<double>(r.differing_pixels) / total : 0.0;
    return r;
}

void write_diff_png(const std::string& path, const lab::Image8& actual, const RefImage& reference,
                    const CompareResult& result) {
    const int w = reference.width, h = reference.height;
    const lab::Image8 expected = encode_srgb(reference);
    const bool same_size = !result.size_mismatch && actual.width == w && actual.height == h;
    std::vector<uint8_t> mask = result.edge_mask;
    if (mask.size() != static_cast<size_t>(w) * h) mask = edge_mask(reference);

    lab::Image8 out;
    out.width = 3 * w;
    out.height = h;
    out.rgba.assign(static_cast<size_t>(out.width) * h * 4, 0);
    auto put = [&](int x, int y, uint8_t r, uint8_t g, uint8_t b) {
        uint8_t* p = &out.rgba[(static_cast<size_t>(y) * out.width + x) * 4];
        p[0] = r;
        p[1] = g;
        p[2] = b;
        p[3] = 255;
    };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const size_t i = static_cast<size_t>(y) * w + x;
            const uint8_t* e = &expected.rgba[4 * i];
            put(x, y, e[0], e[1], e[2]);
            if (!same_size) continue;
            const uint8_t* a = &actual.rgba[4 * i];
            put(w + x, y, a[0], a[1], a[2]);
            int diff = 0;
            for (int ch = 0; ch < 4; ++ch) diff = std::max(diff, std::abs(int(a[ch]) - int(e[ch])));
            const bool edge = mask[i] != 0;
            if (diff == 0) {
                put(2 * w + x, y, 0, 0, 0);
            } else if (edge) {
                if (diff > result.tolerance) put(2 * w + x, y, 255, 220, 0);
                else put(2 * w + x, y, 0, 0, 110);
            } else if (diff > result.tolerance) {
                put(2 * w + x, y, static_cast<uint8_t>(std::min(255, 128 + 4 * diff)), 0, 0);
            } else {
                put(2 * w + x, y, 90, 0, 0);
            }
            if (diff == 0 && edge) put(2 * w + x, y, 0, 0, 40);
        }
    }
    lab::write_png(path, out);
}

CompareResult compare_and_report(const lab::Image8& actual, const RefImage& reference,
                                 const std::string& diff_path, const CompareOptions& options) {
    CompareResult r = compare_images(actual, reference, options);
    if (!r.passed() && !diff_path.empty()) {
        std::error_code ec;
        const std::filesystem::path parent = std::filesystem::path(diff_path).parent_path();
        if (!parent.empty()) std::filesystem::create_directories(parent, ec);
        try {
            write_diff_png(diff_path, actual, reference, r);
            r.diff_image = diff_path;
        } catch (const std::exception& e) {
            r.diff_image = std::string("(could not write ") + diff_path + ": " + e.what() + ")";
        }
    }
    return r;
}

}  // namespace ref
