// pipeline_builder.h — a small builder for the graphics pipelines the labs use.
//
// Defaults: triangle list, fill, back-face culling with counter-clockwise
// front faces (see docs/conventions.md: the projection flips Y), depth test
// LESS with writes on, no blending, dynamic viewport and scissor (so a window
// resize never rebuilds pipelines).
#pragma once

#include "mesh.h"
#include "vk_context.h"

#include <string>
#include <vector>

namespace lab {

// Which lab::Vertex members a shader reads, at locations 0, 1, 2, 3 in this order.
enum VertexAttribute : unsigned {
    kPosition = 1u << 0,
    kNormal = 1u << 1,
    kUv = 1u << 2,
    kTangent = 1u << 3,
};

class PipelineBuilder {
public:
    // `fragment` may be VK_NULL_HANDLE: a depth-only pipeline (lab 4's shadow pass).
    PipelineBuilder& shaders(VkShaderModule vertex, VkShaderModule fragment);
    PipelineBuilder& vertex_attributes(unsigned attribute_mask);
    // A vertex layout other than lab::Vertex (binding 0), e.g. ImGui's ImDrawVert.
    PipelineBuilder& vertex_layout(uint32_t stride, const std::vector<VkVertexInputAttributeDescription>& attributes);
    PipelineBuilder& descriptor_set(VkDescriptorSetLayout layout);
    PipelineBuilder& push_constants(VkShaderStageFlags stages, uint32_t size);
    PipelineBuilder& cull(VkCullModeFlags mode);
    // `compare`: the depth test's operator (default LESS).
    PipelineBuilder& depth(bool test, bool write, VkCompareOp compare = VK_COMPARE_OP_LESS);
    PipelineBuilder& alpha_blend(bool enabled);
    PipelineBuilder& topology(VkPrimitiveTopology topology);
    // Depth bias on, its constant and slope factors set per draw (vkCmdSetDepthBias).
    PipelineBuilder& dynamic_depth_bias();
    // Depth clamp (the device feature depthClamp must be enabled): geometry in front of the near
    // plane or beyond the far plane is not clipped but drawn at depth 0 or 1.
    PipelineBuilder& depth_clamp(bool enabled);
    // How many colour attachments the subpass has (default 1; 0: depth only), and their blend
    // state when neither the default (opaque) nor alpha_blend() fits.
    PipelineBuilder& color_attachments(uint32_t count);
    PipelineBuilder& color_blend(const VkPipelineColorBlendAttachmentState& state);
    // Specialization constants for both stages (the same constant_ids in the vertex and
    // fragment shader). `info` must stay valid until build().
    PipelineBuilder& specialization(const VkSpecializationInfo* info);

    struct Result {
        Handle<VkPipelineLayout> layout;
        Handle<VkPipeline> pipeline;
    };
    Result build(const VulkanContext& vk, VkRenderPass render_pass) const;

private:
    VkShaderModule vertex_ = VK_NULL_HANDLE;
    VkShaderModule fragment_ = VK_NULL_HANDLE;
    unsigned attributes_ = kPosition;
    uint32_t custom_stride_ = 0;  // != 0: custom_attributes_ instead of lab::Vertex
    std::vector<VkVertexInputAttributeDescription> custom_attributes_;
    std::vector<VkDescriptorSetLayout> set_layouts_;
    std::vector<VkPushConstantRange> push_ranges_;
    VkCullModeFlags cull_ = VK_CULL_MODE_BACK_BIT;
    bool depth_test_ = true;
    bool depth_write_ = true;
    VkCompareOp depth_compare_ = VK_COMPARE_OP_LESS;
    bool blend_ = false;
    bool depth_bias_ = false;
    bool depth_clamp_ = false;
    uint32_t color_attachments_ = 1;
    bool custom_blend_ = false;
    VkPipelineColorBlendAttachmentState blend_state_{};
    VkPrimitiveTopology topology_ = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    const VkSpecializationInfo* specialization_ = nullptr;
};

// One descriptor set layout from a list of (binding = index, type, stages).
struct DescriptorBinding {
    VkDescriptorType type;
    VkShaderStageFlags stages;
    uint32_t count = 1;  // an array of `count` descriptors
};
// Throws VulkanError (one line: which count, how many, the device's limit) when the set needs more
// descriptors than the device's limits allow; a device must refuse such a layout in a pipeline.
Handle<VkDescriptorSetLayout> make_descriptor_set_layout(const VulkanContext& vk,
                                                         const std::vector<DescriptorBinding>& bindings);
// What make_descriptor_set_layout checks: "" when `bindings` fit `limits` as one set, else the
// first count that does not ("… needs 24 samplers in the fragment stage; the device allows 16
// (maxPerStageDescriptorSamplers)"). Per-stage limits apply to all the sets a pipeline uses
// together; one set over them is already too many.
std::string descriptor_limit_problem(const VkPhysicalDeviceLimits& limits, const std::vector<DescriptorBinding>& bindings);
// A pool big enough for `max_sets` sets of the given bindings.
Handle<VkDescriptorPool> make_descriptor_pool(const VulkanContext& vk, const std::vector<DescriptorBinding>& bindings,
                                              uint32_t max_sets);
VkDescriptorSet allocate_descriptor_set(const VulkanContext& vk, VkDescriptorPool pool, VkDescriptorSetLayout layout);
// Points `binding` of `set` at a whole buffer.
void write_buffer_descriptor(const VulkanContext& vk, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                             VkBuffer buffer, VkDeviceSize size);
// Points `binding` (a combined image sampler) of `set` at `view` read through `sampler`.
void write_image_descriptor(const VulkanContext& vk, VkDescriptorSet set, uint32_t binding, VkSampler sampler,
                            VkImageView view);
// Points `binding` (an array of combined image samplers) of `set`, from element 0 on, at `images`
// (each with its sampler and the layout it is read in).
void write_image_descriptors(const VulkanContext& vk, VkDescriptorSet set, uint32_t binding,
                             const std::vector<VkDescriptorImageInfo>& images);

}  // namespace lab
