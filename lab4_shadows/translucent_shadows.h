// translucent_shadows.h — lab 4's second lesson: the shadows of translucent casters.
//
// An opaque caster stops a light; a translucent one (opacity α < 1) lets 1 − α of it through,
// and two of them in a row let (1 − α₁)(1 − α₂) through. But only those between the receiver and
// the light count: a glass slab under a glass ball gets the ball's 1 − α, the floor under both
// gets the product, and neither slab dims itself. So beside each depth map a light gets a
// transmittance map of K layers, the translucent casters' front faces (as the light sees them)
// along each texel's ray peeled off one at a time, nearest first (depth peeling): layer k holds
// g = the depth of the (k+1)-th face and r = its 1 − α. The lookup
// (shaders/lab4_shadows/translucent_shadows.glsl) multiplies a tap's light by the r of every layer
// that lies in front of the point. K is the most faces a ray can cross: one per convex caster, two
// per other (a torus), at most kMaxLayers; past K the last layer holds the product of every face
// beyond the one before it, at the nearest one's depth (a receiver among those faces gets too
// little light: the faces behind it count too). Two front faces at exactly the same depth in one
// texel both count (r = the product), and g then holds depth² (< depth): the later layers take
// them again, so what lies behind gets too little light, never too much. Only scenes with translucent casters render these maps, and only where those
// casters are: the rest of the map keeps "nothing translucent" (r = g = 1), so a glass ball a tenth
// of the map across costs about a hundredth of a full-map pass, per layer.
#pragma once

#include "light_frustum.h"
#include "offscreen.h"
#include "pipeline_builder.h"
#include "vk_context.h"

#include <algorithm>
#include <array>
#include <functional>
#include <string>
#include <vector>

class TranslucentShadows {
public:
    static constexpr uint32_t kMaxLayers = 4;  // layers per texel at most (memory: 8 bytes per texel each)

    // `depth_format`: the shadow maps' depth format (the pass needs a depth test of its own);
    // `layers`: K (0: no translucent caster: only the render pass exists, for the 1×1 stand-in
    // maps); `casters`: the shadow pipelines' shared state (vertex input, push constants) and
    // `vertex_shader` (shadow.vert).
    TranslucentShadows(const lab::VulkanContext& vk, VkFormat depth_format, uint32_t layers, const lab::PipelineBuilder& casters,
                       VkShaderModule vertex_shader, const std::string& shader_dir);

    struct Map {
        lab::Image scratch_depth;     // the depth test between translucent faces, not kept
        LayeredTarget transmittance;  // a face's layer k: r = 1 − α of the (k+1)-th face, g = its depth
        std::vector<std::vector<uint32_t>> layer_of;  // [face][k]: the array layer make_map() gave it
        lab::Handle<VkDescriptorPool> pool;
        std::vector<VkDescriptorSet> previous;  // [array layer]: the peel reads that face's layer k − 1 (k = 0: 1×1 "nothing")
        std::vector<VkRect2D> drawn;  // [face]: where the last render drew (elsewhere r = g = 1)
    };
    // A transmittance map of `resolution`² (a cube: six faces), K layers per face, cleared.
    Map make_map(uint32_t resolution, bool cube) const;

    // Face `face` of `map`: for each layer k, begins its pass over `area` (the texels its
    // translucent casters cover in the used² square the depth map drew: covered_texels() in
    // offscreen.h) and what the last render drew —
    // r cleared to 1, g to depth 1 there, the rest kept — binds the set that reads layer k − 1 and,
    // for each of its pipelines, calls `draw_translucent(k)` (k goes into the push constants). Layers
    // before the last: the nearest face beyond layer k − 1 (its depth first, then its depth and
    // 1 − α); the last: r ×= 1 − α of every face beyond layer k − 1, then the nearest one's depth
    // into g. Nothing at all when `area` and what was drawn are both empty.
    void render(VkCommandBuffer cmd, Map& map, uint32_t face, bool cube, VkRect2D area, uint32_t used,
                const std::function<void(uint32_t layer)>& draw_translucent) const;

    // The push constants' z (translucent_shadow.frag): how much farther (relative) than layer k − 1
    // a face must be to be another face. 32-bit float layers: 0 — every peel pipeline differs from
    // the one that stored layer k − 1 only in write masks, and the invariance rules require the same
    // fragments, depth included, for those (Vulkan spec, appendix "Invariance", Rule 2 "Required"
    // and Corollary 1; translucent_shadows.cpp); g = 1 · depth is exact. 16-bit: a half's rounding
    // (at most 2⁻¹¹ relative), twice over.
    float peel_slack() const { return format_ == VK_FORMAT_R32G32_SFLOAT ? 0.0f : 1.0f / 1024.0f; }

    // How far (in depth) a receiver must lie behind the nearest translucent caster to be behind
    // it, for `f`'s map drawn at `resolution`² texels (perspective maps: the lookup divides it by
    // P's distance along the map's axis).
    static float tolerance(const LightFrustum& f, uint32_t resolution);

    bool active() const { return layers_ > 0; }
    uint32_t layers() const { return std::max(layers_, 1u); }  // per face (the stand-ins: 1)

private:
    VkFormat format_ = VK_FORMAT_R32G32_SFLOAT;
    VkFormat depth_format_;
    uint32_t layers_;
    const lab::VulkanContext& vk_;
    lab::Handle<VkRenderPass> pass_;                        // transmittance + scratch depth
    lab::Handle<VkDescriptorSetLayout> previous_layout_;    // the layer before, read by the peel
    lab::Handle<VkSampler> texel_sampler_;                  // nearest: the peel reads its own texel
    lab::Image nothing_;                                    // 1×1, r = g = 1: what layer 0 "reads"
    // [cube], all the same state but the write masks (see peel_slack()):
    std::array<lab::PipelineBuilder::Result, 2> depth_;     // the nearest face's depth (scratch depth only)
    std::array<lab::PipelineBuilder::Result, 2> layer_;     // at that depth: g = the nearest face's depth, r = its 1 − α
    std::array<lab::PipelineBuilder::Result, 2> nearest_;   // the last layer: g = the nearest face's depth
    std::array<lab::PipelineBuilder::Result, 2> multiply_;  // the last layer, before depth_: r ×= 1 − α of every face
};
