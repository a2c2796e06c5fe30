#include "pipeline_builder.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

namespace lab {

PipelineBuilder& PipelineBuilder::shaders(VkShaderModule vertex, VkShaderModule fragment) {
    vertex_ = vertex;
    fragment_ = fragment;
    return *this;
}
PipelineBuilder& PipelineBuilder::vertex_attributes(unsigned mask) {
    attributes_ = mask;
    return *this;
}
PipelineBuilder& PipelineBuilder::vertex_layout(uint32_t stride,
                                                const std::vector<VkVertexInputAttributeDescription>& attributes) {
    custom_stride_ = stride;
    custom_attributes_ = attributes;
    return *this;
}
PipelineBuilder& PipelineBuilder::descriptor_set(VkDescriptorSetLayout layout) {
    set_layouts_.push_back(layout);
    return *this;
}
PipelineBuilder& PipelineBuilder::push_constants(VkShaderStageFlags stages, uint32_t size) {
    push_ranges_.push_back({stages, 0, size});
    return *this;
}
PipelineBuilder& PipelineBuilder::cull(VkCullModeFlags mode) {
    cull_ = mode;
    return *this;
}
PipelineBuilder& PipelineBuilder::depth(bool test, bool write, VkCompareOp compare) {
    depth_test_ = test;
    depth_write_ = write;
    depth_compare_ = compare;
    return *this;
}
PipelineBuilder& PipelineBuilder::alpha_blend(bool enabled) {
    blend_ = enabled;
    return *this;
}
PipelineBuilder& PipelineBuilder::topology(VkPrimitiveTopology topology) {
    topology_ = topology;
    return *this;
}
PipelineBuilder& PipelineBuilder::dynamic_depth_bias() {
    depth_bias_ = true;
    return *this;
}
PipelineBuilder& PipelineBuilder::depth_clamp(bool enabled) {
    depth_clamp_ = enabled;
    return *this;
}
PipelineBuilder& PipelineBuilder::color_attachments(uint32_t count) {
    color_attachments_ = count;
    return *this;
}
PipelineBuilder& PipelineBuilder::color_blend(const VkPipelineColorBlendAttachmentState& state) {
    custom_blend_ = true;
    blend_state_ = state;
    return *this;
}
PipelineBuilder& PipelineBuilder::specialization(const VkSpecializationInfo* info) {
    specialization_ = info;
    return *this;
}

PipelineBuilder::Result PipelineBuilder::build(const VulkanContext& vk, VkRenderPass render_pass) const {
    VkDevice device = vk.device();
    Result result;

    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = static_cast<uint32_t>(set_layouts_.size());
    layout_info.pSetLayouts = set_layouts_.data();
    layout_info.pushConstantRangeCount = static_cast<uint32_t>(push_ranges_.size());
    layout_info.pPushConstantRanges = push_ranges_.data();
    VkPipelineLayout layout;
    VK_CHECK(vkCreatePipelineLayout(device, &layout_info, nullptr, &layout));
    result.layout = Handle<VkPipelineLayout>(layout, [device](VkPipelineLayout l) { vkDestroyPipelineLayout(device, l, nullptr); });

    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vertex_;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fragment_;
    stages[1].pName = "main";
    stages[0].pSpecializationInfo = specialization_;
    stages[1].pSpecializationInfo = specialization_;

    // Only the attributes the shader reads are declared (unused ones are a validation warning).
    const VkVertexInputBindingDescription binding{0, custom_stride_ ? custom_stride_ : uint32_t(sizeof(Vertex)),
                                                  VK_VERTEX_INPUT_RATE_VERTEX};
    const VkVertexInputAttributeDescription all[4] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
        {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)},
        {3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)},
    };
    std::vector<VkVertexInputAttributeDescription> attributes;
    for (unsigned i = 0; i < 4; ++i)
        if (!custom_stride_ && (attributes_ & (1u << i))) attributes.push_back(all[i]);
    if (custom_stride_) attributes = custom_attributes_;
    VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertex_input.vertexBindingDescriptionCount = attributes.empty() ? 0 : 1;
    vertex_input.pVertexBindingDescriptions = &binding;
    vertex_input.vertexAttributeDescriptionCount = static_cast<uint32_t>(attributes.size());
    vertex_input.pVertexAttributeDescriptions = attributes.data();

    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = topology_;

    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;

    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = cull_;
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    raster.depthBiasEnable = depth_bias_;
    raster.depthClampEnable = depth_clamp_;

    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;

    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = depth_test_;
    depth.depthWriteEnable = depth_write_;
    depth.depthCompareOp = depth_compare_;

    VkPipelineColorBlendAttachmentState blend_attachment{};
    blend_attachment.colorWriteMask =
        VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    if (blend_) {  // classic "over": src·α + dst·(1 − α)
        blend_attachment.blendEnable = VK_TRUE;
        blend_attachment.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
        blend_attachment.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        blend_attachment.colorBlendOp = VK_BLEND_OP_ADD;
        blend_attachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
        blend_attachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        blend_attachment.alphaBlendOp = VK_BLEND_OP_ADD;
    }
    if (custom_blend_) blend_attachment = blend_state_;
    VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend.attachmentCount = color_attachments_;
    blend.pAttachments = &blend_attachment;

    const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR,
                                             VK_DYNAMIC_STATE_DEPTH_BIAS};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = depth_bias_ ? 3 : 2;
    dynamic.pDynamicStates = dynamic_states;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.stageCount = fragment_ ? 2 : 1;
    info.pStages = stages;
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = layout;
    info.renderPass = render_pass;
    VkPipeline pipeline;
    VK_CHECK(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    result.pipeline = Handle<VkPipeline>(pipeline, [device](VkPipeline p) { vkDestroyPipeline(device, p, nullptr); });
    return result;
}

