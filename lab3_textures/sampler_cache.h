// sampler_cache.h — the samplers lab 3's materials ask for: one VkSampler per distinct setting.
//
// A sampler is how the shader reads a texture: the filter between texels (nearest or linear),
// between mip levels (none, nearest, linear), the wrap mode outside [0, 1], and anisotropic
// filtering for surfaces seen at a grazing angle. Samplers are independent of images, so
// materials with the same settings share one (sampler_cache.cpp makes them).
#pragma once

#include "scene.h"
#include "vk_context.h"
#include "vk_handle.h"

#include <map>
#include <string>
#include <vector>

// The VkSamplerCreateInfo for `desc` with `anisotropy` (already clamped; 1 = off).
VkSamplerCreateInfo sampler_info(const lab::SamplerDesc& desc, float anisotropy);

// A material whose anisotropy is done by probes in the shader gets the sampler without it.
// Anisotropy is clamped to the device limit (or off when the device lacks the feature) with one
// warning line each time a request is clamped.
class SamplerCache {
public:
    explicit SamplerCache(const lab::VulkanContext& vk) : vk_(vk) {}
    VkSampler get(const lab::SamplerDesc& desc);
    size_t size() const { return samplers_.size(); }
    // The anisotropy the device really uses for `requested` (1 = off).
    float effective_anisotropy(int requested) const;
    const std::vector<std::string>& warnings() const { return warnings_; }

private:
    const lab::VulkanContext& vk_;
    std::map<lab::SamplerDesc, lab::Handle<VkSampler>> samplers_;
    std::vector<std::string> warnings_;
};
