// render_target.h — where frames go: a window (swapchain) or an offscreen image.
//
// A lab records the same commands in both modes: begin_frame() hands it a
// command buffer inside a render pass that has already cleared colour and
// depth and set the viewport; end_frame() submits (and presents).
#pragma once

#include "buffer.h"
#include "image_io.h"
#include "pass_timer.h"
#include "vk_context.h"

#include <glm/glm.hpp>

#include <array>
#include <functional>
#include <initializer_list>

namespace lab {

struct Frame {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    uint32_t slot = 0;  // frame-in-flight slot: index per-frame resources (uniform buffers) with it
    VkExtent2D extent{};
    PassTimer* timer = nullptr;  // names passes for the panel's GPU times (pass_timer.h); null: none
};

// Commands a lab records before the target's render pass begins (lab 4: the shadow passes render
// into their own images first). Called with the frame's command buffer begun; may be empty.
using BeforePass = std::function<void(const Frame&)>;
// Commands recorded after the render pass, with the frame's image in TRANSFER_DST_OPTIMAL layout
// (the UI copies its opaque panels there, imgui_renderer.h). Only targets whose images accept
// copies call it (a window whose surface allows TRANSFER_DST usage).
using AfterPass = std::function<void(VkCommandBuffer cmd, VkImage image)>;

class RenderTarget {
public:
    static constexpr uint32_t kFramesInFlight = 2;

    virtual ~RenderTarget() = default;
    virtual VkRenderPass render_pass() const = 0;
    virtual VkExtent2D extent() const = 0;
    // Starts a frame cleared to `clear_linear` (linear RGB). Returns false when
    // no frame can be drawn right now (minimized window, swapchain recreated).
    // `before_pass` (if set) records its commands before the render pass begins.
    virtual bool begin_frame(const glm::vec3& clear_linear, Frame& frame, const BeforePass& before_pass = {}) = 0;
    // Ends the pass, records `after_pass` (if set and the target takes copies), submits (and presents).
    virtual void end_frame(const AfterPass& after_pass = {}) = 0;
    // Blocks until the frame before the last one begun has finished on the GPU (two frames are in
    // flight): what a benchmark times, frame by frame.
    virtual void wait_for_previous_frame() const = 0;
};

// The pieces both targets share: one render pass layout and per-slot command buffers + fences.
Handle<VkRenderPass> make_render_pass(const VulkanContext& vk, VkFormat color_format, VkImageLayout color_final_layout);

// A render pass of one subpass with its two external dependencies (before and after), owned by
// a Handle: what every pass here (frame, UI overlay, shadow maps) is made of. The frame's pass
// has two more (make_render_pass): the overload below takes any number.
Handle<VkRenderPass> create_render_pass(const VulkanContext& vk, uint32_t attachment_count,
                                        const VkAttachmentDescription* attachments, const VkSubpassDescription& subpass,
                                        uint32_t dependency_count, const VkSubpassDependency* dependencies);
inline Handle<VkRenderPass> create_render_pass(const VulkanContext& vk, uint32_t attachment_count,
                                               const VkAttachmentDescription* attachments,
                                               const VkSubpassDescription& subpass,
                                               const VkSubpassDependency (&dependencies)[2]) {
    return create_render_pass(vk, attachment_count, attachments, subpass, 2, dependencies);
}

// A framebuffer for `pass` over `views` (in the pass's attachment order): a target's colour and
// depth, the UI overlay's colour.
Handle<VkFramebuffer> make_framebuffer(const VulkanContext& vk, VkRenderPass pass,
                                       std::initializer_list<VkImageView> views, VkExtent2D extent);

// The images the targets and the UI make for themselves (depth buffers, the headless colour image,
// the UI's overlay and font atlas): one level, one layer, device-local, with a 2D view of
// `aspect`. (Lab 3 teaches image creation with mip levels; lab 4 cube maps.)
Image create_target_image(const VulkanContext& vk, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                          VkImageAspectFlags aspect);
// A 2D view of the one level and layer of `image` (also a swapchain's images).
Handle<VkImageView> create_target_view(const VulkanContext& vk, VkImage image, VkFormat format,
                                       VkImageAspectFlags aspect);
// A layout change of a one-level colour image, with its memory dependency (UI uploads and copies,
// a window's image before presenting).
void target_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags src_access,
                    VkAccessFlags dst_access, VkPipelineStageFlags src_stage, VkPipelineStageFlags dst_stage);

class FrameSlots {
public:
    explicit FrameSlots(const VulkanContext& vk);
    // Waits until the slot's previous submission has finished.
    void wait(uint32_t slot) const;
    void reset_fence(uint32_t slot) const;
    // Resets the slot's command buffer by resetting its own pool (cheaper than resetting single
    // command buffers, which needs a pool created with RESET_COMMAND_BUFFER_BIT). After wait(slot).
    void reset_commands(uint32_t slot) const;
    VkCommandBuffer command_buffer(uint32_t slot) const { return commands_[slot]; }
    VkFence fence(uint32_t slot) const { return fences_[slot]; }

private:
    const VulkanContext& vk_;
    std::array<Handle<VkCommandPool>, RenderTarget::kFramesInFlight> pools_;  // one per slot
    std::array<VkCommandBuffer, RenderTarget::kFramesInFlight> commands_{};
    std::array<Handle<VkFence>, RenderTarget::kFramesInFlight> fences_;
};

// Begins `frame.cmd` (already reset), records `before_pass`, then begins the render pass, clears,
// sets viewport and scissor to `frame.extent`.
void begin_render_pass(const Frame& frame, VkRenderPass pass, VkFramebuffer framebuffer, const glm::vec3& clear_linear,
                       const BeforePass& before_pass);

}  // namespace lab
