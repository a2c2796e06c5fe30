// translucent_shadows.cpp — transmittance maps: their format, render pass, layers and the peel's
// pipelines, and the depth tolerance the lookup uses (translucent_shadows.h).
#include "translucent_shadows.h"

#include "cube_map.h"
#include "image.h"
#include "shader.h"

#include <algorithm>

namespace {
// How far behind the nearest translucent caster a receiver must be to be behind it, in texels.
constexpr double kTranslucentTexels = 2.0;

// The smallest rectangle holding both (an empty one: extent 0).
VkRect2D merged(VkRect2D a, VkRect2D b) {
    if (a.extent.width == 0 || a.extent.height == 0) return b;
    if (b.extent.width == 0 || b.extent.height == 0) return a;
    const int32_t x0 = std::min(a.offset.x, b.offset.x), y0 = std::min(a.offset.y, b.offset.y);
    const int32_t x1 = std::max(a.offset.x + int32_t(a.extent.width), b.offset.x + int32_t(b.extent.width));
    const int32_t y1 = std::max(a.offset.y + int32_t(a.extent.height), b.offset.y + int32_t(b.extent.height));
    return {{x0, y0}, {uint32_t(x1 - x0), uint32_t(y1 - y0)}};
}
}  // namespace

TranslucentShadows::TranslucentShadows(const lab::VulkanContext& vk, VkFormat depth_format, uint32_t layers,
                                       const lab::PipelineBuilder& casters, VkShaderModule vertex_shader,
                                       const std::string& shader_dir)
    : depth_format_(depth_format), layers_(std::min(layers, kMaxLayers)), vk_(vk) {
    // Two channels the pass blends into and the lookup samples: 32-bit float where the device
    // blends it, else 16-bit.
    const VkFormatFeatureFlags blend_use = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
    format_ = format_supports(vk, VK_FORMAT_R32G32_SFLOAT, blend_use) ? VK_FORMAT_R32G32_SFLOAT : VK_FORMAT_R16G16_SFLOAT;
    pass_ = make_offscreen_pass(vk, format_, depth_format);
    if (!active()) return;
    // The peel: the pass of layer k reads layer k − 1 at its own texel (set 0, binding 0), a
    // different layer of the same image, written by the pass before (its dependency makes the
    // writes visible to this fragment shader). Layer 0 reads a 1×1 image that holds nothing.
    previous_layout_ = lab::make_descriptor_set_layout(vk, {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT}});
    texel_sampler_ = make_depth_sampler(vk, false, false);
    nothing_ = create_image_2d(vk, {1, 1}, format_, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                               VK_IMAGE_ASPECT_COLOR_BIT);
    vk.run_once([&](VkCommandBuffer cmd) {
        const VkImage image = nothing_.image.get();
        image_barrier(cmd, image, 0, 1, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                      VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        const VkClearColorValue nothing{{1.0f, 1.0f, 0.0f, 0.0f}};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &nothing, 1, &all);
        image_barrier(cmd, image, 0, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
    });
    const lab::Handle<VkShaderModule> fragment_shader = lab::load_shader(vk, shader_dir, "translucent_shadow.frag");
    for (int cube = 0; cube < 2; ++cube) {
        // Front faces as the light sees them; a cube face's view mirrors the winding. (A caster
        // whose transform mirrors is inside out, here as in the camera's pass and the
        // reference: docs/scene-format.md, "Negative scale".)
        const VkCullModeFlags back = cube ? VK_CULL_MODE_FRONT_BIT : VK_CULL_MODE_BACK_BIT;
        // The peel compares a face's depth in one pass with the depth an earlier pass stored for the
        // same face, so the pipelines must compute the same depth. The invariance rules (Vulkan spec,
        // appendix "Invariance") guarantee that only for state whose change is *required* to have no
        // side effects (Rule 2: attachment contents, scissor, write masks, clear values; Corollary 1:
        // fragment generation is then invariant). Blend and depth-test parameters are only "strongly
        // suggested", and their enables not listed at all. So all four pipelines share every state
        // but the write masks: the same blend (r, g ×= the fragment's: src · 0 + dst · src, alpha
        // kept) and the same depth test (LESS_OR_EQUAL); they differ in which channels they write
        // and whether they write depth. Each layer's pass clears r = g = 1, so "×=" on a cleared
        // texel stores the fragment's value exactly (1 · x = x).
        VkPipelineColorBlendAttachmentState multiply{VK_TRUE, VK_BLEND_FACTOR_ZERO, VK_BLEND_FACTOR_SRC_COLOR, VK_BLEND_OP_ADD,
                                                     VK_BLEND_FACTOR_ZERO, VK_BLEND_FACTOR_ONE, VK_BLEND_OP_ADD, 0};
        const auto writing = [&](VkColorComponentFlags channels) {
            multiply.colorWriteMask = channels;
            return multiply;
        };
        const VkColorComponentFlags r = VK_COLOR_COMPONENT_R_BIT, g = VK_COLOR_COMPONENT_G_BIT;
        lab::PipelineBuilder builder = casters;
        builder.shaders(vertex_shader, fragment_shader).descriptor_set(previous_layout_).cull(back).depth_clamp(vk.enabled_features().depthClamp);
        // The nearest face beyond the layer before: its depth into the scratch depth, nothing else.
        depth_[cube] = builder.color_blend(writing(0)).depth(true, true, VK_COMPARE_OP_LESS_OR_EQUAL).build(vk, pass_);
        // Then the fragments at exactly that depth (≤ what depth_ left): r = 1 − α, g = depth.
        layer_[cube] = builder.color_blend(writing(r | g)).depth(true, false, VK_COMPARE_OP_LESS_OR_EQUAL).build(vk, pass_);
        // The last layer: g alone, as layer_ …
        nearest_[cube] = builder.color_blend(writing(g)).depth(true, false, VK_COMPARE_OP_LESS_OR_EQUAL).build(vk, pass_);
        // … and, drawn before depth_ (the depth still the clear value 1), r ×= 1 − α of every face.
        multiply_[cube] = builder.color_blend(writing(r)).depth(true, false, VK_COMPARE_OP_LESS_OR_EQUAL).build(vk, pass_);
    }
}

