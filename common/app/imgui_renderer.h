// imgui_renderer.h — draws ImGui's panels with Vulkan, rasterizing them only when they change.
//
// With a CPU driver (lavapipe) the panels' pixels are a large part of a window frame: hundreds of
// small blended, textured triangles. Yet most frames show the same panels as the frame before
// (the camera moves, the UI does not). So the panels are drawn into an overlay image only when
// ImGui's draw data differ from the last drawn (compared byte for byte, not hashed), and every
// frame puts that overlay over the picture: where a panel is opaque its pixels are copied
// (vkCmdCopyImage after the frame's render pass, a memcpy per row on a CPU driver); the rest —
// borders, collapsed title bars — is blended inside the pass, one rectangle (two triangles) each.
// ui_regions.h says which pixels are which.
//
// The overlay holds premultiplied linear colour and coverage. Drawing ImGui's triangles into a
// cleared overlay with "over" blending (colour: src·α + dst·(1−α); alpha: α + dst·(1−α)) and then
// blending it with out = overlay.rgb + picture·(1 − overlay.a) gives the same result as drawing
// the triangles straight onto the picture (the "over" operator is associative).
#pragma once

#include "buffer.h"
#include "render_target.h"
#include "ui_regions.h"
#include "vk_context.h"

#include <array>
#include <cstdint>
#include <vector>

struct ImDrawData;

namespace lab {

class ImGuiRenderer {
public:
    // `target_pass`: the frame's render pass (the overlay is blended inside it); `target_format`:
    // its colour format (the overlay's, so that copies are exact); `copy_to_target`: whether
    // copy_opaque() may be used (the target's images accept transfers), else everything is blended.
    ImGuiRenderer(const VulkanContext& vk, VkRenderPass target_pass, VkFormat target_format, bool copy_to_target);
    ~ImGuiRenderer();
    ImGuiRenderer(const ImGuiRenderer&) = delete;
    ImGuiRenderer& operator=(const ImGuiRenderer&) = delete;

    // Outside any render pass, before the frame's own: redraws the overlay if `draw_data` (or the
    // framebuffer size) changed since the last call. `slot` is the frame-in-flight slot (the
    // vertex and index buffers of a slot are free once its fence was waited for).
    void prepare(VkCommandBuffer cmd, uint32_t slot, VkExtent2D extent, const ImDrawData& draw_data);
    // Inside the frame's render pass: blends the overlay's translucent parts over the picture.
    void composite(VkCommandBuffer cmd) const;
    // After the frame's render pass: copies the overlay's opaque panels into `target_image`
    // (in TRANSFER_DST_OPTIMAL layout).
    void copy_opaque(VkCommandBuffer cmd, VkImage target_image) const;

    // How many times the overlay was drawn (the rest of the frames reused it).
    uint64_t redraw_count() const { return redraws_; }

private:
    void make_overlay(VkExtent2D extent);
    bool same_as_last(const ImDrawData& draw_data, VkExtent2D extent);
    void upload(uint32_t slot, const ImDrawData& draw_data);
    void draw_overlay(VkCommandBuffer cmd, uint32_t slot, const ImDrawData& draw_data);

    const VulkanContext& vk_;
    const VkFormat overlay_format_;
    const bool copy_to_target_;
    // ImGui's colours are sRGB-encoded; the targets are *_SRGB and encode again on write. Each
    // vertex colour channel goes through this table (sRGB byte -> linear byte) before drawing.
    std::array<uint8_t, 256> srgb_to_linear_{};

    Image font_;  // ImGui's font atlas, R8G8B8A8_SRGB (white texels, coverage in alpha)
    Handle<VkSampler> nearest_;
    Handle<VkDescriptorSetLayout> set_layout_;
    Handle<VkDescriptorPool> pool_;
    VkDescriptorSet font_set_ = VK_NULL_HANDLE;
    VkDescriptorSet overlay_set_ = VK_NULL_HANDLE;
    Handle<VkPipelineLayout> ui_layout_;        // ImGui's triangles into the overlay
    Handle<VkPipeline> ui_pipeline_;
    Handle<VkPipelineLayout> composite_layout_; // the overlay onto the frame
    Handle<VkPipeline> composite_pipeline_;

    Handle<VkRenderPass> overlay_pass_;
    Image overlay_;  // the target's format (8-bit sRGB) and size
    Handle<VkFramebuffer> overlay_framebuffer_;
    VkExtent2D overlay_extent_{};

    // Per frame in flight: ImGui's vertices and indices (host-visible, mapped, grown on demand).
    std::array<Buffer, RenderTarget::kFramesInFlight> vertices_;
    std::array<Buffer, RenderTarget::kFramesInFlight> indices_;

    std::vector<uint8_t> last_, current_;  // the draw data drawn last / this frame, as bytes
    bool overlay_valid_ = false;
    UiRegions regions_;
    std::vector<VkImageCopy> copies_;  // regions_.copy for vkCmdCopyImage  // which pixels the overlay copies and blends (bounds: the overlay pass's render area)
    uint64_t redraws_ = 0;
};

}  // namespace lab
