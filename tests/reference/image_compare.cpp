// image_compare.cpp — GPU PNG vs CPU reference (see image_compare.h).
#include "reference/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
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

// ---------------------------------------------------------------------------
// Error figures
// ---------------------------------------------------------------------------

glm::dvec3 srgb8_to_lab(const uint8_t rgb[3]) {
    const double r = srgb_decode(rgb[0] / 255.0), g = srgb_decode(rgb[1] / 255.0), b = srgb_decode(rgb[2] / 255.0);
    // Linear sRGB → XYZ (IEC 61966-2-1, D65), divided by the white point.
    const double X = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
    const double Y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    const double Z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
    auto f = [](double t) {
        const double e = 216.0 / 24389.0, k = 24389.0 / 27.0;
        return t > e ? std::cbrt(t) : (k * t + 16.0) / 116.0;
    };
    const double fx = f(X), fy = f(Y), fz = f(Z);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double ciede2000(const glm::dvec3& lab1, const glm::dvec3& lab2) {
    constexpr double kPi = 3.14159265358979323846;
    const double deg = kPi / 180.0;
    const double L1 = lab1.x, a1 = lab1.y, b1 = lab1.z, L2 = lab2.x, a2 = lab2.y, b2 = lab2.z;
    const double C1 = std::hypot(a1, b1), C2 = std::hypot(a2, b2);
    const double Cm = 0.5 * (C1 + C2);
    const double Cm7 = std::pow(Cm, 7.0);
    const double G = 0.5 * (1.0 - std::sqrt(Cm7 / (Cm7 + std::pow(25.0, 7.0))));
    const double a1p = (1.0 + G) * a1, a2p = (1.0 + G) * a2;
    const double C1p = std::hypot(a1p, b1), C2p = std::hypot(a2p, b2);
    auto hue = [&](double b, double ap) {
        if (b == 0.0 && ap == 0.0) return 0.0;
        double h = std::atan2(b, ap) / deg;
        return h < 0.0 ? h + 360.0 : h;
    };
    const double h1p = hue(b1, a1p), h2p = hue(b2, a2p);
    const double dLp = L2 - L1, dCp = C2p - C1p;
    double dhp = 0.0;
    if (C1p * C2p != 0.0) {
        dhp = h2p - h1p;
        if (dhp > 180.0) dhp -= 360.0;
        else if (dhp < -180.0) dhp += 360.0;
    }
    const double dHp = 2.0 * std::sqrt(C1p * C2p) * std::sin(0.5 * dhp * deg);
    const double Lpm = 0.5 * (L1 + L2), Cpm = 0.5 * (C1p + C2p);
    double hpm = h1p + h2p;
    if (C1p * C2p != 0.0) {
        if (std::abs(h1p - h2p) <= 180.0) hpm *= 0.5;
        else hpm = (h1p + h2p < 360.0) ? 0.5 * (h1p + h2p + 360.0) : 0.5 * (h1p + h2p - 360.0);
    }
    const double T = 1.0 - 0.17 * std::cos((hpm - 30.0) * deg) + 0.24 * std::cos(2.0 * hpm * deg) +
                     0.32 * std::cos((3.0 * hpm + 6.0) * deg) - 0.20 * std::cos((4.0 * hpm - 63.0) * deg);
    const double dTheta = 30.0 * std::exp(-std::pow((hpm - 275.0) / 25.0, 2.0));
    const double Cpm7 = std::pow(Cpm, 7.0);
    const double RC = 2.0 * std::sqrt(Cpm7 / (Cpm7 + std::pow(25.0, 7.0)));
    const double SL = 1.0 + 0.015 * (Lpm - 50.0) * (Lpm - 50.0) / std::sqrt(20.0 + (Lpm - 50.0) * (Lpm - 50.0));
    const double SC = 1.0 + 0.045 * Cpm, SH = 1.0 + 0.015 * Cpm * T;
    const double RT = -std::sin(2.0 * dTheta * deg) * RC;
    const double l = dLp / SL, c = dCp / SC, h = dHp / SH;
    return std::sqrt(l * l + c * c + h * h + RT * c * h);
}

std::vector<uint8_t> colour_edge_mask(const lab::Image8& image, int threshold) {
    const int w = image.width, h = image.height;
    std::vector<uint8_t> mask(static_cast<size_t>(w) * h, 0);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const uint8_t* p = &image.rgba[(static_cast<size_t>(y) * w + x) * 4];
            bool edge = false;
            for (int dy = -1; dy <= 1 && !edge; ++dy) {
                for (int dx = -1; dx <= 1 && !edge; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                    const uint8_t* q = &image.rgba[(static_cast<size_t>(ny) * w + nx) * 4];
                    for (int ch = 0; ch < 3; ++ch)
                        if (std::abs(int(p[ch]) - int(q[ch])) > threshold) edge = true;
                }
            }
            mask[static_cast<size_t>(y) * w + x] = edge ? 1 : 0;
        }
    }
    return mask;
}

