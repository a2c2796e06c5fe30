// headless_target.h — render into an offscreen colour + depth image, read it back as a PNG.
#pragma once

#include "render_target.h"

namespace lab {

class HeadlessTarget : public RenderTarget {
public:
    // 8-bit sRGB: the hardware encodes the shader's linear colour on write.
    static constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;

    HeadlessTarget(const VulkanContext& vk, VkExtent2D extent);
    ~HeadlessTarget() override;

    VkRenderPass render_pass() const override { return render_pass_; }
    VkExtent2D extent() const override { return extent_; }
    bool begin_frame(const glm::vec3& clear_linear, Frame& frame, const BeforePass& before_pass = {}) override;
    void end_frame(const AfterPass& after_pass = {}) override;  // `after_pass` is not called
    void wait_for_previous_frame() const override;

    // Blocks until frame number `frame_number` (counting begin_frame calls from 0) has finished.
    void wait_for_frame(uint64_t frame_number) const;
    // Waits for all frames, copies the colour image to the host (row 0 = top).
    Image8 read_pixels();

private:
    const VulkanContext& vk_;
    VkExtent2D extent_;
    Handle<VkRenderPass> render_pass_;
    Image color_;
    Image depth_;
    Handle<VkFramebuffer> framebuffer_;
    FrameSlots slots_;
    uint32_t slot_ = 0;
    uint64_t frames_begun_ = 0;
};

}  // namespace lab
