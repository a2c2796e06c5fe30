// test_map_footprint.cpp — lab 4's maps sized to the picture (lab4_shadows/map_footprint.cpp), by
// hand. The set-ups are chosen so that the answer is one line of trigonometry: a camera 10 units
// above a floor, looking straight down with a 90° field of view over 1000 × 1000 pixels, sees
// 20 units across, so one pixel is 0.02 units wide everywhere on the floor. A map needs
// kTexelsPerPixel (2) texels across each pixel.
#include "map_footprint.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace {

constexpr uint32_t kPixels = 1000;
const Box kFloor{{-50.0, 0.0, -50.0}, {50.0, 0.0, 50.0}};

// Looking straight down from (x, 10, z), 90° field of view, square picture, Vulkan depth 0…1.
glm::dmat4 top_down_camera(double x = 0.0, double z = 0.0) {
    return glm::perspectiveRH_ZO(glm::radians(90.0), 1.0, 0.1, 100.0) *
           glm::lookAtRH(glm::dvec3(x, 10.0, z), glm::dvec3(x, 0.0, z), glm::dvec3(0.0, 0.0, -1.0));
}

// A directional light straight down, its orthographic map 10 units across, over x, z in [−5, 5].
LightFrustum overhead_map() {
    LightFrustum f;
    f.origin = glm::dvec3(0.0);
    f.view_projection = glm::orthoRH_ZO(-5.0, 5.0, -5.0, 5.0, 1.0, 40.0) *
                        glm::lookAtRH(glm::dvec3(0.0, 20.0, 0.0), glm::dvec3(0.0), glm::dvec3(0.0, 0.0, -1.0));
    f.texel = 10.0;
    return f;
}

const glm::dvec3 kDown(0.0, -1.0, 0.0);
// A slab above the whole map: every floor point under it can be in its shadow.
const FootprintCaster kRoof{{{-5.0, 1.0, -5.0}, {5.0, 2.0, 5.0}}, 1, false};

TEST(MapFootprint, TopDownSamplesLieOnTheFloorAPixelApart) {
    const std::vector<ViewSample> samples = sample_view(top_down_camera(), kPixels, kPixels, {kFloor});
    ASSERT_EQ(samples.size(), 33u * 19u);  // every ray of the grid meets the floor
    for (const ViewSample& s : samples) {
        EXPECT_NEAR(s.point.y, 0.0, 1e-9);
        EXPECT_NEAR(s.pixel, 0.02, 1e-9);  // 2 · 10 · tan 45° / 1000
        EXPECT_EQ(s.receiver, 0);
    }
}

TEST(MapFootprint, OrthographicMapNeedsItsWidthOverAPixel) {
    const std::vector<ViewSample> samples = sample_view(top_down_camera(), kPixels, kPixels, {kFloor});
    // 10 units of map over 0.02-unit pixels: 500 pixels' worth, 1000 texels; the next size up,
    // 2048 · 2^(−4/4) = 1024.
    ASSERT_EQ(kTexelsPerPixel, 2.0);
    const double texels = texels_needed(overhead_map(), samples, {kRoof}, kDown, true);
    EXPECT_NEAR(texels, 1000.0, 1e-6);
    EXPECT_EQ(footprint_resolution(texels, 2048), 1024u);
    // Twice as many pixels across the same view: twice the texels.
    EXPECT_NEAR(texels_needed(overhead_map(), sample_view(top_down_camera(), 2 * kPixels, 2 * kPixels, {kFloor}), {kRoof},
                              kDown, true),
                2000.0, 1e-6);
}

TEST(MapFootprint, OnlyWhereACasterCanShadowCounts) {
    const std::vector<ViewSample> samples = sample_view(top_down_camera(), kPixels, kPixels, {kFloor});
    // A caster below the floor casts downwards, away from it: nothing the picture shows needs the map.
    const FootprintCaster below{{{-5.0, -3.0, -5.0}, {5.0, -2.0, 5.0}}, 1, false};
    EXPECT_EQ(texels_needed(overhead_map(), samples, {below}, kDown, true), 0.0);
    EXPECT_EQ(footprint_resolution(0.0, 2048), kFewestTexels);
    // The floor as its own caster: a convex opaque object never shadows itself; one that can, does.
    const FootprintCaster floor_only{kFloor, 0, false};
    EXPECT_EQ(texels_needed(overhead_map(), samples, {floor_only}, kDown, true), 0.0);
    FootprintCaster self_shadowing = floor_only;
    self_shadowing.shadows_itself = true;
    EXPECT_NEAR(texels_needed(overhead_map(), samples, {self_shadowing}, kDown, true), 1000.0, 1e-6);
    // A small caster under the map counts where its shadow (or a pixel near it) is.
    const FootprintCaster post{{{-0.1, 1.0, -0.1}, {0.1, 3.0, 0.1}}, 1, false};
    EXPECT_NEAR(texels_needed(overhead_map(), samples, {post}, kDown, true), 1000.0, 1e-6);
}