namespace {
int pixel_diff(const uint8_t* a, const uint8_t* b) {
    int d = 0;
    for (int ch = 0; ch < 3; ++ch) d = std::max(d, std::abs(int(a[ch]) - int(b[ch])));
    return d;
}
// Nearest-rank percentile of a vector (reordered in place).
double percentile(std::vector<double>& v, double p) {
    if (v.empty()) return 0.0;
    size_t rank = static_cast<size_t>(std::ceil(p * double(v.size())));
    rank = std::clamp<size_t>(rank, 1, v.size()) - 1;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(rank), v.end());
    return v[rank];
}
}  // namespace

std::string ErrorStats::line() const {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "mean_abs=%.4f p99_abs=%.1f max_abs=%d over_2=%.4f%% mean_de2000=%.4f p99_de2000=%.3f "
                  "pixels=%zu masked=%zu",
                  mean_abs, p99_abs, max_abs, 100.0 * share_over_2, mean_de, p99_de, pixels, masked);
    return buf;
}

ErrorStats error_stats(const lab::Image8& a, const lab::Image8& b, const std::vector<uint8_t>& mask) {
    if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size())
        throw std::invalid_argument("images differ in size (" + std::to_string(a.width) + "x" +
                                    std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                                    std::to_string(b.height) + ")");
    const size_t total = static_cast<size_t>(a.width) * a.height;
    if (!mask.empty() && mask.size() != total) throw std::invalid_argument("mask size differs from the image");
    ErrorStats s;
    s.width = a.width;
    s.height = a.height;
    std::vector<double> abs_err, de;
    abs_err.reserve(total);
    de.reserve(total);
    double sum_abs = 0.0, sum_de = 0.0;
    size_t over = 0;
    for (size_t i = 0; i < total; ++i) {
        if (!mask.empty() && mask[i]) {
            ++s.masked;
            continue;
        }
        const uint8_t* p = &a.rgba[4 * i];
        const uint8_t* q = &b.rgba[4 * i];
        const int d = pixel_diff(p, q);
        s.max_abs = std::max(s.max_abs, d);
        over += d > 2;
        sum_abs += d;
        abs_err.push_back(d);
        const double e = d == 0 ? 0.0 : ciede2000(srgb8_to_lab(p), srgb8_to_lab(q));
        sum_de += e;
        de.push_back(e);
    }
    s.pixels = abs_err.size();
    if (s.pixels > 0) {
        s.mean_abs = sum_abs / double(s.pixels);
        s.mean_de = sum_de / double(s.pixels);
        s.share_over_2 = double(over) / double(s.pixels);
        s.p99_abs = percentile(abs_err, 0.99);
        s.p99_de = percentile(de, 0.99);
    }
    return s;
}

