// depth_view.h — depth images on screen as grey squares, near black and far white: the shadow-map
// view (`--dev-shadow-view`, the Shadows panel). Drawn inside the frame's render pass, over the
// picture, with a plain (non-comparing) sampler: the shader reads the stored depth itself.
#pragma once

#include "offscreen.h"
#include "pipeline_builder.h"
#include "vk_context.h"

#include <glm/glm.hpp>

#include <map>
#include <string>
#include <vector>

class DepthView {
public:
    // `pass`: the render pass it draws in; `max_images`: how many different views it may show
    // (each gets its descriptor set on first use; the views must outlive this object); the shaders
    // depth_view.vert / .frag come from `shader_dir`.
    DepthView(const lab::VulkanContext& vk, VkRenderPass pass, uint32_t max_images, const std::string& shader_dir);

    // Draws the layers of `target` (a depth image in DEPTH_STENCIL_READ_ONLY_OPTIMAL, e.g. a cube
    // map's six faces) as squares at the bottom centre of a frame of `extent`, three to a row, the
    // first row on top. `clip_to_view`: the inverse of the map's projection; each stored depth is
    // taken back through it to a distance and spread from near (black) to far (white), else a
    // perspective map looks nearly all white. The identity shows the depth as stored (orthographic).
    // `used`: the texels per side the map pass drew (0: all), the square shown.
    void draw(VkCommandBuffer cmd, const LayeredTarget& target, const glm::mat4& clip_to_view, VkExtent2D extent,
              uint32_t used = 0);

private:
    const lab::VulkanContext& vk_;
    lab::Handle<VkSampler> sampler_;
    lab::Handle<VkDescriptorSetLayout> set_layout_;
    lab::Handle<VkDescriptorPool> pool_;
    lab::PipelineBuilder::Result pipeline_;
    std::map<VkImageView, VkDescriptorSet> sets_;  // written once, on first use
    uint32_t max_images_;
};
