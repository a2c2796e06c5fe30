#include "depth_view.h"

#include "offscreen.h"
#include "shader.h"

#include <algorithm>
#include <stdexcept>

namespace {
constexpr VkShaderStageFlags kBoth = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
struct ViewConstants {  // depth_view.vert / .frag
    glm::vec4 rect;     // x0, y0, x1, y1 in normalized device coordinates
    glm::mat4 clip_to_view;
    glm::vec4 used;     // x: the share of the image's side the map pass drew (a square at its corner)
};
}  // namespace

DepthView::DepthView(const lab::VulkanContext& vk, VkRenderPass pass, uint32_t max_images, const std::string& shader_dir)
    : vk_(vk), sampler_(make_depth_sampler(vk, false, false)), max_images_(max_images) {
    const std::vector<lab::DescriptorBinding> bindings = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT}};
    set_layout_ = lab::make_descriptor_set_layout(vk, bindings);
    pool_ = lab::make_descriptor_pool(vk, bindings, max_images);
    const lab::Handle<VkShaderModule> vert = lab::load_shader(vk, shader_dir, "depth_view.vert");
    const lab::Handle<VkShaderModule> frag = lab::load_shader(vk, shader_dir, "depth_view.frag");
    pipeline_ = lab::PipelineBuilder()
                    .shaders(vert, frag)
                    .vertex_attributes(0)  // the rectangle comes from the vertex index
                    .descriptor_set(set_layout_)
                    .push_constants(kBoth, sizeof(ViewConstants))
                    .cull(VK_CULL_MODE_NONE)
                    .depth(false, false)
                    .build(vk, pass);
}

void DepthView::draw(VkCommandBuffer cmd, const LayeredTarget& target, const glm::mat4& clip_to_view, VkExtent2D extent,
                     uint32_t used) {
    if (target.layers() == 0) return;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.pipeline);
    const int n = int(target.layers()), columns = std::min(n, 3), rows = (n + columns - 1) / columns;
    const float height = rows == 1 ? 0.8f : 0.84f / float(rows);  // one square, in NDC (2 = the whole window)
    const float width = height * float(extent.height) / float(std::max(extent.width, 1u));
    for (int i = 0; i < n; ++i) {
        const VkImageView layer = target.layer(uint32_t(i));
        auto it = sets_.find(layer);
        if (it == sets_.end()) {
            if (sets_.size() >= max_images_) throw std::logic_error("DepthView: more images than max_images");
            const VkDescriptorSet set = lab::allocate_descriptor_set(vk_, pool_, set_layout_);
            lab::write_image_descriptors(vk_, set, 0, {{sampler_, layer, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL}});
            it = sets_.emplace(layer, set).first;
        }
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.layout, 0, 1, &it->second, 0, nullptr);
        const float x0 = (float(i % columns) - 0.5f * float(columns)) * (width + 0.01f);
        const float y1 = 0.98f - float(rows - 1 - i / columns) * (height + 0.01f);
        const float share = used == 0 ? 1.0f : float(used) / float(target.size);
        const ViewConstants constants{{x0, y1 - height, x0 + width, y1}, clip_to_view, glm::vec4(share, 0.0f, 0.0f, 0.0f)};
        vkCmdPushConstants(cmd, pipeline_.layout, kBoth, 0, sizeof constants, &constants);
        vkCmdDraw(cmd, 6, 1, 0, 0);
    }
}
