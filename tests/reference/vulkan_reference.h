// vulkan_reference.h — the oracle's answers about Vulkan objects, for the tests of lab 3's and lab
// 4's device code: what a sampler must hold for a material's settings or for a shadow lookup, and
// what a map's texels read as.
//
// Like the rest of tests/reference/, a student copy holds only this header and a prebuilt library
// (scripts/exercise.sh): the tests take their expected values from it, not from their own source.
#pragma once

#include "image_io.h"
#include "scene.h"
#include "vk_context.h"

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

namespace ref {

// The groups of VkSamplerCreateInfo fields that lab::SamplerDesc's settings decide.
enum class SamplerFields { Filter, Wrap, Mipmaps, Anisotropy };

// What is wrong in `got` for a sampler of `desc` with `anisotropy` (already clamped to the
// device), in the fields of `which`: one line per field, naming the field, what it holds and the
// spec's section to read; empty when every field is as the spec and scene.h's meaning of the
// settings ask. The largest map the labs load (16384 texels a side) must reach its last level.
std::vector<std::string> sampler_problems(const VkSamplerCreateInfo& got, const lab::SamplerDesc& desc,
                                          float anisotropy, SamplerFields which);

// What is wrong in `got` for lab 4's comparison sampler (a depth map read through compareEnable):
// one line per field, as above: the rule is the lesson's (lab 4's README, exercise comparison_sampler).
std::vector<std::string> comparison_sampler_problems(const VkSamplerCreateInfo& got);

// Level 0 of a 2D colour image (`width` × `height`, in SHADER_READ_ONLY_OPTIMAL, made with
// TRANSFER_SRC usage) as the device converts its texels to numbers, RGBA floats row by row. The
// image is left in TRANSFER_SRC_OPTIMAL.
std::vector<float> texels_as_numbers(const lab::VulkanContext& vk, VkImage image, uint32_t width, uint32_t height);

// Every level of a 2D RGBA8 image of `levels` levels (level 0 `width` × `height`, in
// SHADER_READ_ONLY_OPTIMAL, made with TRANSFER_SRC usage), read back as bytes; the image is left
// as it was.
std::vector<lab::Image8> read_levels(const lab::VulkanContext& vk, VkImage image, uint32_t width, uint32_t height,
                                     uint32_t levels);

}  // namespace ref
