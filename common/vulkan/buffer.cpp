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

Buffer Buffer::device_only(const VulkanContext& vk, VkDeviceSize size, VkBufferUsageFlags usage) {
    return Buffer(vk, size, usage, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
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

}  // namespace lab
