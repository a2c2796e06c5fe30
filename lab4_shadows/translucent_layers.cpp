#include "translucent_layers.h"

#include "render_target.h"
#include "shader.h"

#include <algorithm>
#include <stdexcept>

namespace {
constexpr VkDeviceSize kNodeBytes = 16;  // LayerNode: colour (two packHalf2x16), depth, next
constexpr uint32_t kEmpty = 0xFFFFFFFFu;  // LAYER_END: a pixel's empty list
struct GpuStats {  // LayerStats (std430)
    uint32_t width;
    uint32_t overflow_pixels;
    uint32_t dropped;
    uint32_t pixels;
};
// heads_ holds three arrays of one uint per pixel: list heads, fragment counts, optical depths.
constexpr VkDeviceSize kWordsPerPixel = 3;
}  // namespace

TranslucentLayers::TranslucentLayers(const lab::VulkanContext& vk, VkExtent2D extent, VkRenderPass render_pass,
                                     VkDescriptorSetLayout set_layout, const std::string& shader_dir)
    : vk_(vk) {
    counter_ = lab::Buffer::device_only(vk, sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    // The stats are the host's to read, one buffer per frame in flight (as the renderer's uniforms):
    // a frame's counts are read when its slot comes round again, after its fence, never waiting.
    for (uint32_t slot = 0; slot < lab::RenderTarget::kFramesInFlight; ++slot) {
        stats_buffers_.push_back(lab::Buffer::host_visible(vk, sizeof(GpuStats), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT));
        *static_cast<GpuStats*>(stats_buffers_.back().mapped()) = {};
    }
    pending_.assign(lab::RenderTarget::kFramesInFlight, false);
    resize(extent);

    // The resolve: a full-screen triangle (no vertex buffer), no depth test, and the blend that
    // puts the layers over what is there: colour = src · 1 + dst · src.a, i.e. C + T · opaque;
    // the attachment's alpha is kept (src · 0 + dst · 1).
    vertex_shader_ = lab::load_shader(vk, shader_dir, "translucent_resolve.vert");
    fragment_shader_ = lab::load_shader(vk, shader_dir, "translucent_resolve.frag");
    VkPipelineColorBlendAttachmentState over{};
    over.blendEnable = VK_TRUE;
    over.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
    over.dstColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
    over.colorBlendOp = VK_BLEND_OP_ADD;
    over.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
    over.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    over.alphaBlendOp = VK_BLEND_OP_ADD;
    over.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    // K, the resolve's local arrays' size, is a specialization constant: the shader and this class agree.
    const VkSpecializationMapEntry k_entry{0, 0, sizeof(uint32_t)};
    const VkSpecializationInfo k{1, &k_entry, sizeof(kMaxLayers), &kMaxLayers};
    resolve_ = lab::PipelineBuilder()
                   .shaders(vertex_shader_, fragment_shader_)
                   .specialization(&k)
                   .vertex_attributes(0)
                   .descriptor_set(set_layout)
                   .cull(VK_CULL_MODE_NONE)
                   .depth(false, false)
                   .color_blend(over)
                   .build(vk, render_pass);
}

void TranslucentLayers::resize(VkExtent2D extent) {
    const VkDeviceSize pixels = VkDeviceSize(extent.width) * extent.height;
    const VkDeviceSize range = vk_.properties().limits.maxStorageBufferRange;  // the most one binding may see
    if (kWordsPerPixel * pixels * sizeof(uint32_t) > range)
        throw std::runtime_error("translucent objects in a " + std::to_string(extent.width) + "x" +
                                 std::to_string(extent.height) + " frame: three words per pixel need more than the " +
                                 std::to_string(range) + " bytes a storage buffer may hold on this device");
    extent_ = extent;
    // The pool: kNodesPerPixel nodes per pixel on average. A glass ball shows two layers where it is
    // (its front and back), two nested or intersecting ones four, and they rarely cover the whole
    // frame: 4 per pixel leaves room for much more, at 64 bytes per pixel (59 MB at 1280×720).
    // No larger than one binding may be.
    pool_nodes_ = uint32_t(std::min<VkDeviceSize>(kNodesPerPixel * pixels, range / kNodeBytes));
    heads_ = lab::Buffer();  // the old ones first (the GPU is done with them): their memory is reused
    nodes_ = lab::Buffer();
    heads_ = lab::Buffer::device_only(vk_, kWordsPerPixel * pixels * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    nodes_ = lab::Buffer::device_only(vk_, pool_nodes_ * kNodeBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
}

std::vector<lab::DescriptorBinding> TranslucentLayers::bindings() {
    return std::vector<lab::DescriptorBinding>(4, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT});
}

void TranslucentLayers::write_descriptors(VkDescriptorSet set, uint32_t slot) const {
    const VkDeviceSize pixels = VkDeviceSize(extent_.width) * extent_.height;
    lab::write_buffer_descriptor(vk_, set, kFirstBinding + 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, heads_.get(),
                                 kWordsPerPixel * pixels * sizeof(uint32_t));
    lab::write_buffer_descriptor(vk_, set, kFirstBinding + 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nodes_.get(),
                                 pool_nodes_ * kNodeBytes);
    lab::write_buffer_descriptor(vk_, set, kFirstBinding + 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, counter_.get(),
                                 sizeof(uint32_t));
    lab::write_buffer_descriptor(vk_, set, kFirstBinding + 3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                 stats_buffers_[slot].get(), sizeof(GpuStats));
}

void TranslucentLayers::read_stats(uint32_t slot) {
    if (!pending_[slot]) return;
    const GpuStats& gpu = *static_cast<const GpuStats*>(stats_buffers_[slot].mapped());
    stats_ = {gpu.overflow_pixels, gpu.dropped};
    pending_[slot] = false;
}

void TranslucentLayers::clear(VkCommandBuffer cmd, uint32_t slot) {
    // The slot's previous frame has finished (its fence): its counts can be read, and the buffer
    // zeroed for this frame by the host (a host write before the submit is seen by the GPU).
    read_stats(slot);
    *static_cast<GpuStats*>(stats_buffers_[slot].mapped()) = {extent_.width, 0, 0, extent_.width * extent_.height};
    pending_[slot] = true;
    last_slot_ = slot;

    // The lists are shared by the frames in flight: the previous frame's layer draws and resolve
    // (fragment shaders) must be done with them before this frame empties and refills them.
    VkMemoryBarrier before{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    before.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    before.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 1, &before, 0,
                         nullptr, 0, nullptr);
    // Every list empty, every pixel's count and optical depth 0, no node taken. (The nodes
    // themselves need no clearing: only the nodes a list reaches are read, and each was written
    // this frame.)
    const VkDeviceSize heads_bytes = VkDeviceSize(extent_.width) * extent_.height * sizeof(uint32_t);
    vkCmdFillBuffer(cmd, heads_.get(), 0, heads_bytes, kEmpty);
    vkCmdFillBuffer(cmd, heads_.get(), heads_bytes, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(cmd, counter_.get(), 0, VK_WHOLE_SIZE, 0);
    // The fills must land before the translucent draws' atomics read and write them.
    VkMemoryBarrier after{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    after.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    after.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 1, &after, 0,
                         nullptr, 0, nullptr);
}

void TranslucentLayers::resolve(VkCommandBuffer cmd, VkDescriptorSet set, VkRect2D area) const {
    // Inside a render pass a barrier must match one of the pass's own self-dependencies
    // (render_target.cpp): the layers' shader writes, then the resolve's reads of them. By region:
    // each pixel's resolve reads only what that pixel's fragments wrote.
    VkMemoryBarrier written{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    written.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    written.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                         VK_DEPENDENCY_BY_REGION_BIT, 1, &written, 0, nullptr, 0, nullptr);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, resolve_.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, resolve_.layout, 0, 1, &set, 0, nullptr);
    // Only where translucent objects may be: elsewhere every list is empty, and the whole frame's
    // worth of fragments would cost more than the layers themselves.
    vkCmdSetScissor(cmd, 0, 1, &area);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    const VkRect2D whole{{0, 0}, extent_};
    vkCmdSetScissor(cmd, 0, 1, &whole);  // what the pass began with, for what is drawn after
}

void TranslucentLayers::collect() { read_stats(last_slot_); }

std::string TranslucentLayers::summary() const {
    return "translucent layers: up to " + std::to_string(kMaxLayers) + " per pixel exact; " +
           std::to_string(stats_.overflow_pixels) + " px over " + std::to_string(kMaxLayers) + ", " +
           std::to_string(stats_.dropped) + " fragments dropped (pool full)";
}
