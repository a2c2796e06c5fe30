// image_compare.h — compare a GPU-rendered PNG with the CPU reference.
//
// Rasterisation and ray casting agree everywhere except where coverage is a
// matter of rounding: a pixel centre within a hair of a silhouette may be
// claimed by either side. Those pixels form the *edge mask*: every pixel whose
// 3×3 neighbourhood in the reference contains more than one object id
// (object/object and object/background boundaries). Away from the edge mask
// the images must agree to within the tolerance; overall only a small
// fraction of pixels may differ.
#pragma once

#include "image_io.h"
#include "reference/cpu_reference.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace ref {

struct CompareOptions {
    int tolerance = 1;                      // allowed |difference| per channel, in 1/255 units
    double max_fraction_differing = 0.005;  // of all pixels, counting edges
    // Also treat as edges pixels whose 3×3 neighbourhood has more than one
    // triangle id (useful for lit scenes where the shading is discontinuous
    // between the faces of one object). Off for unlit lab 1.
    bool triangle_edges = false;
    // Also treat as edges pixels whose surface is seen nearly edge-on:
    // |cos(angle between geometric normal and view direction)| < grazing_cos.
    // 0 disables it.
    double grazing_cos = 0.0;
};

struct CompareResult {
    int width = 0;
    int height = 0;
    bool size_mismatch = false;  // the images differ in size: nothing else is meaningful
    int tolerance = 1;
    double max_fraction_allowed = 0.005;

    // Away from edges.
    int max_diff_interior = 0;           // largest channel difference, 1/255 units
    int worst_x = -1, worst_y = -1;      // where it occurred (−1: no interior difference at all)
    uint8_t worst_expected[4] = {0, 0, 0, 0};
    uint8_t worst_actual[4] = {0, 0, 0, 0};
    size_t interior_differing = 0;       // interior pixels beyond the tolerance

    // Everywhere.
    int max_diff_all = 0;
    size_t differing_pixels = 0;         // pixels with some channel beyond the tolerance
    double fraction_differing = 0.0;     // differing_pixels / (width · height)
    size_t edge_pixels = 0;              // size of the edge mask

    std::vector<uint8_t> edge_mask;      // 1 = edge pixel, row-major
    std::string diff_image;              // path of the diff visualisation, if one was written

    bool passed() const;
    std::string describe() const;  // a multi-line summary for gtest failure messages
};

// The edge mask of a reference image (see the file comment and CompareOptions).
std::vector<uint8_t> edge_mask(const RefImage& reference, const CompareOptions& options = {});

// Compares `actual` (the GPU's PNG) with encode_srgb(reference). All four
// channels count (alpha must be 255 like the reference's).
CompareResult compare_images(const lab::Image8& actual, const RefImage& reference,
                             const CompareOptions& options = {});

// Writes a visualisation, three panels side by side: expected | actual | diff.
// In the diff panel: black = equal (very dark blue on the edge mask),
// blue = edge pixel different but within tolerance, yellow = edge pixel beyond
// tolerance, red (brighter = larger) = interior pixel beyond tolerance,
// dark red = interior pixel different but within tolerance.
void write_diff_png(const std::string& path, const lab::Image8& actual, const RefImage& reference,
                    const CompareResult& result);

// compare_images(), and on failure also write_diff_png() to `diff_path` (its
// folder is created if needed) and record the path in the result.
CompareResult compare_and_report(const lab::Image8& actual, const RefImage& reference,
                                 const std::string& diff_path,
                                 const CompareOptions& options = {});

// ---------------------------------------------------------------------------
// Error figures between two 8-bit images (lab_compare, bench/tradeoff.py): how far a
// lab's picture is from a truth, rather than pass/fail against a tolerance.
// ---------------------------------------------------------------------------

// sRGB-encoded 8-bit colour → CIE L*a*b* (D65 white, via linear sRGB and XYZ).
glm::dvec3 srgb8_to_lab(const uint8_t rgb[3]);

// CIEDE2000 colour difference of two L*a*b* colours (Sharma, Wu & Dalal 2005);
// about 1 is a just-noticeable difference.
double ciede2000(const glm::dvec3& lab1, const glm::dvec3& lab2);

// Pixels of exactly (255, 0, 255): the labs' NaN/Inf detector paints them (and lab 3 its
// missing-image checkerboard).
size_t magenta_pixels(const lab::Image8& image);

// Edges of an image seen from its colours alone (no object ids needed): a pixel whose
// 3×3 neighbourhood holds a colour more than `threshold`/255 away in some channel
// (silhouettes against the background or another object, hard shading edges).
std::vector<uint8_t> colour_edge_mask(const lab::Image8& image, int threshold = 16);

