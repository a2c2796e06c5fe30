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

}  // namespace ref