TranslucentShadows::Map TranslucentShadows::make_map(uint32_t resolution, bool cube) const {
    Map m;
    // One scratch depth serves every layer (the layers are rendered one after the other).
    m.scratch_depth = create_image_2d(vk_, {resolution, resolution}, depth_format_,
                                      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    // One 2D array holds every face's K layers; the lookup picks the face itself, as it does for
    // the cube's depth map (cube_map.h). The layers are allocated face by face, in the faces' order
    // (a cube: +X, −X, +Y, −Y, +Z, −Z), and a face's K layers one after another, k = 0 first:
    // `layer_of` records which array layer each got. TRANSFER_DST: the first clear (below) is a
    // copy-engine clear.
    const uint32_t faces = cube ? 6 : 1;
    uint32_t count = 0;  // the layers allocated so far, so also the index of the next one
    m.layer_of.assign(faces, {});
    for (std::vector<uint32_t>& face : m.layer_of)
        for (uint32_t k = 0; k < layers(); ++k) face.push_back(count++);
    VkImageCreateInfo info = image_info_2d({resolution, resolution}, format_,
                                           VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                               VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                           1);
    info.arrayLayers = count;
    LayeredTarget& t = m.transmittance;
    t.image = create_image(vk_, info, VK_IMAGE_VIEW_TYPE_2D_ARRAY, VK_IMAGE_ASPECT_COLOR_BIT);
    t.pass = pass_.get();
    t.size = resolution;
    t.color = true;
    for (uint32_t layer = 0; layer < count; ++layer) {
        t.layer_views.push_back(create_layer_view(vk_, t.image.image.get(), format_, VK_IMAGE_ASPECT_COLOR_BIT, layer));
        t.framebuffers.push_back(make_square_framebuffer(vk_, pass_.get(), {t.layer(layer), m.scratch_depth.view.get()}, resolution));
    }
    // The pass keeps what lies outside its render area, so it starts from the layout the lookup
    // reads (offscreen.h): every layer is cleared whole to "nothing translucent" once, here, and
    // left in that layout.
    vk_.run_once([&](VkCommandBuffer cmd) {
        const VkImage image = t.image.image.get();
        image_barrier(cmd, image, 0, 1, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                      VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, count);
        const VkClearColorValue nothing{{1.0f, 1.0f, 0.0f, 0.0f}};  // as begin_offscreen_pass clears
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, count};
        vkCmdClearColorImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &nothing, 1, &all);
        // The lookup reads it next; the pass's own dependency orders its later writes.
        image_barrier(cmd, image, 0, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, count);
    });
    m.drawn.assign(faces, VkRect2D{});
    if (!active()) return m;
    // The peel's reads: a face's layer k reads the same face's layer k − 1 (k = 0: nothing).
    const std::vector<lab::DescriptorBinding> binding = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT}};
    m.pool = lab::make_descriptor_pool(vk_, binding, count);
    m.previous.resize(count);
    for (const std::vector<uint32_t>& face : m.layer_of)
        for (size_t k = 0; k < face.size(); ++k) {
            VkDescriptorSet& set = m.previous[face[k]];
            set = lab::allocate_descriptor_set(vk_, m.pool.get(), previous_layout_.get());
            const VkImageView read = k == 0 ? nothing_.view.get() : t.layer(face[k - 1]);
            lab::write_image_descriptor(vk_, set, 0, texel_sampler_.get(), read);
        }
    return m;
}

