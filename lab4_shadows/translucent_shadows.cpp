// translucent_shadows.cpp — transmittance maps: their format, render pass and two blending
// pipelines, and the depth tolerance the lookup uses (translucent_shadows.h).
#include "translucent_shadows.h"

#include "image.h"
#include "shader.h"

namespace {
// How far behind the nearest translucent caster a receiver must be to be behind it, in texels.
constexpr double kTranslucentTexels = 2.0;
}  // namespace

TranslucentShadows::TranslucentShadows(const lab::VulkanContext& vk, VkFormat depth_format, bool active,
                                       const lab::PipelineBuilder& casters, VkShaderModule vertex_shader,
                                       const std::string& shader_dir)
    : depth_format_(depth_format), active_(active), vk_(vk) {
    // Two channels the pass blends into and the lookup samples: 32-bit float where the device
    // blends it, else 16-bit.
    const VkFormatFeatureFlags blend_use = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
    format_ = format_supports(vk, VK_FORMAT_R32G32_SFLOAT, blend_use) ? VK_FORMAT_R32G32_SFLOAT : VK_FORMAT_R16G16_SFLOAT;
    pass_ = make_offscreen_pass(vk, format_, depth_format);
    if (!active) return;
    const lab::Handle<VkShaderModule> fragment_shader = lab::load_shader(vk, shader_dir, "translucent_shadow.frag");
    for (int cube = 0; cube < 2; ++cube) {
        // Front faces as the light sees them; a cube face's view mirrors the winding. (A caster
        // whose transform mirrors is inside out, here as in the camera's pass and the
        // reference: docs/scene-format.md, "Negative scale".)
        const VkCullModeFlags back = cube ? VK_CULL_MODE_FRONT_BIT : VK_CULL_MODE_BACK_BIT;
        VkPipelineColorBlendAttachmentState g{};  // the nearest face's depth into g
        g.colorWriteMask = VK_COLOR_COMPONENT_G_BIT;
        // r = r · (1 − α): src · 0 + dst · src (alpha: kept), into r only.
        const VkPipelineColorBlendAttachmentState r{VK_TRUE, VK_BLEND_FACTOR_ZERO, VK_BLEND_FACTOR_SRC_COLOR, VK_BLEND_OP_ADD,
                                                    VK_BLEND_FACTOR_ZERO, VK_BLEND_FACTOR_ONE, VK_BLEND_OP_ADD,
                                                    VK_COLOR_COMPONENT_R_BIT};
        lab::PipelineBuilder builder = casters;
        builder.shaders(vertex_shader, fragment_shader).cull(back).depth_clamp(vk.enabled_features().depthClamp);
        nearest_[cube] = builder.color_blend(g).depth(true, true).build(vk, pass_);
        multiply_[cube] = builder.color_blend(r).depth(false, false).build(vk, pass_);
    }
}

TranslucentShadows::Map TranslucentShadows::make_map(uint32_t resolution, bool cube) const {
    Map m;
    // One scratch depth serves every face (the faces are rendered one after the other).
    m.scratch_depth = create_image_2d(vk_, {resolution, resolution}, depth_format_,
                                      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    const VkImageUsageFlags sampled_color = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    m.transmittance = create_layered_target(vk_, pass_, resolution, cube, format_, sampled_color, VK_IMAGE_ASPECT_COLOR_BIT,
                                            {m.scratch_depth.view});
    return m;
}

void TranslucentShadows::render(VkCommandBuffer cmd, const Map& map, uint32_t face, bool cube,
                                const std::function<void()>& draw_translucent) const {
    map.transmittance.begin(cmd, face);
    for (const auto* pipeline : {&nearest_[cube], &multiply_[cube]}) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline->pipeline);
        draw_translucent();
    }
    vkCmdEndRenderPass(cmd);
}

// A receiver less than kTranslucentTexels texels (world units, t) behind the nearest translucent
// caster is that caster itself (translucent_shadows.glsl). In depth: orthographic t / (far − near);
// perspective, with a texel τ·z wide at distance z, (a − b/(z + t)) − (a − b/z) = b·t / (z(z + t))
// = K / z with K = b·k·τ / (1 + k·τ), k = kTranslucentTexels, b = far·near / (far − near): one
// division per pixel.
float TranslucentShadows::tolerance(double texel, uint32_t resolution, bool perspective, double near_plane,
                                    double far_plane) {
    const double tau = texel / resolution;
    if (!perspective) return float(kTranslucentTexels * tau / (far_plane - near_plane));
    const double b = far_plane * near_plane / (far_plane - near_plane);
    return float(b * kTranslucentTexels * tau / (1.0 + kTranslucentTexels * tau));
}
