// cube_map.cpp — the cube-compatible image and its views (cube_map.h).
#include "cube_map.h"

lab::Image create_image_cube(const lab::VulkanContext& vk, uint32_t size, VkFormat format, VkImageUsageFlags usage,
                             VkImageAspectFlags aspect) {
    // Lab 3's 2D image (image.h), changed in two places: six layers, and CUBE_COMPATIBLE, without
    // which a view may see the layers only as 2D images or a 2D array, never as a cube. The faces
    // are square: a cube view needs width == height.
    VkImageCreateInfo info = image_info_2d({size, size}, format, usage, 1);
    info.arrayLayers = 6;
    info.flags = VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT;
    return create_image(vk, info, VK_IMAGE_VIEW_TYPE_CUBE, aspect);
}

lab::Handle<VkImageView> create_layer_view(const lab::VulkanContext& vk, VkImage image, VkFormat format,
                                           VkImageAspectFlags aspect, uint32_t layer) {
    // A framebuffer renders into the layers its attachments' views cover; one face per pass (each
    // face has its own view-projection matrix), so one layer per view.
    return create_view(vk, image, VK_IMAGE_VIEW_TYPE_2D, format, {aspect, 0, 1, layer, 1});
}

lab::Handle<VkImageView> create_faces_view(const lab::VulkanContext& vk, VkImage image, VkFormat format,
                                           VkImageAspectFlags aspect) {
    return create_view(vk, image, VK_IMAGE_VIEW_TYPE_2D_ARRAY, format, {aspect, 0, 1, 0, 6});
}