void TranslucentShadows::render(VkCommandBuffer cmd, Map& map, uint32_t face, bool cube, VkRect2D area, uint32_t used,
                                const std::function<void(uint32_t layer)>& draw_translucent) const {
    // Where to draw, and where the last render drew and must be cleared back to r = g = 1.
    const VkRect2D pass_area = merged(area, map.drawn[face]);
    map.drawn[face] = area;
    if (pass_area.extent.width == 0 || pass_area.extent.height == 0) return;
    const uint32_t K = layers();
    for (uint32_t k = 0; k < K; ++k) {
        const uint32_t layer = map.layer_of[face][k];  // where make_map() put this face's layer k
        map.transmittance.begin(cmd, layer, 1.0f, pass_area, used);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layer_[cube].layout, 0, 1, &map.previous[layer], 0,
                                nullptr);
        // Before the last layer: the nearest face beyond layer k − 1 (its depth, then its r and g).
        // The last: r ×= every face beyond it (while the depth is still cleared), then the nearest's g.
        const bool last = k + 1 == K;
        const std::array<const lab::PipelineBuilder::Result*, 3> draws = {last ? &multiply_[cube] : nullptr, &depth_[cube],
                                                                          last ? &nearest_[cube] : &layer_[cube]};
        for (const auto* pipeline : draws) {
            if (!pipeline) continue;
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline->pipeline);
            draw_translucent(k);
        }
        vkCmdEndRenderPass(cmd);
    }
}

// A receiver less than kTranslucentTexels texels (world units, t) behind the nearest translucent
// caster is that caster itself (translucent_shadows.glsl). The lookup compares depths, so t must
// be turned into depth. Orthographic: depth is linear, t / (far − near) everywhere. Perspective: a
// texel is τ·z wide at distance z along the axis, so t = k·τ·z (k = kTranslucentTexels) grows
// with z, and the tolerance is the stored depth at z + t minus the stored depth at z (exercise
// cube_face_depth says how depth follows distance). The lookup divides the number returned here
// by P's z (shadows.glsl): one division per pixel.
float TranslucentShadows::tolerance(const LightFrustum& f, uint32_t resolution) {
    const double tau = f.texel / resolution;
    if (!f.perspective) return float(kTranslucentTexels * tau / (f.far_plane - f.near_plane));
    return float(f.depth_b() * kTranslucentTexels * tau / (1.0 + kTranslucentTexels * tau));
}
