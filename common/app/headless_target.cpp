#include "headless_target.h"

#include <cstring>

namespace lab {

HeadlessTarget::HeadlessTarget(const VulkanContext& vk, VkExtent2D extent)
    : vk_(vk),
      extent_(extent),
      // The pass leaves the image ready to be copied out.
      render_pass_(make_render_pass(vk, kColorFormat, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL)),
      color_(create_target_image(vk, extent, kColorFormat,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                 VK_IMAGE_ASPECT_COLOR_BIT)),
      depth_(create_target_image(vk, extent, vk.depth_format(), VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                 VK_IMAGE_ASPECT_DEPTH_BIT)),
      framebuffer_(make_framebuffer(vk, render_pass_, {color_.view, depth_.view}, extent)),
      slots_(vk) {}

HeadlessTarget::~HeadlessTarget() { vkDeviceWaitIdle(vk_.device()); }

bool HeadlessTarget::begin_frame(const glm::vec3& clear_linear, Frame& frame, const BeforePass& before_pass) {
    slots_.wait(slot_);
    slots_.reset_fence(slot_);
    slots_.reset_commands(slot_);
    ++frames_begun_;
    frame.cmd = slots_.command_buffer(slot_);
    frame.slot = slot_;
    frame.extent = extent_;
    begin_render_pass(frame, render_pass_, framebuffer_, clear_linear, before_pass);
    return true;
}

void HeadlessTarget::end_frame(const AfterPass&) {
    VkCommandBuffer cmd = slots_.command_buffer(slot_);
    vkCmdEndRenderPass(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    VK_CHECK(vkQueueSubmit(vk_.queue(), 1, &submit, slots_.fence(slot_)));
    slot_ = (slot_ + 1) % kFramesInFlight;
}

// After end_frame() the next slot is the previous frame's (two in flight).
void HeadlessTarget::wait_for_previous_frame() const { slots_.wait(slot_); }

void HeadlessTarget::wait_for_frame(uint64_t frame_number) const {
    // Frame n used slot n % kFramesInFlight; its fence is reused only by frame n + kFramesInFlight.
    if (frame_number + kFramesInFlight < frames_begun_) return;  // long done: its slot was reused since
    slots_.wait(uint32_t(frame_number % kFramesInFlight));
}

Image8 HeadlessTarget::read_pixels() {
    VK_CHECK(vkQueueWaitIdle(vk_.queue()));
    const VkDeviceSize size = VkDeviceSize(extent_.width) * extent_.height * 4;
    Buffer readback = Buffer::host_visible(vk_, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    vk_.run_once([&](VkCommandBuffer cmd) {
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {extent_.width, extent_.height, 1};
        vkCmdCopyImageToBuffer(cmd, color_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.get(), 1, &region);
        // The fence wait below says the copy has *finished*, not that its writes are visible to
        // the host: the specification asks for this transfer-write -> host-read barrier too.
        VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0,
                             nullptr, 0, nullptr);
    });
    Image8 image;
    image.width = int(extent_.width);
    image.height = int(extent_.height);
    image.rgba.resize(size);
    std::memcpy(image.rgba.data(), readback.mapped(), size);
    for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;  // opaque PNG
    return image;
}

}  // namespace lab
