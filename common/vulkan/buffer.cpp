#include "buffer.h"

#include <cstring>
#include <utility>

namespace lab {


Buffer::Buffer(const VulkanContext& vk, VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags memory)
    : size_(size) {
    VkDevice device = vk.device();
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer;
    VK_CHECK(vkCreateBuffer(device, &info, nullptr, &buffer));
    buffer_ = Handle<VkBuffer>(buffer, [device](VkBuffer b) { vkDestroyBuffer(device, b, nullptr); });

    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, buffer, &req);
    memory_ = vk.allocator().allocate(req, memory, /*image=*/false);
    VK_CHECK(vkBindBufferMemory(device, buffer, memory_.memory(), memory_.offset()));
    mapped_ = memory_.mapped();  // host-visible blocks stay mapped
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
    if (this != &other) {
        Buffer old(std::move(*this));  // destroyed at the end of this scope: buffer, then memory
        memory_ = std::move(other.memory_);
        buffer_ = std::move(other.buffer_);
        size_ = std::exchange(other.size_, 0);
        mapped_ = std::exchange(other.mapped_, nullptr);
    }
    return *this;
}

Image& Image::operator=(Image&& other) noexcept {
    if (this != &other) {
        Image old(std::move(*this));  // destroyed at the end of this scope: view, image, memory
        memory = std::move(other.memory);
        image = std::move(other.image);
        view = std::move(other.view);
    }
    return *this;
}

Buffer Buffer::host_visible(const VulkanContext& vk, VkDeviceSize size, VkBufferUsageFlags usage) {
    return Buffer(vk, size, usage, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
}

Buffer Buffer::device_local(const VulkanContext& vk, const void* data, VkDeviceSize size, VkBufferUsageFlags usage) {
    Buffer staging = host_visible(vk, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    std::memcpy(staging.mapped(), data, size);
    Buffer buffer(vk, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    vk.run_once([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, 0, size};
        vkCmdCopyBuffer(cmd, staging.get(), buffer.get(), 1, &region);
        // The copy's writes must be available to whatever reads the buffer next (vertex input,
        // index fetch, shaders): a fence wait on the host alone does not make them so.
        VkBufferMemoryBarrier done{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
        done.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        done.dstAccessMask = VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_INDEX_READ_BIT |
                             VK_ACCESS_UNIFORM_READ_BIT | VK_ACCESS_SHADER_READ_BIT;
        done.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        done.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        done.buffer = buffer.get();
        done.offset = 0;
        done.size = VK_WHOLE_SIZE;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                                 VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                             0, 0, nullptr, 1, &done, 0, nullptr);
    });
    return buffer;
}

namespace {
Image create_image(const VulkanContext& vk, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                   VkImageAspectFlags aspect, uint32_t mip_levels, bool cube) {
    VkDevice device = vk.device();
    Image result;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.flags = cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {extent.width, extent.height, 1};
    info.mipLevels = mip_levels;
    info.arrayLayers = cube ? 6 : 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image;
    VK_CHECK(vkCreateImage(device, &info, nullptr, &image));
    result.image = Handle<VkImage>(image, [device](VkImage i) { vkDestroyImage(device, i, nullptr); });

    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, image, &req);
    result.memory = vk.allocator().allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, /*image=*/true);
    VK_CHECK(vkBindImageMemory(device, image, result.memory.memory(), result.memory.offset()));

    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image;
    view.viewType = cube ? VK_IMAGE_VIEW_TYPE_CUBE : VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    view.subresourceRange = {aspect, 0, mip_levels, 0, info.arrayLayers};
    VkImageView image_view;
    VK_CHECK(vkCreateImageView(device, &view, nullptr, &image_view));
    result.view = Handle<VkImageView>(image_view, [device](VkImageView v) { vkDestroyImageView(device, v, nullptr); });
    return result;
}
}  // namespace

void image_barrier(VkCommandBuffer cmd, VkImage image, uint32_t base, uint32_t count, VkImageLayout from,
                   VkImageLayout to, VkAccessFlags src_access, VkAccessFlags dst_access, VkPipelineStageFlags src_stage,
                   VkPipelineStageFlags dst_stage) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, base, count, 0, 1};
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

Image create_image_2d(const VulkanContext& vk, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                      VkImageAspectFlags aspect, uint32_t mip_levels) {
    return create_image(vk, extent, format, usage, aspect, mip_levels, false);
}

Image create_image_cube(const VulkanContext& vk, uint32_t size, VkFormat format, VkImageUsageFlags usage,
                        VkImageAspectFlags aspect) {
    return create_image(vk, {size, size}, format, usage, aspect, 1, true);
}

Handle<VkImageView> create_layer_view(const VulkanContext& vk, VkImage image, VkFormat format, VkImageAspectFlags aspect,
                                      uint32_t layer) {
    VkDevice device = vk.device();
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    view.subresourceRange = {aspect, 0, 1, layer, 1};
    VkImageView image_view;
    VK_CHECK(vkCreateImageView(device, &view, nullptr, &image_view));
    return Handle<VkImageView>(image_view, [device](VkImageView v) { vkDestroyImageView(device, v, nullptr); });
}

}  // namespace lab