lab::Image8 error_heatmap(const lab::Image8& a, const lab::Image8& b, const std::vector<uint8_t>& mask,
                          int full_scale) {
    if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size())
        throw std::invalid_argument("images differ in size");
    lab::Image8 out;
    out.width = a.width;
    out.height = a.height;
    out.rgba.assign(a.rgba.size(), 255);
    const size_t total = static_cast<size_t>(a.width) * a.height;
    for (size_t i = 0; i < total; ++i) {
        const uint8_t* p = &a.rgba[4 * i];
        uint8_t* o = &out.rgba[4 * i];
        const int d = pixel_diff(p, &b.rgba[4 * i]);
        if (!mask.empty() && mask[i]) {
            o[0] = 0, o[1] = 0, o[2] = 90;
        } else if (d == 0) {
            // Context: the truth's luminance at a quarter brightness.
            const int l = (54 * p[0] + 183 * p[1] + 19 * p[2]) / 256;
            o[0] = o[1] = o[2] = static_cast<uint8_t>(l / 4);
        } else {
            // Heat ramp over t ∈ (0, 1]: dark red → red → yellow → white.
            const double t = std::min(1.0, double(d) / double(std::max(full_scale, 1)));
            const double r = std::min(1.0, 0.3 + 2.1 * t), g = std::clamp(2.0 * t - 0.5, 0.0, 1.0),
                         bl = std::clamp(3.0 * t - 2.0, 0.0, 1.0);
            o[0] = static_cast<uint8_t>(std::lround(255.0 * r));
            o[1] = static_cast<uint8_t>(std::lround(255.0 * g));
            o[2] = static_cast<uint8_t>(std::lround(255.0 * bl));
        }
    }
    return out;
}

// ---------------------------------------------------------------------------
// Lab 4: the shadow error metric
// ---------------------------------------------------------------------------

double lit_fraction(const uint8_t x[3], const uint8_t u[3], const uint8_t z[3]) {
    double num = 0.0, den = 0.0;
    for (int ch = 0; ch < 3; ++ch) {
        const double span = double(u[ch]) - double(z[ch]);
        num += (double(x[ch]) - double(z[ch])) * span;
        den += span * span;
    }
    return den > 0.0 ? num / den : 1.0;
}

namespace {
void require_same_size(const lab::Image8& a, const lab::Image8& b, const char* what) {
    if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size())
        throw std::invalid_argument(std::string("shadow_metric: ") + what + " is " + std::to_string(b.width) + "x" +
                                    std::to_string(b.height) + ", the reference " + std::to_string(a.width) + "x" +
                                    std::to_string(a.height));
}

// 1 where the Chebyshev distance to a set pixel is ≤ k (a (2k+1)² max filter, done separably).
std::vector<uint8_t> dilate(const std::vector<uint8_t>& in, int w, int h, int k) {
    std::vector<uint8_t> rows(in.size(), 0), out(in.size(), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!in[size_t(y) * w + x]) continue;
            for (int dx = std::max(0, x - k); dx <= std::min(w - 1, x + k); ++dx) rows[size_t(y) * w + dx] = 1;
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!rows[size_t(y) * w + x]) continue;
            for (int dy = std::max(0, y - k); dy <= std::min(h - 1, y + k); ++dy) out[size_t(dy) * w + x] = 1;
        }
    return out;
}
}  // namespace

std::string ShadowMetric::line() const {
    char buf[256];
    std::snprintf(buf, sizeof buf, "wrong_side=%zu wrong_side_pct=%.4f shadow_mae=%.4f receivers=%zu banded=%zu band_k=%d",
                  wrong_side, 100.0 * wrong_side_share, mae, receivers, banded, band_k);
    return buf;
}