TEST(MapFootprint, SamplesOutsideTheMapDoNotCount) {
    // The camera looks at x in [20, 40]: the map covers [−5, 5].
    const std::vector<ViewSample> samples = sample_view(top_down_camera(30.0, 0.0), kPixels, kPixels, {kFloor});
    ASSERT_FALSE(samples.empty());
    const FootprintCaster everywhere{{{-50.0, 1.0, -50.0}, {50.0, 2.0, 50.0}}, 1, false};
    EXPECT_EQ(texels_needed(overhead_map(), samples, {everywhere}, kDown, true), 0.0);
}

TEST(MapFootprint, PerspectiveMapFromTheCamerasPlaceNeedsAsManyTexelsAsPixels) {
    // A spot light where the camera is, with the camera's projection: texel and pixel coincide at
    // every point, so the map needs two texels for each of the picture's 1000 pixels per side.
    LightFrustum f;
    f.origin = glm::dvec3(0.0, 10.0, 0.0);
    f.view_projection = glm::perspectiveRH_ZO(glm::radians(90.0), 1.0, 0.1, 100.0) *
                        glm::lookAtRH(glm::dvec3(0.0), glm::dvec3(0.0, -1.0, 0.0), glm::dvec3(0.0, 0.0, -1.0));
    f.perspective = true;
    const std::vector<ViewSample> samples = sample_view(top_down_camera(), kPixels, kPixels, {kFloor});
    EXPECT_NEAR(texels_needed(f, samples, {kRoof}, f.origin, false), 2000.0, 1e-6);
    // The same light twice as high: a texel of the 1-texel map is 2 · 20 · tan 45° = 40 units
    // wide at the floor, twice the camera's, so the map needs twice the texels.
    f.origin = glm::dvec3(0.0, 20.0, 0.0);
    EXPECT_NEAR(texels_needed(f, samples, {kRoof}, f.origin, false), 4000.0, 1e-6);
}

TEST(MapFootprint, CubeMapUsesTheFaceThePointFallsIn) {
    // A point light where the camera is: the floor below lies in its −Y face, a 90° view like the
    // camera's, so again texel = pixel: 2000 texels; the cube's faces come from fit_point.
    const Box roof = kRoof.box;
    const LightFrustum f = fit_point({0.0, 10.0, 0.0}, {roof});
    ASSERT_TRUE(f.cube);
    const std::vector<ViewSample> samples = sample_view(top_down_camera(), kPixels, kPixels, {kFloor});
    EXPECT_NEAR(texels_needed(f, samples, {kRoof}, f.origin, false), 2000.0, 1e-6);
}

TEST(MapFootprint, ResolutionSteps) {
    // The sizes below 2048: 2048 · 2^(−k/4), rounded up to a multiple of 8: 1728, 1456, 1224, 1024,
    // 864, 728, 616, 512, 432, …
    EXPECT_EQ(footprint_resolution(1500.0, 2048), 1728u);
    EXPECT_EQ(footprint_resolution(1456.0, 2048), 1456u);
    EXPECT_EQ(footprint_resolution(500.0, 2048), 512u);
    EXPECT_EQ(footprint_resolution(513.0, 2048), 616u);
    EXPECT_EQ(footprint_resolution(5000.0, 2048), 2048u);  // never above the scene's resolution
    EXPECT_EQ(footprint_resolution(10.0, 32), 32u);        // nor below it when it is smaller than the fewest
    EXPECT_EQ(footprint_resolution(0.0, 1), 1u);
    EXPECT_EQ(footprint_resolution(0.0, 300), kFewestTexels);
}

TEST(MapFootprint, ASizeDrawnIsKeptWhileItHoldsTheTexelsAndIsNotTwoSizesTooLarge) {
    EXPECT_EQ(footprint_resolution(1300.0, 2048, 1456), 1456u);  // one size too large: kept
    EXPECT_EQ(footprint_resolution(1030.0, 2048, 1456), 1456u);  // still above 1456 / √2 = 1029.6
    EXPECT_EQ(footprint_resolution(1000.0, 2048, 1456), 1024u);  // two sizes: the right one
    EXPECT_EQ(footprint_resolution(1500.0, 2048, 1456), 1728u);  // too small: the next that holds them
    EXPECT_EQ(footprint_resolution(1300.0, 1024, 1456), 1024u);  // drawn for a larger resolution: not kept
}

}  // namespace
