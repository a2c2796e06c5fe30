// texture.h — a texture map on the GPU: the image from pixels, with its mip chain.
//
// The Vulkan half of lab 3's lesson (texture.cpp): a staging buffer the CPU writes, an image in
// device memory, layout transitions around the copy, the mip chain blitted level by level on the
// GPU (or box-filtered on the CPU where the device can't), and the final layout the fragment
// shader samples in. The sampler that reads it is sampler_cache.h.
//
// A map is 8-bit RGBA. Image files store colours sRGB-encoded, while filtering and lighting must
// happen in linear colour; a map that holds numbers rather than colours holds them as they are.
// The image's format tells the sampler which its bytes are: which format each of a material's
// maps gets is exercise texel_format (texture.cpp; docs/lighting.md).
#pragma once

#include "image.h"
#include "image_io.h"
#include "vk_context.h"

#include <cstdint>

// How the mip chain is made: blits on the GPU (vkCmdBlitImage, linear filter) when the format
// supports linear blits and every level halves both sides exactly, else the box filter below on
// the CPU. (A linear blit from an odd size samples two texels where the box needs three.)
enum class MipSource { Auto, Cpu };

// What a map's texels are, as the CPU's box filter averages them: sRGB-encoded colours (decoded
// to linear first) or plain numbers.
enum class TexelEncoding { Srgb, Linear };

// A material's three maps, in the order of their bindings (lit.frag, set 1: 0, 1, 2).
enum class MapKind { Albedo, Specular, Emissive };

// The format a map of `kind` is stored in: how the sampler reads its bytes (exercise texel_format).
VkFormat format_of(MapKind kind);

struct Texture {
    lab::Image image;  // 8-bit RGBA (upload_texture's format), SHADER_READ_ONLY_OPTIMAL, the view covers every level
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t levels = 1;
};

// floor(log2(max(width, height))) + 1: levels down to 1×1.
uint32_t mip_level_count(uint32_t width, uint32_t height);

// The next level of `image` on the CPU: the box filter. Level size max(⌊w/2⌋, 1) × max(⌊h/2⌋, 1);
// each texel is the mean of the parent area it covers, w/⌊w/2⌋ × h/⌊h/2⌋ texels, with partly
// covered texels weighted by the part (an even side: 2 texels; 3 → 1: all three; 5 → 2: 1, 1, ½).
// sRGB is decoded to linear before averaging and encoded after; alpha and linear data as they are.
lab::Image8 downsample(const lab::Image8& image, TexelEncoding encoding);
// True when a linear blit makes exactly that level from `width` × `height`: each side even, or 1.
bool blit_halves_exactly(uint32_t width, uint32_t height);

// Uploads `pixels` as an image of `format` (VK_FORMAT_R8G8B8A8_SRGB or _UNORM; a staging buffer and
// one submit); with `mipmaps` the whole chain: blits where the device has linear blits for the
// format, else the CPU fallback, which averages in the space the format reads (`--dev-no-blit`
// makes a device without blits, so tests run that path on any device).
Texture upload_texture(const lab::VulkanContext& vk, const lab::Image8& pixels, bool mipmaps, MipSource source = MipSource::Auto,
                       VkFormat format = VK_FORMAT_R8G8B8A8_UNORM);
