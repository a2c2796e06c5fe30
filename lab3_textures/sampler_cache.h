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

// "anisotropic": "auto" made concrete for a device; any other setting comes back unchanged. Who
// filters best depends on the device: a CPU rasterizer (lavapipe) pays per texel read, and its
// sampler's anisotropic filter is slower and further from the truth than a few probes along the
// footprint's long axis in the shader, so it gets the probes (`anisotropy` of them at most). A GPU's
// texture unit filters anisotropically in hardware, one lookup in the shader where n probes are n;
// on an NVIDIA H200 its anisotropy 16 came closer to the truth than 4 probes, though not than 8 or
// 16. So a GPU gets the sampler at the degree it supports (up to 16); one without the feature gets
// probes. With "anisotropy": 1 both mean off. Lab 3's README, "What it costs", has the figures.
lab::SamplerDesc choose_anisotropic(const lab::SamplerDesc& desc, VkPhysicalDeviceType type,
                                    const VkPhysicalDeviceLimits& limits, bool sampler_anisotropy);
// "CPU device", "discrete GPU", …: the device's kind, as the startup line and the panel name it.
const char* device_kind(VkPhysicalDeviceType type);

// A material whose anisotropy is done by probes in the shader gets the sampler without it.
// Anisotropy is clamped to the device limit (or off when the device lacks the feature) with one
// warning line each time a request is clamped.
class SamplerCache {
public:
    explicit SamplerCache(const lab::VulkanContext& vk) : vk_(vk) {}
    VkSampler get(const lab::SamplerDesc& desc);
    // choose_anisotropic for this cache's device.
    lab::SamplerDesc resolve(const lab::SamplerDesc& desc) const;
    // What "auto" picks on this device, one line: "anisotropic: auto -> probes (CPU device)" (ASCII:
    // the panel's default font has no arrow).
    std::string auto_choice() const;
    size_t size() const { return samplers_.size(); }
    // The anisotropy the device really uses for `requested` (1 = off).
    float effective_anisotropy(int requested) const;
    const std::vector<std::string>& warnings() const { return warnings_; }

private:
    const lab::VulkanContext& vk_;
    std::map<lab::SamplerDesc, lab::Handle<VkSampler>> samplers_;
    std::vector<std::string> warnings_;
};