ShadowMetric shadow_metric(const lab::Image8& actual, const lab::Image8& shadowed, const lab::Image8& unshadowed,
                           const lab::Image8& unlit, const ShadowMetricOptions& options) {
    if (options.band < 0) throw std::invalid_argument("shadow_metric: negative band");
    if (options.margin < 0) throw std::invalid_argument("shadow_metric: negative margin");
    const int mg = options.margin;
    // S is X plus the margin on every side.
    if (shadowed.width != actual.width + 2 * mg || shadowed.height != actual.height + 2 * mg ||
        actual.rgba.size() != size_t(actual.width) * size_t(actual.height) * 4 ||
        shadowed.rgba.size() != size_t(shadowed.width) * size_t(shadowed.height) * 4)
        throw std::invalid_argument("shadow_metric: the picture is " + std::to_string(actual.width) + "x" +
                                    std::to_string(actual.height) + ", the reference " + std::to_string(shadowed.width) +
                                    "x" + std::to_string(shadowed.height) + " (margin " + std::to_string(mg) + ")");
    require_same_size(shadowed, unshadowed, "the unshadowed reference");
    require_same_size(shadowed, unlit, "the unlit reference");
    const int W = shadowed.width, H = shadowed.height;  // the reference frame, margin included
    const int w = actual.width, h = actual.height;      // the judged picture: its centre
    const size_t big = size_t(W) * size_t(H), total = size_t(w) * size_t(h);
    const auto at = [&](size_t i) { return size_t(int(i / size_t(w)) + mg) * size_t(W) + size_t(int(i % size_t(w)) + mg); };
    ShadowMetric m;
    m.width = w;
    m.height = h;
    m.band_k = options.band;
    std::vector<uint8_t> state(big, 0);  // S's state over the whole reference frame
    for (size_t i = 0; i < big; ++i) {
        const uint8_t* u = &unshadowed.rgba[4 * i];
        const uint8_t* z = &unlit.rgba[4 * i];
        if (pixel_diff(u, z) < options.min_contrast) continue;
        state[i] = lit_fraction(&shadowed.rgba[4 * i], u, z) >= 0.5 ? 1 : 2;
    }
    // The band: p is in it when some pixel within Chebyshev distance k has another S-state
    // (found on the whole reference frame, so edges in the margin count).
    std::vector<uint8_t> band(big, 0);
    for (uint8_t value = 0; value < 3; ++value) {
        std::vector<uint8_t> has(big, 0);
        for (size_t i = 0; i < big; ++i) has[i] = state[i] == value;
        const std::vector<uint8_t> near = dilate(has, W, H, options.band);
        for (size_t i = 0; i < big; ++i)
            if (near[i] && state[i] != value) band[i] = 1;
    }
    m.state.assign(total, 0);
    m.band.assign(total, 0);
    m.wrong.assign(total, 0);
    double sum = 0.0;
    for (size_t i = 0; i < total; ++i) {
        const size_t r = at(i);  // the same pixel in the reference frame
        m.state[i] = state[r];
        m.band[i] = band[r];
        if (m.state[i] == 0) continue;
        ++m.receivers;
        const uint8_t* x = &actual.rgba[4 * i];
        const uint8_t* s = &shadowed.rgba[4 * r];
        sum += (std::abs(int(x[0]) - int(s[0])) + std::abs(int(x[1]) - int(s[1])) + std::abs(int(x[2]) - int(s[2]))) / 3.0;
        if (m.band[i]) {
            ++m.banded;
            continue;
        }
        const uint8_t* u = &unshadowed.rgba[4 * r];
        const uint8_t* z = &unlit.rgba[4 * r];
        if ((lit_fraction(x, u, z) >= 0.5 ? 1 : 2) != m.state[i]) {
            m.wrong[i] = 1;
            ++m.wrong_side;
        }
    }
    if (m.receivers > 0) m.mae = sum / double(m.receivers);
    if (m.receivers > m.banded) m.wrong_side_share = double(m.wrong_side) / double(m.receivers - m.banded);
    return m;
}

lab::Image8 shadow_metric_picture(const lab::Image8& shadowed, const ShadowMetric& metric) {
    lab::Image8 out;
    out.width = shadowed.width;
    out.height = shadowed.height;
    out.rgba.assign(shadowed.rgba.size(), 255);
    for (size_t i = 0; i < metric.state.size(); ++i) {
        const uint8_t* p = &shadowed.rgba[4 * i];
        uint8_t* o = &out.rgba[4 * i];
        const int l = (54 * p[0] + 183 * p[1] + 19 * p[2]) / 256;
        o[0] = o[1] = o[2] = static_cast<uint8_t>(l / 3);
        if (metric.state[i] && metric.band[i]) o[0] = 0, o[1] = 0, o[2] = 110;
        if (metric.wrong[i]) {
            const bool too_bright = metric.state[i] == 2;  // S in shadow, X lit
            o[0] = too_bright ? 255 : 0, o[1] = too_bright ? 40 : 255, o[2] = too_bright ? 40 : 255;
        }
    }
    return out;
}

size_t magenta_pixels(const lab::Image8& image) {
    size_t n = 0;
    for (size_t i = 0; i + 3 < image.rgba.size(); i += 4)
        n += image.rgba[i] == 255 && image.rgba[i + 1] == 0 && image.rgba[i + 2] == 255;
    return n;
}

}  // namespace ref
