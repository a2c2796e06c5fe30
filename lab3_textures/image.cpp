// image.cpp — creating an image, binding its memory, making its views; the layout barrier
// (image.h).
#include "image.h"

#include "vk_check.h"

VkImageCreateInfo image_info_2d(VkExtent2D extent, VkFormat format, VkImageUsageFlags usage, uint32_t mip_levels) {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {extent.width, extent.height, 1};
    info.mipLevels = mip_levels;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    // OPTIMAL: the texels in the driver's own arrangement (tiles), fast to sample and render to,
    // which the CPU cannot address: pixels arrive by a copy from a buffer (texture.cpp).
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    // Every use the image will ever have (sampled, copied into, blitted from, rendered to): the
    // driver may lay it out for exactly these, and any other use is an error the validation
    // layer reports.
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;  // one queue family uses it
    // UNDEFINED: nothing to keep yet; the first barrier (or render pass) gives it a layout.
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    return info;
}

lab::Image create_image(const lab::VulkanContext& vk, const VkImageCreateInfo& info, VkImageViewType view_type,
                        VkImageAspectFlags aspect) {
    VkDevice device = vk.device();
    lab::Image result;
    VkImage image;
    VK_CHECK(vkCreateImage(device, &info, nullptr, &image));
    result.image = lab::Handle<VkImage>(image, [device](VkImage i) { vkDestroyImage(device, i, nullptr); });

    // A new image has no memory. The driver says how much it needs, aligned how, and which memory
    // types may hold it (memoryTypeBits); of those we want DEVICE_LOCAL, the GPU's own memory
    // (fastest to sample; on a discrete GPU the CPU cannot map it). The allocator hands out a
    // range of a larger block (memory.h), kept apart from buffers' blocks (`image`: true).
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, image, &req);
    result.memory = vk.allocator().allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, /*image=*/true);
    VK_CHECK(vkBindImageMemory(device, image, result.memory.memory(), result.memory.offset()));

    // Shaders and framebuffers never see an image itself, only a view of it.
    result.view = create_view(vk, image, view_type, info.format, {aspect, 0, info.mipLevels, 0, info.arrayLayers});
    return result;
}

lab::Image create_image_2d(const lab::VulkanContext& vk, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                           VkImageAspectFlags aspect, uint32_t mip_levels) {
    return create_image(vk, image_info_2d(extent, format, usage, mip_levels), VK_IMAGE_VIEW_TYPE_2D, aspect);
}

lab::Handle<VkImageView> create_view(const lab::VulkanContext& vk, VkImage image, VkImageViewType view_type,
                                     VkFormat format, const VkImageSubresourceRange& range) {
    VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    info.image = image;
    info.viewType = view_type;
    info.format = format;  // the image's (a compatible one could reinterpret its texels)
    info.subresourceRange = range;
    VkImageView view;
    VK_CHECK(vkCreateImageView(vk.device(), &info, nullptr, &view));
    VkDevice device = vk.device();
    return lab::Handle<VkImageView>(view, [device](VkImageView v) { vkDestroyImageView(device, v, nullptr); });
}

void image_barrier(VkCommandBuffer cmd, VkImage image, uint32_t base_level, uint32_t level_count, VkImageLayout from,
                   VkImageLayout to, VkAccessFlags src_access, VkAccessFlags dst_access, VkPipelineStageFlags src_stage,
                   VkPipelineStageFlags dst_stage, uint32_t layer_count) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    // The memory dependency: the writes of `src_access` (e.g. a copy's TRANSFER_WRITE) made
    // available and visible to `dst_access` (e.g. the fragment shader's SHADER_READ). Without it
    // a reader may see stale texels, even after the writer's stage has finished.
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    // The layout transition, done between the two halves of the dependency. `from` must be the
    // layout the levels are in (UNDEFINED: their contents may be thrown away).
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;  // no hand-over between queue families
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, base_level, level_count, 0, layer_count};
    // The execution dependency: `dst_stage` of later commands waits for `src_stage` of earlier
    // ones (TOP_OF_PIPE as the source: wait for nothing).
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}
