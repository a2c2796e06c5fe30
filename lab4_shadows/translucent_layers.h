// translucent_layers.h — lab 4: translucent objects in the camera's pass, composed exactly per pixel.
//
// "Over" blending (c = α·layer + (1 − α)·c) is right only when the layers arrive back to front.
// Sorting objects is not sorting surfaces: of two objects that intersect, or one inside another,
// each is partly in front of the other, and no order of the objects is right everywhere. So the
// layers are sorted per pixel instead, with a per-pixel linked list (order-independent
// transparency, an "A-buffer"):
//  1. before the pass (clear()): every pixel's list is emptied and the node pool's counter zeroed;
//  2. the translucent objects are drawn (lit.frag built with TRANSLUCENT_LAYER, both faces in one
//     draw, depth tested against the opaque objects, neither depth nor colour written): each
//     fragment takes a node from the pool, stores its shaded colour, opacity and depth there and
//     pushes it onto its pixel's list (shaders/lab4_shadows/translucent_layers.glsl);
//  3. a barrier inside the pass (the render pass's self-dependency, render_target.cpp), then one
//     full-screen triangle, scissored to where the translucent objects are (resolve()), sorts each
//     pixel's list by depth and blends the composed layers over the opaque picture
//     (translucent_resolve.frag).
// Two limits, both counted (stats()) and shown (Shadows panel; headless: a warning, summary()):
//  - a pixel composes its kMaxLayers nearest layers; the farther ones' colour is dropped (they lie
//    behind K others), their (1 − α) is kept: what is behind them is dimmed by every layer;
//  - the pool holds kNodesPerPixel nodes per pixel on average; a fragment past its end is not
//    stored. Which fragments those are depends on the order the GPU runs them in, so a pixel that
//    lost one shows none of its layers' colour, only their whole transmittance (every fragment
//    counts it, stored or not): the same every run, never brighter than the exact picture. Which
//    pixels lose one is not deterministic (the pool is shared by the frame; the resolve of one
//    pixel cannot know another's, inside the pass): a frame that overflowed is counted.
// Only scenes with a translucent object make one of these.
#pragma once

#include "buffer.h"
#include "pipeline_builder.h"
#include "vk_context.h"

#include <cstdint>
#include <string>
#include <vector>

class TranslucentLayers {
public:
    static constexpr uint32_t kMaxLayers = 16;     // K: layers composed per pixel (translucent_resolve.frag's K)
    static constexpr uint32_t kNodesPerPixel = 4;  // the pool: 4 nodes per pixel of the frame (16 bytes each)
    static constexpr uint32_t kFirstBinding = 10;  // set 0's bindings 10..13 (translucent_layers.glsl)

    // What a frame could not store or compose (read back after its fence).
    struct Stats {
        uint32_t overflow_pixels = 0;  // pixels with more than kMaxLayers layers (the farther ones dropped)
        uint32_t dropped = 0;          // fragments not stored: the pool was full
    };

    // Buffers for frames of `extent`; the resolve pipeline for `render_pass`, its set 0 laid out by
    // `set_layout` (the renderer's, with bindings() at kFirstBinding).
    TranslucentLayers(const lab::VulkanContext& vk, VkExtent2D extent, VkRenderPass render_pass,
                      VkDescriptorSetLayout set_layout, const std::string& shader_dir);

    // Set 0's bindings kFirstBinding.. (fragment shaders): heads, nodes, counter, stats.
    static std::vector<lab::DescriptorBinding> bindings();
    // Points those bindings of `set` (frame slot `slot`'s) at the buffers.
    void write_descriptors(VkDescriptorSet set, uint32_t slot) const;

    // The frame size the buffers are made for; resize() makes new ones (the GPU must be idle: the
    // old ones may be in use, and every set must be written again).
    VkExtent2D extent() const { return extent_; }
    void resize(VkExtent2D extent);

    // Outside the render pass, before it (its slot's fence has signalled): reads back the slot's
    // last stats, empties every list and the pool for this frame.
    void clear(VkCommandBuffer cmd, uint32_t slot);
    // Inside the pass, after the translucent objects' draws: waits for their writes, then composes
    // the lists over `area` (pixels; set 0 = `set` is bound here).
    void resolve(VkCommandBuffer cmd, VkDescriptorSet set, VkRect2D area) const;
    // Once the GPU is idle (after the last frame): reads back the last frame's stats.
    void collect();

    const Stats& stats() const { return stats_; }
    // "translucent layers: up to K per pixel exact; N px over K, M fragments dropped (pool full)"
    std::string summary() const;

private:
    void read_stats(uint32_t slot);

    const lab::VulkanContext& vk_;
    VkExtent2D extent_{};
    uint32_t pool_nodes_ = 0;
    lab::Buffer heads_;    // three uints per pixel: the first node of its list, its fragments, their optical depth (device-only, as the two below)
    lab::Buffer nodes_;    // the pool: 16-byte nodes
    lab::Buffer counter_;  // one uint: nodes taken so far this frame
    std::vector<lab::Buffer> stats_buffers_;  // [frame slot] host-visible: width, overflow_pixels, dropped, pixels
    std::vector<bool> pending_;               // [frame slot]: written by a frame not read back yet
    uint32_t last_slot_ = 0;                  // the slot of the last frame cleared
    Stats stats_;
    lab::Handle<VkShaderModule> vertex_shader_, fragment_shader_;
    lab::PipelineBuilder::Result resolve_;
};
