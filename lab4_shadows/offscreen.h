// offscreen.h — the Vulkan objects of lab 4's first pass: render passes into images the camera's
// pass samples afterwards (the shadow maps). The depth-only render pass and its dependencies (the
// barrier between the passes), the map's image with a framebuffer per layer (a cube map's six face
// views), beginning a pass, the samplers that read depth maps (the comparison sampler), and the
// format check that picks the depth format. shadow_maps.cpp uses them.
#pragma once

#include "bounds.h"
#include "buffer.h"
#include "vk_context.h"
#include "vk_handle.h"

#include <glm/glm.hpp>

#include <vector>

// Does the device support `features` for `format` (optimal tiling)?
bool format_supports(const lab::VulkanContext& vk, VkFormat format, VkFormatFeatureFlags features);

// A one-subpass render pass into `color` (VK_FORMAT_UNDEFINED: none) and `depth`, both cleared
// (over the render area). The colour starts and ends SHADER_READ_ONLY (what lies outside the
// render area is kept: move a new image there first); the depth is kept and ends DEPTH_STENCIL_READ_ONLY when there
// is no colour (a depth map), else it is dropped. Its dependencies order the pass after earlier
// shader reads of the same images (earlier frames) and before the vertex / fragment shaders that
// read them next.
lab::Handle<VkRenderPass> make_offscreen_pass(const lab::VulkanContext& vk, VkFormat color, VkFormat depth);

// A square framebuffer of `size`² over `views` (in the pass's attachment order).
lab::Handle<VkFramebuffer> make_square_framebuffer(const lab::VulkanContext& vk, VkRenderPass pass,
                                              const std::vector<VkImageView>& views, uint32_t size);

// A square image to render into and sample afterwards: 2D, or a cube map (six layers) with a 2D
// view of each face to render into; one framebuffer of `pass` per layer.
struct LayeredTarget {
    lab::Image image;                                      // its view: 2D, or a cube
    std::vector<lab::Handle<VkImageView>> layer_views;     // a cube's faces (2D: none, the image's view)
    lab::Handle<VkImageView> faces;  // a cube's six faces as one 2D array (layer = face): what the lookup
                                     // samples, picking the face itself (shadows.glsl, shadow_cube)
    std::vector<lab::Handle<VkFramebuffer>> framebuffers;  // [layer]
    VkRenderPass pass = VK_NULL_HANDLE;
    uint32_t size = 0;   // size² texels
    bool color = false;  // a colour image (else depth)

    LayeredTarget() = default;
    LayeredTarget(LayeredTarget&&) noexcept = default;
    LayeredTarget& operator=(LayeredTarget&& other) noexcept;  // framebuffers, views, then the image
    uint32_t layers() const { return uint32_t(framebuffers.size()); }
    VkImageView layer(uint32_t i) const { return layer_views.empty() ? image.view.get() : layer_views[i].get(); }
    VkImageView sampled() const { return faces ? faces.get() : image.view.get(); }  // what shaders read
    // begin_offscreen_pass() on layer `i`: cleared, viewport and scissor set; `area` (extent 0:
    // the whole layer) limits the render area and the scissor, `used` (0: all) the viewport.
    void begin(VkCommandBuffer cmd, uint32_t i, float depth = 1.0f, VkRect2D area = {}, uint32_t used = 0) const;
    // Every layer cleared (a pass begun and ended on each), e.g. before anything samples it.
    void clear(VkCommandBuffer cmd) const;
};

// `size`² texels of `format`, 1 layer or 6 (`cube`); each framebuffer's attachments are the layer,
// then `more` (e.g. a depth buffer the layers share: they are rendered one after the other).
LayeredTarget create_layered_target(const lab::VulkanContext& vk, VkRenderPass pass, uint32_t size, bool cube, VkFormat format,
                                    VkImageUsageFlags usage, VkImageAspectFlags aspect,
                                    const std::vector<VkImageView>& more = {});

// Begins `pass` on `framebuffer` (size²) over `area` (extent 0: the whole square): colour (if any)
// cleared to (1, 1, 0, 0), depth to `depth` (1: nothing there) there; the viewport covers the
// used² square at (0, 0) (`used` 0: the whole square; a map sized to the picture draws fewer
// texels than it has), the scissor `area` within it.
void begin_offscreen_pass(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer framebuffer, uint32_t size, bool color,
                          float depth = 1.0f, VkRect2D area = {}, uint32_t used = 0);

// A sampler for depth maps: nearest or linear, optionally comparing the lookup's reference depth
// with the stored one (which compare op, and what a lookup outside the map reads: exercise
// comparison_sampler in offscreen.cpp). depth_sampler_info is its create info, made without a device.
VkSamplerCreateInfo depth_sampler_info(bool linear, bool compare);
lab::Handle<VkSampler> make_depth_sampler(const lab::VulkanContext& vk, bool linear, bool compare);

// The texels of a `size`² target that anything inside `boxes` (world space) can cover through
// `world_to_clip`, with a texel to spare: the whole target when a box reaches behind the
// projection's plane (w ≤ 0 at some corners), none when no box is in front of it or all lie off
// the target. What a pass must draw or clear, or whether a caster can reach a cube face at all.
// `extent`: a target of any shape (lab 4's camera pass asks it where its translucent objects are).
VkRect2D covered_texels(const glm::dmat4& world_to_clip, const std::vector<lab::Box>& boxes, VkExtent2D extent);
inline VkRect2D covered_texels(const glm::dmat4& world_to_clip, const std::vector<lab::Box>& boxes, uint32_t size) {
    return covered_texels(world_to_clip, boxes, VkExtent2D{size, size});
}
