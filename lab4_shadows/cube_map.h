// cube_map.h — the image a point light's shadow map lives in, and the views each use needs.
//
// A point light shines every way, so its map is a cube map: one image of six square layers, the
// faces +X, −X, +Y, −Y, +Z, −Z in that order (the order a cube view gives them; light_frustum.h
// looks along the same six directions, face by face). The image is made once; what differs is how
// each use sees it:
//   - a render pass draws one face at a time, through a 2D view of that face alone;
//   - a sampler through a cube view takes a direction and picks the face itself;
//   - our lookup reads the six faces through one 2D-array view (layer = face) and picks the face
//     itself, so that its filter taps may cross into a neighbouring face (shadows.glsl).
#pragma once

#include "image.h"

// A cube-compatible image, `size`² texels per face, one mip level; its view is a cube view.
lab::Image create_image_cube(const lab::VulkanContext& vk, uint32_t size, VkFormat format, VkImageUsageFlags usage,
                             VkImageAspectFlags aspect);
// A 2D view of the face in `layer`: what a framebuffer renders that face into.
lab::Handle<VkImageView> create_layer_view(const lab::VulkanContext& vk, VkImage image, VkFormat format,
                                           VkImageAspectFlags aspect, uint32_t layer);
// The six faces as one 2D-array view (layer = face).
lab::Handle<VkImageView> create_faces_view(const lab::VulkanContext& vk, VkImage image, VkFormat format,
                                           VkImageAspectFlags aspect);
