// buffer.h — a VkBuffer with its own memory (and Image, the same for an image and its view).
//
// Two kinds are enough for the labs:
//  - host-visible buffers, mapped once for their whole life (uniforms, storage
//    written every frame, readbacks);
//  - device-local buffers filled once through a staging copy (vertices, indices).
#pragma once

#include "memory.h"
#include "vk_context.h"

#include <cstddef>

namespace lab {

class Buffer {
public:
    Buffer() = default;
    Buffer(Buffer&&) noexcept = default;
    // Not defaulted: member-wise assignment would free the old memory before the old buffer.
    Buffer& operator=(Buffer&& other) noexcept;
    // A host-visible, coherent, persistently mapped buffer.
    static Buffer host_visible(const VulkanContext& vk, VkDeviceSize size, VkBufferUsageFlags usage);
    // A device-local buffer with undefined contents, for the device alone to fill (shaders, fills).
    static Buffer device_only(const VulkanContext& vk, VkDeviceSize size, VkBufferUsageFlags usage);
    // A device-local buffer holding `data` (uploaded through a temporary staging buffer).
    static Buffer device_local(const VulkanContext& vk, const void* data, VkDeviceSize size,
                               VkBufferUsageFlags usage);

    VkBuffer get() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; }  // nullptr for device-local buffers

private:
    Buffer(const VulkanContext& vk, VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags memory);

    // Members are destroyed in reverse order: the buffer first, then the memory bound to it
    // (a range of a larger block: see memory.h).
    Allocation memory_;
    Handle<VkBuffer> buffer_;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

// An image with its memory and one view. Destroyed in reverse order: view, image, then the memory
// bound to the image. (Creating one: render_target.h for the targets' own images; lab 3 teaches it.)
struct Image {
    Allocation memory;
    Handle<VkImage> image;
    Handle<VkImageView> view;

    Image() = default;
    Image(Image&&) noexcept = default;
    Image& operator=(Image&& other) noexcept;  // destroys the old image in the right order first
};

}  // namespace lab
