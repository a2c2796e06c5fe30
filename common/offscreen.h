// offscreen.h — render passes into images the lab samples afterwards (lab 4's shadow maps):
// the render pass, framebuffers, beginning a pass, samplers for depth maps, format checks.
#pragma once

#include "vk_context.h"
#include "vk_handle.h"

#include <vector>

namespace lab {

// Does the device support `features` for `format` (optimal tiling)?
bool format_supports(const VulkanContext& vk, VkFormat format, VkFormatFeatureFlags features);

// A one-subpass render pass into `color` (VK_FORMAT_UNDEFINED: none) and `depth`, both cleared.
// The colour ends SHADER_READ_ONLY; the depth is kept and ends DEPTH_STENCIL_READ_ONLY when there
// is no colour (a depth map), else it is dropped. Its dependencies order the pass after earlier
// shader reads of the same images (earlier frames) and before the vertex / fragment shaders that
// read them next.
Handle<VkRenderPass> make_offscreen_pass(const VulkanContext& vk, VkFormat color, VkFormat depth);

// A square framebuffer of `size`² over `views` (in the pass's attachment order).
Handle<VkFramebuffer> make_square_framebuffer(const VulkanContext& vk, VkRenderPass pass,
                                              const std::vector<VkImageView>& views, uint32_t size);

// Begins `pass` on `framebuffer` (size²): colour (if any) cleared to (1, 1, 0, 0), depth to 1;
// viewport and scissor cover the whole square.
void begin_offscreen_pass(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer framebuffer, uint32_t size, bool color);

// A sampler for depth maps: nearest or linear, optionally comparing (compare op LESS_OR_EQUAL:
// 1 where the reference ≤ the stored depth); outside the map it reads white (depth 1).
Handle<VkSampler> make_depth_sampler(const VulkanContext& vk, bool linear, bool compare);

}  // namespace lab
