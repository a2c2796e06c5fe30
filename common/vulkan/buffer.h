// buffer.h — a VkBuffer with its own memory.
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

// An image with its memory and one view (render targets, textures).
// Destroyed in reverse order: view, image, then the memory bound to the image.
struct Image {
    Allocation memory;
    Handle<VkImage> image;
    Handle<VkImageView> view;

    Image() = default;
    Image(Image&&) noexcept = default;
    Image& operator=(Image&& other) noexcept;  // destroys the old image in the right order first
};

// A layout transition of the colour mip levels [base, base + count) of `image`, with the memory
// dependency from `src_access` in `src_stage` to `dst_access` in `dst_stage`.
void image_barrier(VkCommandBuffer cmd, VkImage image, uint32_t base, uint32_t count, VkImageLayout from,
                   VkImageLayout to, VkAccessFlags src_access, VkAccessFlags dst_access, VkPipelineStageFlags src_stage,
                   VkPipelineStageFlags dst_stage);

// `mip_levels` levels; the view covers all of them.
Image create_image_2d(const VulkanContext& vk, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                      VkImageAspectFlags aspect, uint32_t mip_levels = 1);
// A cube map: six square layers of `size`² (+X, −X, +Y, −Y, +Z, −Z), the view a cube view.
Image create_image_cube(const VulkanContext& vk, uint32_t size, VkFormat format, VkImageUsageFlags usage,
                        VkImageAspectFlags aspect);
// A 2D view of one layer of `image` (e.g. a cube face to render into).
Handle<VkImageView> create_layer_view(const VulkanContext& vk, VkImage image, VkFormat format, VkImageAspectFlags aspect,
                                      uint32_t layer);

}  // namespace lab