std::string descriptor_limit_problem(const VkPhysicalDeviceLimits& limits, const std::vector<DescriptorBinding>& bindings) {
    // A combined image sampler counts as a sampler and as a sampled image (the spec's limits for
    // both say so); every descriptor counts towards maxPerStageResources.
    struct Count {
        const char* what;
        bool (*counts)(VkDescriptorType);
        uint32_t per_stage, per_set;
        const char *per_stage_name, *per_set_name;
    };
    const auto sampler = [](VkDescriptorType t) {
        return t == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER || t == VK_DESCRIPTOR_TYPE_SAMPLER;
    };
    const auto sampled = [](VkDescriptorType t) {
        return t == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER || t == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    };
    const auto uniform = [](VkDescriptorType t) { return t == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER; };
    const auto storage = [](VkDescriptorType t) { return t == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER; };
    const auto any = [](VkDescriptorType) { return true; };
    const Count counts[] = {
        {"samplers", sampler, limits.maxPerStageDescriptorSamplers, limits.maxDescriptorSetSamplers,
         "maxPerStageDescriptorSamplers", "maxDescriptorSetSamplers"},
        {"sampled images", sampled, limits.maxPerStageDescriptorSampledImages, limits.maxDescriptorSetSampledImages,
         "maxPerStageDescriptorSampledImages", "maxDescriptorSetSampledImages"},
        {"uniform buffers", uniform, limits.maxPerStageDescriptorUniformBuffers, limits.maxDescriptorSetUniformBuffers,
         "maxPerStageDescriptorUniformBuffers", "maxDescriptorSetUniformBuffers"},
        {"storage buffers", storage, limits.maxPerStageDescriptorStorageBuffers, limits.maxDescriptorSetStorageBuffers,
         "maxPerStageDescriptorStorageBuffers", "maxDescriptorSetStorageBuffers"},
        {"descriptors", any, limits.maxPerStageResources, UINT32_MAX, "maxPerStageResources", ""},
    };
    const std::pair<VkShaderStageFlagBits, const char*> stages[] = {{VK_SHADER_STAGE_VERTEX_BIT, "vertex"},
                                                                     {VK_SHADER_STAGE_FRAGMENT_BIT, "fragment"}};
    const auto too_many = [](const char* what, uint64_t needed, const std::string& where, uint32_t allowed,
                             const char* limit) {
        return "a descriptor set needs " + std::to_string(needed) + " " + what + where + "; this device allows " +
               std::to_string(allowed) + " (" + limit + ")";
    };
    for (const Count& c : counts) {
        uint64_t in_set = 0;
        for (const DescriptorBinding& b : bindings)
            if (c.counts(b.type)) in_set += b.count;
        if (in_set > c.per_set) return too_many(c.what, in_set, " in one set", c.per_set, c.per_set_name);
        for (const auto& [stage, name] : stages) {
            uint64_t in_stage = 0;
            for (const DescriptorBinding& b : bindings)
                if (c.counts(b.type) && (b.stages & stage)) in_stage += b.count;
            if (in_stage > c.per_stage)
                return too_many(c.what, in_stage, std::string(" in the ") + name + " stage", c.per_stage, c.per_stage_name);
        }
    }
    return "";
}