struct ErrorStats {
    int width = 0, height = 0;
    size_t pixels = 0;         // pixels counted (all, minus the mask)
    size_t masked = 0;         // pixels left out by the mask
    // Per pixel: the largest |difference| over R, G, B, in 1/255 units.
    double mean_abs = 0.0;
    double p99_abs = 0.0;      // 99th percentile (nearest rank)
    int max_abs = 0;
    double share_over_2 = 0.0; // share of pixels with a difference above 2/255 (0 … 1)
    // Per pixel: CIEDE2000 between the two colours.
    double mean_de = 0.0;
    double p99_de = 0.0;

    std::string line() const;  // one line "mean_abs=… p99_abs=… …" (what lab_compare prints)
};

// The figures of `b` against `a` (same size; throws std::invalid_argument otherwise).
// Pixels with mask[i] != 0 are left out (mask may be empty: none).
ErrorStats error_stats(const lab::Image8& a, const lab::Image8& b, const std::vector<uint8_t>& mask = {});

// A picture of where b differs from a: a's luminance, dimmed, where they agree; a heat
// colour (dark red → red → yellow → white) growing with the pixel's largest channel
// difference up to `full_scale`/255 (and beyond, white). Masked pixels are dark blue.
lab::Image8 error_heatmap(const lab::Image8& a, const lab::Image8& b, const std::vector<uint8_t>& mask = {},
                          int full_scale = 32);

// ---------------------------------------------------------------------------
// Lab 4: the shadow error metric (docs/testing.md, "The shadow error metric").
// Three reference pictures (ref::render_shadow_reference): S = ray-traced shadows, U = every
// light unoccluded, Z = the shadow-casting lights off. For a picture X and a pixel p (8-bit
// sRGB values, R, G, B as a vector):
//   receiver:        |U − Z| ≥ min_contrast in some channel (a shadow-casting light shows there);
//   lit fraction:    f_X = (X − Z)·(U − Z) / |U − Z|²  (1 = fully lit, 0 = fully shadowed);
//   state:           lit if f ≥ ½, shadow otherwise; non-receivers have a state of their own;
//   band:            pixels with a pixel of another S-state within k pixels in x and in y;
//   wrong_side:      receivers outside the band where state(X) ≠ state(S);
//   mae:             over all receivers, the mean of |X − S| averaged over R, G, B, in 1/255.
// ---------------------------------------------------------------------------

struct ShadowMetricOptions {
    int band = 4;          // k, in pixels (the PCF radius in texels + 1; see docs/testing.md)
    int min_contrast = 3;  // 1/255: smaller light contributions are too faint to classify
    // S, U and Z are `margin` pixels larger than X on every side (ref::render_shadow_reference with
    // that margin): the band is found on the larger frame and cropped, so an S edge just outside the
    // picture bands the pixels within k of it as one inside does. Use margin ≥ band; 0: same size.
    int margin = 0;
};

struct ShadowMetric {
    int width = 0, height = 0;
    size_t receivers = 0;         // pixels a shadow-casting light reaches in U
    size_t banded = 0;            // receivers within the band around S's shadow edges
    size_t wrong_side = 0;        // receivers outside the band on the other side than in S
    double wrong_side_share = 0;  // wrong_side / (receivers − banded), 0 … 1
    double mae = 0.0;             // mean |X − S| over receivers, 1/255 units
    std::vector<uint8_t> state;   // S's state per pixel: 0 not a receiver, 1 lit, 2 shadow
    std::vector<uint8_t> band;    // 1 = within k of a state change of S
    std::vector<uint8_t> wrong;   // 1 = a wrong-side pixel

    int band_k = 0;

    std::string line() const;  // "wrong_side=… wrong_side_pct=… shadow_mae=… receivers=… banded=… band_k=…"
};

// The lit fraction f of colour x between z (light off) and u (light on), 8-bit RGB.
double lit_fraction(const uint8_t x[3], const uint8_t u[3], const uint8_t z[3]);

// The metric of `actual` against the shadowed reference S (S, U, Z the size of `actual` plus
// 2·options.margin each way; throws std::invalid_argument otherwise). The returned per-pixel
// vectors are the size of `actual`.
ShadowMetric shadow_metric(const lab::Image8& actual, const lab::Image8& shadowed, const lab::Image8& unshadowed,
                           const lab::Image8& unlit, const ShadowMetricOptions& options = {});

// A picture of the metric: S's luminance dimmed, receivers in the band dark blue, wrong-side
// pixels red (X lit where S is in shadow) or cyan (X in shadow where S is lit).
lab::Image8 shadow_metric_picture(const lab::Image8& shadowed, const ShadowMetric& metric);

}  // namespace ref
