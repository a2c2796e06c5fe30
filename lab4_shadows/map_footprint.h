// map_footprint.h — lab 4: how many texels a shadow map needs for the picture it is used in
// (README, "Maps sized to the picture"). Texels far smaller than the pixel they land in are work
// the picture cannot show. So the map is drawn with two texels across each pixel where the
// picture can show one of its shadows, and never more than the scene's resolution.
#pragma once

#include "light_frustum.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

// A point of the picture: where a ray through a pixel first meets a receiver's box, and how wide
// one pixel is there (world units). The boxes are larger than their objects, so the point is no
// farther than the surface the pixel shows, and its pixel no wider: the estimate errs on the fine side.
struct ViewSample {
    glm::dvec3 point;
    double pixel = 0.0;
    double reach = 0.0;  // how far the pixels between it and the next samples can lie from it (world units)
    int receiver = -1;   // whose box it lies on
};

// A box the map holds, as texels_needed sees it: which receiver it is, and whether it can shadow
// itself (not a convex opaque one: casters_for in shadow_maps.cpp).
struct FootprintCaster {
    Box box;
    int receiver = -1;
    bool shadows_itself = true;
};

// Rays through a grid of pixels of a `width`×`height` picture (edges and corners included, where
// the nearest receivers usually are), `world_to_clip` the camera's projection · view (Vulkan depth
// 0…1). A ray that meets no box gives no sample.
std::vector<ViewSample> sample_view(const glm::dmat4& world_to_clip, uint32_t width, uint32_t height,
                                    const std::vector<Box>& receivers);

// Texels across one pixel's width. One would do for the picture's sharpness, but a shadow edge
// snaps to the map's texels (and the normal offset moves it by one more): at one texel per pixel
// the edges land a pixel off the ray-traced truth, at two within it (README, "Maps sized to the
// picture": 1000 random scenes with every texel, one and two texels per pixel).
constexpr double kTexelsPerPixel = 2.0;

// The texels per side at which a map of `f` has kTexelsPerPixel texels across each pixel wherever
// the picture can show one of its shadows: kTexelsPerPixel · max over the samples of (a texel's
// width there, for a map of one texel) / (the pixel's width). A sample counts only where a
// caster can shadow it or a pixel around it (the ray to the light, `light`: its position, or
// with `directional` the way it travels, meets another caster's box, or its own if it shadows
// itself, grown by the sample's reach), and only inside the map (a 2D map's edges; behind the
// light). A lit floor far from every shadow needs no texels at all. 0 when no sample counts.
double texels_needed(const LightFrustum& f, const std::vector<ViewSample>& samples,
                     const std::vector<FootprintCaster>& casters, const glm::dvec3& light, bool directional);

// What the map pass draws, given `texels` needed and what it drew last (`drawn`, 0: nothing yet):
// one of the sizes resolution · 2^(−k/4) (k = 0, 1, …; each rounded up to a multiple of 8, at
// least kFewestTexels, at most `resolution`), the smallest that holds `texels`. It keeps `drawn`
// while that still holds them and is less than two sizes (√2) too large: a camera moving back
// and forth across one size redraws nothing.
constexpr uint32_t kFewestTexels = 64;
uint32_t footprint_resolution(double texels, uint32_t resolution, uint32_t drawn = 0);
