#include "render_target.h"

namespace lab {

Handle<VkRenderPass> make_render_pass(const VulkanContext& vk, VkFormat color_format, VkImageLayout color_final_layout) {
    VkAttachmentDescription attachments[2] = {};
    attachments[0].format = color_format;
    attachments[0].samples = VK_SAMPLE_COUNT_1_BIT;
    attachments[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    attachments[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachments[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachments[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachments[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // cleared anyway
    attachments[0].finalLayout = color_final_layout;
    attachments[1].format = vk.depth_format();
    attachments[1].samples = VK_SAMPLE_COUNT_1_BIT;
    attachments[1].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    attachments[1].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;  // depth is not needed after the pass
    attachments[1].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachments[1].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachments[1].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    attachments[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;

    VkAttachmentReference color_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &color_ref;
    subpass.pDepthStencilAttachment = &depth_ref;

    // The previous frame's writes (colour, depth, a copy into the colour image) and its readback
    // copy's reads must finish before this frame clears the same attachments.
    VkSubpassDependency dependencies[4] = {};
    VkSubpassDependency& dependency = dependencies[0];
    dependency.srcSubpass = VK_SUBPASS_EXTERNAL;
    dependency.dstSubpass = 0;
    dependency.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
                              VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependency.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                               VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    dependency.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
    dependency.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;

    // ...and this frame's colour must be written before anyone copies it out (headless readback)
    // or copies into it (a window's opaque UI panels).
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;

    // Lab 4's translucent layers: fragment shaders write per-pixel lists that a later draw in the
    // same pass reads. A barrier inside a render pass is allowed only where the pass declares a
    // dependency of its subpass on itself that covers it: this one (by region: each pixel reads
    // what its own fragments wrote).
    VkSubpassDependency& self = dependencies[2];
    self.srcSubpass = 0;
    self.dstSubpass = 0;
    self.srcStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    self.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    self.dstStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    self.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    self.dependencyFlags = VK_DEPENDENCY_BY_REGION_BIT;

    // ...and the counts those shaders write into host-visible memory are read by the host after
    // the frame's fence, which alone does not make device writes visible to the host.
    dependencies[3].srcSubpass = 0;
    dependencies[3].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[3].srcStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    dependencies[3].srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    dependencies[3].dstStageMask = VK_PIPELINE_STAGE_HOST_BIT;
    dependencies[3].dstAccessMask = VK_ACCESS_HOST_READ_BIT;

    return create_render_pass(vk, 2, attachments, subpass, 4, dependencies);
}

Handle<VkRenderPass> create_render_pass(const VulkanContext& vk, uint32_t attachment_count,
                                        const VkAttachmentDescription* attachments, const VkSubpassDescription& subpass,
                                        uint32_t dependency_count, const VkSubpassDependency* dependencies) {
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = attachment_count;
    info.pAttachments = attachments;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = dependency_count;
    info.pDependencies = dependencies;
    VkRenderPass pass;
    VK_CHECK(vkCreateRenderPass(vk.device(), &info, nullptr, &pass));
    VkDevice device = vk.device();
    return Handle<VkRenderPass>(pass, [device](VkRenderPass p) { vkDestroyRenderPass(device, p, nullptr); });
}

Handle<VkFramebuffer> make_framebuffer(const VulkanContext& vk, VkRenderPass pass,
                                       std::initializer_list<VkImageView> views, VkExtent2D extent) {
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = pass;
    info.attachmentCount = uint32_t(views.size());
    info.pAttachments = views.begin();
    info.width = extent.width;
    info.height = extent.height;
    info.layers = 1;
    VkFramebuffer framebuffer;
    VK_CHECK(vkCreateFramebuffer(vk.device(), &info, nullptr, &framebuffer));
    VkDevice device = vk.device();
    return Handle<VkFramebuffer>(framebuffer, [device](VkFramebuffer f) { vkDestroyFramebuffer(device, f, nullptr); });
}

Image create_target_image(const VulkanContext& vk, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                          VkImageAspectFlags aspect) {
    // 2D, one level, one layer, one sample, optimal tiling, exclusive, contents undefined.
    const VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, nullptr, 0, VK_IMAGE_TYPE_2D, format,
                                 {extent.width, extent.height, 1}, 1, 1, VK_SAMPLE_COUNT_1_BIT,
                                 VK_IMAGE_TILING_OPTIMAL, usage, VK_SHARING_MODE_EXCLUSIVE, 0, nullptr,
                                 VK_IMAGE_LAYOUT_UNDEFINED};
    VkDevice device = vk.device();
    VkImage image;
    VK_CHECK(vkCreateImage(device, &info, nullptr, &image));
    Image result;
    result.image = Handle<VkImage>(image, [device](VkImage i) { vkDestroyImage(device, i, nullptr); });
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, image, &req);
    result.memory = vk.allocator().allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, /*image=*/true);
    VK_CHECK(vkBindImageMemory(device, image, result.memory.memory(), result.memory.offset()));
    result.view = create_target_view(vk, image, format, aspect);
    return result;
}

Handle<VkImageView> create_target_view(const VulkanContext& vk, VkImage image, VkFormat format,
                                       VkImageAspectFlags aspect) {
    const VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, nullptr, 0, image, VK_IMAGE_VIEW_TYPE_2D,
                                     format, {}, {aspect, 0, 1, 0, 1}};
    VkDevice device = vk.device();
    VkImageView view;
    VK_CHECK(vkCreateImageView(device, &info, nullptr, &view));
    return Handle<VkImageView>(view, [device](VkImageView v) { vkDestroyImageView(device, v, nullptr); });
}

void target_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags src_access,
                    VkAccessFlags dst_access, VkPipelineStageFlags src_stage, VkPipelineStageFlags dst_stage) {
    const VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, nullptr, src_access, dst_access, from, to,
                                       VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, image,
                                       {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

FrameSlots::FrameSlots(const VulkanContext& vk) : vk_(vk) {
    VkDevice device = vk.device();
    for (uint32_t slot = 0; slot < RenderTarget::kFramesInFlight; ++slot) {
        VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool_info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;  // re-recorded every frame
        pool_info.queueFamilyIndex = vk.queue_family();
        VkCommandPool pool;
        VK_CHECK(vkCreateCommandPool(device, &pool_info, nullptr, &pool));
        pools_[slot] = Handle<VkCommandPool>(pool, [device](VkCommandPool p) { vkDestroyCommandPool(device, p, nullptr); });

        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = pool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        VK_CHECK(vkAllocateCommandBuffers(device, &alloc, &commands_[slot]));  // freed with the pool
    }

    for (auto& fence : fences_) {
        VkFenceCreateInfo info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        info.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // the first wait() returns at once
        VkFence f;
        VK_CHECK(vkCreateFence(device, &info, nullptr, &f));
        fence = Handle<VkFence>(f, [device](VkFence x) { vkDestroyFence(device, x, nullptr); });
    }
}

void FrameSlots::wait(uint32_t slot) const {
    VkFence fence = fences_[slot];
    VK_CHECK(vkWaitForFences(vk_.device(), 1, &fence, VK_TRUE, UINT64_MAX));
}

void FrameSlots::reset_fence(uint32_t slot) const {
    VkFence fence = fences_[slot];
    VK_CHECK(vkResetFences(vk_.device(), 1, &fence));
}

void FrameSlots::reset_commands(uint32_t slot) const { VK_CHECK(vkResetCommandPool(vk_.device(), pools_[slot], 0)); }

void begin_render_pass(const Frame& frame, VkRenderPass pass, VkFramebuffer framebuffer, const glm::vec3& clear_linear,
                       const BeforePass& before_pass) {
    VkCommandBuffer cmd = frame.cmd;
    const VkExtent2D extent = frame.extent;
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    if (before_pass) before_pass(frame);

    VkClearValue clears[2];
    clears[0].color = {{clear_linear.r, clear_linear.g, clear_linear.b, 1.0f}};  // the *_SRGB target encodes it
    clears[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    info.renderPass = pass;
    info.framebuffer = framebuffer;
    info.renderArea = {{0, 0}, extent};
    info.clearValueCount = 2;
    info.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &info, VK_SUBPASS_CONTENTS_INLINE);

    VkViewport viewport{0.0f, 0.0f, float(extent.width), float(extent.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, extent};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace lab
