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

lab::SamplerDesc choose_anisotropic(const lab::SamplerDesc& desc, VkPhysicalDeviceType type,
                                    const VkPhysicalDeviceLimits& limits, bool sampler_anisotropy) {
    using A = lab::SamplerDesc::Anisotropic;
    if (desc.anisotropic != A::Auto) return desc;  // an explicit choice wins
    lab::SamplerDesc chosen = desc;
    if (type == VK_PHYSICAL_DEVICE_TYPE_CPU || !sampler_anisotropy) {
        chosen.anisotropic = A::Probes;
        return chosen;
    }
    // Integrated, discrete, virtual and "other" devices: the texture unit's own filter.
    chosen.anisotropic = A::Sampler;
    if (desc.anisotropy > 1) chosen.anisotropy = std::clamp(int(limits.maxSamplerAnisotropy), 1, 16);
    return chosen;
}

const char* device_kind(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU device";
    default: return "other device";
    }
}

lab::SamplerDesc SamplerCache::resolve(const lab::SamplerDesc& desc) const {
    return choose_anisotropic(desc, vk_.properties().deviceType, vk_.properties().limits,
                              vk_.enabled_features().samplerAnisotropy);
}

std::string SamplerCache::auto_choice() const {
    lab::SamplerDesc probe;  // anisotropy 16: what "auto" does where anisotropy is on
    probe.anisotropic = lab::SamplerDesc::Anisotropic::Auto;
    const lab::SamplerDesc chosen = resolve(probe);
    const std::string by = chosen.anisotropic == lab::SamplerDesc::Anisotropic::Probes
                               ? "probes"
                               : "the sampler's anisotropy, up to " + std::to_string(chosen.anisotropy);
    return "anisotropic: auto -> " + by + " (" + device_kind(vk_.properties().deviceType) + ")";
}

VkSampler SamplerCache::get(const lab::SamplerDesc& material) {
    // "anisotropic": "probes": the fragment shader filters anisotropically itself (lit.frag, probes()),
    // so the VkSampler has no hardware anisotropy: the plain trilinear one, shared with "anisotropy": 1.
    lab::SamplerDesc desc = resolve(material);
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