Handle<VkDescriptorSetLayout> make_descriptor_set_layout(const VulkanContext& vk,
                                                         const std::vector<DescriptorBinding>& bindings) {
    // Checked here, before Vulkan sees it: a pipeline over a set past these limits is invalid use,
    // which a device may answer with anything.
    const std::string problem = descriptor_limit_problem(vk.properties().limits, bindings);
    if (!problem.empty()) throw VulkanError(problem);
    std::vector<VkDescriptorSetLayoutBinding> vk_bindings;
    for (uint32_t i = 0; i < bindings.size(); ++i)
        vk_bindings.push_back({i, bindings[i].type, bindings[i].count, bindings[i].stages, nullptr});
    VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    info.bindingCount = static_cast<uint32_t>(vk_bindings.size());
    info.pBindings = vk_bindings.data();
    VkDescriptorSetLayout layout;
    VK_CHECK(vkCreateDescriptorSetLayout(vk.device(), &info, nullptr, &layout));
    VkDevice device = vk.device();
    return Handle<VkDescriptorSetLayout>(layout, [device](VkDescriptorSetLayout l) { vkDestroyDescriptorSetLayout(device, l, nullptr); });
}

Handle<VkDescriptorPool> make_descriptor_pool(const VulkanContext& vk, const std::vector<DescriptorBinding>& bindings,
                                              uint32_t max_sets) {
    std::vector<VkDescriptorPoolSize> sizes;
    for (const auto& b : bindings) sizes.push_back({b.type, max_sets * b.count});
    VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    info.maxSets = max_sets;
    info.poolSizeCount = static_cast<uint32_t>(sizes.size());
    info.pPoolSizes = sizes.data();
    VkDescriptorPool pool;
    VK_CHECK(vkCreateDescriptorPool(vk.device(), &info, nullptr, &pool));
    VkDevice device = vk.device();
    return Handle<VkDescriptorPool>(pool, [device](VkDescriptorPool p) { vkDestroyDescriptorPool(device, p, nullptr); });
}

VkDescriptorSet allocate_descriptor_set(const VulkanContext& vk, VkDescriptorPool pool, VkDescriptorSetLayout layout) {
    VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    info.descriptorPool = pool;
    info.descriptorSetCount = 1;
    info.pSetLayouts = &layout;
    VkDescriptorSet set;
    VK_CHECK(vkAllocateDescriptorSets(vk.device(), &info, &set));
    return set;  // freed with its pool
}

void write_buffer_descriptor(const VulkanContext& vk, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                             VkBuffer buffer, VkDeviceSize size) {
    VkDescriptorBufferInfo buffer_info{buffer, 0, size};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = type;
    write.pBufferInfo = &buffer_info;
    vkUpdateDescriptorSets(vk.device(), 1, &write, 0, nullptr);
}

void write_image_descriptor(const VulkanContext& vk, VkDescriptorSet set, uint32_t binding, VkSampler sampler,
                            VkImageView view) {
    write_image_descriptors(vk, set, binding, {{sampler, view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}});
}

void write_image_descriptors(const VulkanContext& vk, VkDescriptorSet set, uint32_t binding,
                             const std::vector<VkDescriptorImageInfo>& images) {
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = binding;
    write.descriptorCount = uint32_t(images.size());
    write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    write.pImageInfo = images.data();
    vkUpdateDescriptorSets(vk.device(), 1, &write, 0, nullptr);
}

}  // namespace lab
