// cpu_texture.h — texture sampling for the CPU reference, written from the Vulkan specification
// (chapter "Texel Filtering" / "Texel Coordinate Systems"), independent of the lab's code:
//
//   * its own decoding of the image files (stb_image compiled here) and of the procedural
//     sources (from their formulas in docs/scene-format.md);
//   * its own mip chain: each level the box average of the one above in *linear* colour (a child
//     texel is the mean over the parent area it covers: 2×2 for even sides, all three texels for
//     3 → 1, overlap-weighted for 5 → 2), kept in double, never re-quantized;
//   * each map decoded as what it holds in the lighting equation: sRGB colour, or data (byte / 255);
//   * texel centres at (i + ½)/size; wrap modes repeat, mirrored repeat, clamp to edge;
//   * nearest: texel floor(u·w); linear: the 4 texels around u·w − ½, bilinear weights;
//   * LOD λ = log2(ρmax) with ρ from *analytic* UV derivatives at the pixel (ray differentials,
//     Igehy 1999), the isotropic ρmax = max(|∂uv/∂x|·size, |∂uv/∂y|·size); level nearest:
//     ceil(λ + ½) − 1, level linear: between floor(λ) and floor(λ)+1 (λ clamped to the chain).
// Anisotropic filtering is not modelled: tests that compare against this use anisotropy 1.
// The supersampled ground truth (render_supersampled) averages level-0 bilinear lookups at
// n×n points of every pixel: the texture averaged over the pixel's footprint.
#pragma once

#include "reference/cpu_reference.h"

#include <glm/glm.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace ref {

struct TextureLevel {
    int width = 0;
    int height = 0;
    std::vector<glm::dvec4> texels;  // linear RGBA, row 0 = v ∈ [0, 1/height)
    const glm::dvec4& at(int x, int y) const { return texels[size_t(y) * size_t(width) + size_t(x)]; }
};

struct RefTexture {
    std::vector<TextureLevel> levels;  // [0] = the image; one level without mipmaps
    bool fallback = false;             // the map could not be read: the magenta/black checkerboard
};

// 8-bit RGBA pixels → a texture (linear), with the mip chain down to 1×1 if `mipmaps`. `srgb`:
// the RGB bytes are sRGB-encoded colour (else linear data, byte / 255); alpha is always linear.
RefTexture make_texture(int width, int height, const std::vector<unsigned char>& srgb_rgba, bool mipmaps, bool srgb = true);
// A map as the scene names it ("procedural:NAME" or a file). Files that do not decode, or that
// exceed `max_dimension`, give the checkerboard with fallback = true.
RefTexture load_texture(const std::string& map, bool mipmaps, int max_dimension = 16384, bool srgb = true);

// The wrapped integer texel coordinate (spec: "Wrapping Operation").
int wrap_texel(int i, int size, lab::SamplerDesc::Wrap wrap);

// What a conformant implementation may do differently from the exact lookup, for tests that must
// hold on any GPU (the Vulkan specification, chapter "Image Operations"):
//   * texel coordinates keep only VkPhysicalDeviceLimits::subTexelPrecisionBits fraction bits, so a
//     bilinear weight, or the texel a nearest lookup picks, may be decided 2^-bits of a texel away;
//   * the rasteriser snaps vertices to subPixelPrecisionBits, which moves the point a pixel's
//     coordinates are interpolated at by up to 2^-bits of a pixel on each screen axis (the move
//     inside the triangle is the corners' moves interpolated, so no larger than theirs): in texels,
//     2^-bits · (|∂u/∂x| + |∂u/∂y|) (u in texels; the lookup's own derivatives, so a scaled or
//     distorted lookup moves as far as its footprint);
//   * the scale factor ρ may be approximated by any f with, per screen axis,
//         max(|∂u/∂x|, |∂v/∂x|) ≤ f_x ≤ √3·(|∂u/∂x| + |∂v/∂x|)   (u, v in texels)
//     `lod_between` = t picks λ = (1 − t)·λ_low + t·λ_high inside that range; a negative value (the
//     default) keeps the exact λ = log2(ρmax).
// `corner` (−1, 0 or 1 per texel axis) moves every lookup's texel coordinates to that corner of the
// box the first two allow, at each mip level in that level's texels. The default is the exact lookup.
struct SamplingVariant {
    glm::dvec2 corner{0.0};
    double texel_step = 0.0;  // 2^-subTexelPrecisionBits
    double pixel_step = 0.0;  // 2^-subPixelPrecisionBits
    double lod_between = -1.0;
};

// One filtered lookup at `level` (no mip selection): nearest or bilinear, at texel coordinates
// moved by `texel_shift` (SamplingVariant; 0: the exact lookup).
glm::dvec4 sample_level(const TextureLevel& level, glm::dvec2 uv, lab::SamplerDesc::Filter filter,
                        lab::SamplerDesc::Wrap wrap, glm::dvec2 texel_shift = glm::dvec2(0.0));

// The LOD λ = log2(ρmax) of a lookup with UV derivatives dx, dy (per pixel) on `level0`.
double lod(const TextureLevel& level0, glm::dvec2 dx, glm::dvec2 dy);
// The smallest and largest λ the specification's bounds on ρ allow (see SamplingVariant).
glm::dvec2 lod_bounds(const TextureLevel& level0, glm::dvec2 dx, glm::dvec2 dy);

// A full lookup as a sampler with `desc` does it (anisotropy ignored).
glm::dvec4 sample(const RefTexture& texture, const lab::SamplerDesc& desc, glm::dvec2 uv, glm::dvec2 dx,
                  glm::dvec2 dy, const SamplingVariant& variant = {});

// The texture coordinates material `m`'s maps are read at, for the mesh's `uv` (docs/scene-format.md).
glm::dvec2 material_uv(const lab::MaterialDesc& m, glm::dvec2 uv);

// A ShadeFn for lab 3 (Phong or flat shading): lab 2's equation with the material's textured terms
// as docs/lighting.md and docs/scene-format.md define them (the maps at the material's transformed
// UV, "distorted" sampling included). The UV derivatives come from ray differentials of a
// width × height image.
// With `supersample_level0` every lookup is bilinear on level 0 (for render_supersampled).
// `variant`: every lookup of the shader done that way (tests/test_lab3_render.cpp's envelope).
// Lab 4: with `shadows`, every light with cast_shadows is scaled by shadows->transmittance() at the
// hit (cpu_shadow.h); the hit's geometric_normal must point to the shaded side.
class ShadowCasters;
ShadeFn make_texture_shader(const lab::Scene& scene, int width, int height, bool supersample_level0 = false,
                            const SamplingVariant& variant = {}, std::shared_ptr<const ShadowCasters> shadows = nullptr);

// The LOD λ of the first map's lookup (albedo, else specular, else emissive) at a hit, from the
// same ray differentials; −1e9 for misses and materials without maps. λ ≤ 0: magnified.
std::function<double(const Hit&)> make_lod_probe(const lab::Scene& scene, int width, int height);

// The ground truth for filtering: n × n rays per pixel on a regular grid, each shaded with
// level-0 bilinear lookups, averaged (linear colour). Misses average in the background.
RefImage render_supersampled(const lab::Scene& scene, int width, int height, int n);

}  // namespace ref
