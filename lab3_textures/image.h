// image.h — an image in device memory, its view, and the barrier that changes its layout.
//
// Lab 3's textures are the first images a lab makes itself (the frame's colour and depth images
// belong to the render target, common/). An image is three objects: the VkImage (size, format,
// levels, layers, and every use it will have), the device memory bound to it, and a view (which
// aspect, levels and layers a shader or framebuffer sees, and as what: 2D, cube, array). Where
// its texels sit in memory — its layout — depends on the next use (being copied into, being
// sampled); a barrier changes the layout and orders the accesses before it against those after.
#pragma once

#include "buffer.h"  // lab::Image: the memory, the image, the view (destroyed in reverse)
#include "vk_context.h"
#include "vk_handle.h"

#include <cstdint>

// A 2D image of `mip_levels` levels and one layer, optimally tiled, contents undefined: the
// description create_image() makes (other shapes start from it: more layers, other flags).
VkImageCreateInfo image_info_2d(VkExtent2D extent, VkFormat format, VkImageUsageFlags usage, uint32_t mip_levels);

// The image `info` describes, device-local memory bound to it, and a view of `view_type` over
// its `aspect` (colour or depth), every level and every layer.
lab::Image create_image(const lab::VulkanContext& vk, const VkImageCreateInfo& info, VkImageViewType view_type,
                        VkImageAspectFlags aspect);
// create_image() of image_info_2d() with a 2D view (a texture).
lab::Image create_image_2d(const lab::VulkanContext& vk, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                           VkImageAspectFlags aspect, uint32_t mip_levels = 1);
// A view of `range` (aspect, levels, layers) of `image`, seen as `view_type`.
lab::Handle<VkImageView> create_view(const lab::VulkanContext& vk, VkImage image, VkImageViewType view_type,
                                     VkFormat format, const VkImageSubresourceRange& range);

// Moves the colour levels [base_level, base_level + level_count) of `image` (of its first
// `layer_count` layers) from layout `from` to `to`: what `src_access` wrote in `src_stage` is made
// visible to `dst_access` in `dst_stage`, and nothing in `dst_stage` starts on those levels before
// the transition is done.
void image_barrier(VkCommandBuffer cmd, VkImage image, uint32_t base_level, uint32_t level_count, VkImageLayout from,
                   VkImageLayout to, VkAccessFlags src_access, VkAccessFlags dst_access, VkPipelineStageFlags src_stage,
                   VkPipelineStageFlags dst_stage, uint32_t layer_count = 1);
