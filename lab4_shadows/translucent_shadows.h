// translucent_shadows.h — lab 4's second lesson: the shadows of translucent casters.
//
// An opaque caster stops a light; a translucent one (opacity α < 1) lets 1 − α of it through,
// and two of them in a row let (1 − α₁)(1 − α₂) through. Beside each depth map a light gets a
// transmittance map of the same size: for each texel's ray from the light, r = the product of
// 1 − α over the translucent casters' front faces, g = the depth of the nearest one. The lookup
// (shaders/lab4_shadows/translucent_shadows.glsl) multiplies a tap's light by r when the point
// lies behind that nearest face. Only scenes with translucent casters render these maps, and
// only where those casters are: the rest of the map keeps "nothing translucent" (r = g = 1), so a
// glass ball a tenth of the map across costs about a hundredth of a full-map pass.
#pragma once

#include "offscreen.h"
#include "pipeline_builder.h"
#include "vk_context.h"

#include <array>
#include <functional>
#include <string>
#include <vector>

class TranslucentShadows {
public:
    // `depth_format`: the shadow maps' depth format (the pass needs a depth test of its own);
    // `casters`: the shadow pipelines' shared state (vertex input, push constants) and
    // `vertex_shader` (shadow.vert). With `active` false (no translucent caster) only the render
    // pass exists, for the 1×1 stand-in maps.
    TranslucentShadows(const lab::VulkanContext& vk, VkFormat depth_format, bool active, const lab::PipelineBuilder& casters,
                       VkShaderModule vertex_shader, const std::string& shader_dir);

    struct Map {
        lab::Image scratch_depth;    // the depth test between translucent faces, not kept
        LayeredTarget transmittance;  // r = Π(1 − α), g = the nearest translucent depth; a layer per face
        std::vector<VkRect2D> drawn;  // [face]: where the last render drew (elsewhere r = g = 1)
    };
    // A transmittance map of `resolution`² (a cube: six faces) beside a depth map, cleared.
    Map make_map(uint32_t resolution, bool cube) const;

    // Face `face` of `map`: begins its pass over `area` (the texels its translucent casters cover:
    // covered_texels() in offscreen.h) and what the last render drew — r cleared to 1, g to depth
    // 1 there, the rest kept — and, for each of the two pipelines — nearest depth into g, then
    // r ×= 1 − α — binds it and calls `draw_translucent()`. Nothing at all when both are empty.
    void render(VkCommandBuffer cmd, Map& map, uint32_t face, bool cube, VkRect2D area,
                const std::function<void()>& draw_translucent) const;

    // How far (in depth) a receiver must lie behind the nearest translucent caster to be behind
    // it, for a map of `resolution`² over `texel` world units (perspective: per unit distance).
    static float tolerance(double texel, uint32_t resolution, bool perspective, double near_plane, double far_plane);

    bool active() const { return active_; }

private:
    VkFormat format_ = VK_FORMAT_R32G32_SFLOAT;
    VkFormat depth_format_;
    bool active_;
    const lab::VulkanContext& vk_;
    lab::Handle<VkRenderPass> pass_;                        // transmittance + scratch depth
    std::array<lab::PipelineBuilder::Result, 2> nearest_;   // [cube]: g = nearest translucent depth
    std::array<lab::PipelineBuilder::Result, 2> multiply_;  // [cube]: r ×= 1 − α
};
