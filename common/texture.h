// texture.h — textures on the GPU (lab 3): upload with a mip chain, and samplers.
//
// Every map is 8-bit RGBA in a *_SRGB format: the sampler decodes sRGB to linear before it
// filters, so filtering and lighting happen in linear colour (docs/lighting.md).
#pragma once

#include "buffer.h"
#include "image_io.h"
#include "texture_image.h"
#include "scene.h"
#include "vk_context.h"

#include <map>
#include <string>
#include <vector>

namespace lab {

// How the mip chain is made: blits on the GPU (vkCmdBlitImage, linear filter) when the format
// supports linear blits, else a 2×2 box filter in linear colour on the CPU.
enum class MipSource { Auto, Cpu };

struct Texture {
    Image image;  // VK_FORMAT_R8G8B8A8_SRGB, SHADER_READ_ONLY_OPTIMAL, the view covers every level
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t levels = 1;
};

// floor(log2(max(width, height))) + 1: levels down to 1×1.
uint32_t mip_level_count(uint32_t width, uint32_t height);

// The next level of `image` on the CPU: each texel the mean of its 2×2 parent texels in linear
// colour (an odd last row / column is averaged with itself), re-encoded to sRGB.
Image8 downsample_srgb(const Image8& image);

// Uploads `pixels` (a staging buffer and one submit); with `mipmaps` the whole chain. The
// environment variable LAB_MIPMAPS=cpu forces the CPU fallback (so tests can run that path on a
// device that has linear blits).
Texture upload_texture(const VulkanContext& vk, const Image8& pixels, bool mipmaps, MipSource source = MipSource::Auto);

// One VkSampler per distinct SamplerDesc. Anisotropy is clamped to the device limit (or off
// when the device lacks the feature) with one warning line each time a request is clamped.
class SamplerCache {
public:
    explicit SamplerCache(const VulkanContext& vk) : vk_(vk) {}
    VkSampler get(const SamplerDesc& desc);
    size_t size() const { return samplers_.size(); }
    // The anisotropy the device really uses for `requested` (1 = off).
    float effective_anisotropy(int requested) const;
    const std::vector<std::string>& warnings() const { return warnings_; }

private:
    const VulkanContext& vk_;
    std::map<SamplerDesc, Handle<VkSampler>> samplers_;
    std::vector<std::string> warnings_;
};

}  // namespace lab
