#include "buffer.h"

#include <cstring>

namespace lab {

namespace {
// Memory for a buffer or an image, of the first type with the wanted properties.
Handle<VkDeviceMemory> allocate_memory(const VulkanContext& vk, const VkMemoryRequirements& req,
                                       VkMemoryPropertyFlags properties) {
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = vk.find_memory_type(req.memoryTypeBits, properties);
    VkDeviceMemory memory;
    VK_CHECK(vkAllocateMemory(vk.device(), &alloc, nullptr, &memory));
    VkDevice device = vk.device();
    return Handle<VkDeviceMemory>(memory, [device](VkDeviceMemory m) { vkFreeMemory(device, m, nullptr); });
}
}  // namespace

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
    memory_ = allocate_memory(vk, req, memory);
    VK_CHECK(vkBindBufferMemory(device, buffer, memory_, 0));
    if (memory & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) VK_CHECK(vkMapMemory(device, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
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
    });
    return buffer;
}

Image create_image_2d(const VulkanContext& vk, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                      VkImageAspectFlags aspect, uint32_t mip_levels) {
    VkDevice device = vk.device();
    Image result;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {extent.width, extent.height, 1};
    info.mipLevels = mip_levels;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image;
    VK_CHECK(vkCreateImage(device, &info, nullptr, &image));
    result.image = Handle<VkImage>(image, [device](VkImage i) { vkDestroyImage(device, i, nullptr); });

    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, image, &req);
    result.memory = allocate_memory(vk, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VK_CHECK(vkBindImageMemory(device, image, result.memory, 0));

    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    view.subresourceRange = {aspect, 0, mip_levels, 0, 1};
    VkImageView image_view;
    VK_CHECK(vkCreateImageView(device, &view, nullptr, &image_view));
    result.view = Handle<VkImageView>(image_view, [device](VkImageView v) { vkDestroyImageView(device, v, nullptr); });
    return result;
}

}  // namespace lab
