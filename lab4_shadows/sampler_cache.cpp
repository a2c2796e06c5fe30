// sampler_cache.cpp — a VkSampler from a material's sampler settings (the scene's "sampler").
#include "sampler_cache.h"

#include "vk_check.h"

#include <algorithm>
#include <cstdio>

// Anisotropic filtering is an optional device feature (samplerAnisotropy, enabled by the context
// when present) with a limit (maxSamplerAnisotropy, 16 on most devices): ask for more and the
// sampler is invalid, so the request is clamped here and the student is told.
float SamplerCache::effective_anisotropy(int requested) const {
    if (requested <= 1 || !vk_.enabled_features().samplerAnisotropy) return 1.0f;
    return std::min(float(requested), vk_.properties().limits.maxSamplerAnisotropy);
}

// The sampler a material's settings ask for, `anisotropy` already clamped to the device: only a
// choice of fields, no device, so it can be checked field by field.
VkSamplerCreateInfo sampler_info(const lab::SamplerDesc& desc, float anisotropy) {
    using S = lab::SamplerDesc;
    // EXERCISE sampler_settings: fill `info` from `desc`: which filter for magnification and minification, which mipmap mode, which address mode on each axis, whether anisotropy is on and how much (`anisotropy` is already clamped to the device), and how "mipmaps": "none" keeps the sampler on level 0. Read VkSamplerCreateInfo in the spec ("Samplers") and lab::SamplerDesc in scene.h. Wrong: every texture blocky and shimmering, mirror wrap repeating, the far floor a moiré. Checked by SamplerSettings.*, Lab3Render.MinifiedFloorTrilinear, Lab3Render.DistortedSamplingWholeOffsetMirror, Lab3Render.AlbedoMapMagnified.
    // STUB: VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};  // nearest, repeat, level 0 only
    const VkFilter filter = desc.filter == S::Filter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
    const VkSamplerAddressMode wrap = desc.wrap == S::Wrap::Repeat  ? VK_SAMPLER_ADDRESS_MODE_REPEAT
                                      : desc.wrap == S::Wrap::Clamp ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE
                                                                    : VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = filter;
    info.minFilter = filter;
    info.mipmapMode = desc.mipmaps == S::Mipmaps::Linear ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = info.addressModeV = info.addressModeW = wrap;
    info.anisotropyEnable = anisotropy > 1.0f ? VK_TRUE : VK_FALSE;
    info.maxAnisotropy = anisotropy;
    info.minLod = 0.0f;
    // "mipmaps": "none" reads level 0 only (the spec's way to switch mipmapping off).
    info.maxLod = desc.mipmaps == S::Mipmaps::None ? 0.0f : VK_LOD_CLAMP_NONE;
    info.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_BLACK;
    // END EXERCISE
    return info;
}

VkSampler SamplerCache::get(const lab::SamplerDesc& material) {
    // "anisotropic": "probes": the fragment shader filters anisotropically itself (lit.frag, probes()),
    // so the VkSampler has no hardware anisotropy: the plain trilinear one, shared with "anisotropy": 1.
    lab::SamplerDesc desc = material;
    if (desc.anisotropic == lab::SamplerDesc::Anisotropic::Probes) {
        desc.anisotropy = 1;
        desc.anisotropic = lab::SamplerDesc::Anisotropic::Sampler;
    }
    auto it = samplers_.find(desc);
    if (it != samplers_.end()) return it->second;
    const float anisotropy = effective_anisotropy(desc.anisotropy);
    if (desc.anisotropy > 1 && anisotropy < float(desc.anisotropy)) {
        char line[160];
        std::snprintf(line, sizeof line, "anisotropy %d clamped to %g (the device limit%s)", desc.anisotropy,
                      double(anisotropy),
                      vk_.enabled_features().samplerAnisotropy ? "" : ": no anisotropic filtering");
        warnings_.push_back(line);
        std::fprintf(stderr, "warning: %s\n", line);
    }
    const VkSamplerCreateInfo info = sampler_info(desc, anisotropy);
    VkSampler sampler;
    VK_CHECK(vkCreateSampler(vk_.device(), &info, nullptr, &sampler));
    VkDevice device = vk_.device();
    return samplers_.emplace(desc, lab::Handle<VkSampler>(sampler, [device](VkSampler s) { vkDestroySampler(device, s, nullptr); }))
        .first->second;
}
