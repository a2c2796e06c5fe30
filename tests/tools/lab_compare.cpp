// lab_compare — how far one picture is from another, in one line.
//
//   lab_compare A.png B.png [--heatmap out.png] [--mask edges] [--shadow U.png Z.png [--band K]]
//
// A is the truth (e.g. `lab_reference --ideal`), B the picture judged. Prints
//   mean_abs=… p99_abs=… max_abs=… over_2=…% mean_de2000=… p99_de2000=… pixels=… masked=…
// per pixel the largest |difference| over R, G, B in 1/255 units (mean, 99th percentile,
// maximum, share above 2/255) and the CIEDE2000 difference (about 1 = just noticeable).
// --mask edges leaves out A's edges (colour_edge_mask: silhouettes, hard shading edges),
// to see the error inside surfaces alone. --heatmap writes where the error is (error_heatmap).
// --shadow (lab 4): A is the ray-traced shadowed reference, U and Z the same scene unoccluded and
// with the shadow-casting lights off (lab_reference --unshadowed / --unlit); the line gains the
// shadow error metric "wrong_side=… wrong_side_pct=… shadow_mae=… receivers=… banded=… band_k=…"
// (docs/testing.md), with the band k (default 4); --heatmap then draws the metric's picture.
// The figures come from tests/reference/image_compare.h, the comparison the tests use.
#include "reference/image_compare.h"

#include "image_io.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

int main(int argc, char** argv) {
    std::string a_path, b_path, heatmap, mask, unshadowed, unlit;
    int band = 4;
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string f = argv[i];
            if (f == "--help" || f == "-h") {
                std::puts("usage: lab_compare A.png B.png [--heatmap out.png] [--mask edges] [--shadow U.png Z.png [--band K]]");
                return 0;
            }
            if (f == "--shadow") {
                if (i + 2 >= argc) throw std::invalid_argument("--shadow needs two images (unshadowed, unlit)");
                unshadowed = argv[++i];
                unlit = argv[++i];
            } else if (f == "--band") {
                if (i + 1 >= argc) throw std::invalid_argument("--band needs a value");
                const std::string v = argv[++i];
                char* end = nullptr;
                const long k = std::strtol(v.c_str(), &end, 10);
                if (v.empty() || *end != '\0' || k < 0 || k > 64)
                    throw std::invalid_argument("--band: '" + v + "' is not a whole number in 0 ... 64");
                band = int(k);
            } else if (f == "--heatmap" || f == "--mask") {
                if (i + 1 >= argc) throw std::invalid_argument(f + " needs a value");
                (f == "--heatmap" ? heatmap : mask) = argv[++i];
            } else if (!f.empty() && f[0] == '-') {
                throw std::invalid_argument("unknown option '" + f + "'");
            } else if (a_path.empty()) {
                a_path = f;
            } else if (b_path.empty()) {
                b_path = f;
            } else {
                throw std::invalid_argument("unexpected argument '" + f + "' (two images expected)");
            }
        }
        if (b_path.empty()) throw std::invalid_argument("two images are needed: lab_compare A.png B.png");
        if (!mask.empty() && mask != "edges") throw std::invalid_argument("--mask: unknown mask '" + mask + "' (edges)");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "lab_compare: %s (see --help)\n", e.what());
        return 2;
    }
    try {
        const lab::Image8 a = lab::read_png(a_path);
        const lab::Image8 b = lab::read_png(b_path);
        if (a.width != b.width || a.height != b.height)
            throw std::runtime_error(b_path + ": " + std::to_string(b.width) + "x" + std::to_string(b.height) +
                                     ", but " + a_path + " is " + std::to_string(a.width) + "x" +
                                     std::to_string(a.height));
        const std::vector<uint8_t> m = mask == "edges" ? ref::colour_edge_mask(a) : std::vector<uint8_t>{};
        const ref::ErrorStats stats = ref::error_stats(a, b, m);
        std::string shadow_line;
        ref::ShadowMetric metric;
        if (!unshadowed.empty()) {
            ref::ShadowMetricOptions options;
            options.band = band;
            metric = ref::shadow_metric(b, a, lab::read_png(unshadowed), lab::read_png(unlit), options);
            shadow_line = " " + metric.line();
        }
        if (!heatmap.empty()) {
            const std::filesystem::path parent = std::filesystem::path(heatmap).parent_path();
            if (!parent.empty() && !std::filesystem::is_directory(parent))
                throw std::runtime_error(heatmap + ": folder '" + parent.string() + "' does not exist");
            lab::write_png(heatmap, unshadowed.empty() ? ref::error_heatmap(a, b, m) : ref::shadow_metric_picture(a, metric));
        }
        std::printf("%s%s\n", stats.line().c_str(), shadow_line.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "lab_compare: %s\n", e.what());
        return 2;
    }
    return 0;
}
