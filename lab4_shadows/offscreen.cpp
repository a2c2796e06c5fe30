// offscreen.cpp — the shadow pass's render passes, images, framebuffers and samplers (offscreen.h).
#include "offscreen.h"

#include "cube_map.h"
#include "render_target.h"
#include "vk_check.h"

#include <algorithm>
#include <cmath>

bool format_supports(const lab::VulkanContext& vk, VkFormat format, VkFormatFeatureFlags features) {
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(vk.physical_device(), format, &p);
    return (p.optimalTilingFeatures & features) == features;
}

// A render pass into a light's map: `color` (VK_FORMAT_UNDEFINED: none) and depth, both
// cleared, then read by the camera's pass. The dependencies order this pass after the shaders
// of earlier frames that read the same images, and before the shaders that read them next.
lab::Handle<VkRenderPass> make_offscreen_pass(const lab::VulkanContext& vk, VkFormat color, VkFormat depth) {
    std::vector<VkAttachmentDescription> attachments;
    VkAttachmentReference color_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkAttachmentReference depth_ref{color ? 1u : 0u, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    if (color)
        // From the layout it is read in, not UNDEFINED: a pass over part of the image keeps the rest.
        attachments.push_back({0, color, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE,
                               VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_DONT_CARE,
                               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
    // Without colour the depth is the map and is kept; with colour it only finds the nearest
    // translucent face and is dropped.
    attachments.push_back({0, depth, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR,
                           color ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE,
                           VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_DONT_CARE, VK_IMAGE_LAYOUT_UNDEFINED,
                           color ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL
                                 : VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL});
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = color ? 1 : 0;
    subpass.pColorAttachments = color ? &color_ref : nullptr;
    subpass.pDepthStencilAttachment = &depth_ref;

    const VkPipelineStageFlags shaders = VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    const VkPipelineStageFlags tests = VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    const VkAccessFlags depth_rw = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    const VkAccessFlags color_rw = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    // The barrier between the passes. A render pass's subpass dependencies with VK_SUBPASS_EXTERNAL
    // order it against the commands before and after it: here the camera's pass of the previous
    // frame (which read this map) must finish reading before this pass clears and writes it, and
    // this pass's depth writes must be visible to the next pass's shader reads.
    VkSubpassDependency dependencies[2] = {};
    // EXERCISE pass_dependencies: fill both dependencies: which stages and accesses came before (earlier shader reads of the map, earlier depth and colour writes) and must finish before this pass's fragment tests write, and which stages of the passes after it read what this pass wrote? Read "Render Pass Creation" / VkSubpassDependency and "Synchronization and Cache Control" in the spec; `shaders`, `tests`, `depth_rw`, `color_rw` above are most of the pieces (a pass with colour attachments also needs the stage that writes them). Wrong: the synchronization validation layer reports SYNC-HAZARD-WRITE-AFTER-WRITE (this pass's layout transition or store against the writes before it) and SYNC-HAZARD-READ-AFTER-WRITE (a lookup reading the map before the writes are visible); every lab 4 render fails on them; on a real GPU shadows flicker or lag a frame. Checked by Lab4Shadows.SpotLightMatchesTheReference, Lab4Shadows.DirectionalLightMatchesTheReference, Lab4Shadows.TwoOverlappingTranslucentObjectsMultiply.
    // STUB: dependencies[0] = {VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, 0, 0};
    // STUB: dependencies[1] = {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0, 0};
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;  // earlier reads (and this pass's earlier use) first
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = shaders | tests | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[0].srcAccessMask = depth_rw | (color ? color_rw : 0);
    dependencies[0].dstStageMask = tests | (color ? VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT : 0);
    dependencies[0].dstAccessMask = depth_rw | (color ? color_rw : 0);
    dependencies[1].srcSubpass = 0;  // then the map is read by the camera's pass
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = tests | (color ? VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT : 0);
    dependencies[1].srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | (color ? VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT : 0);
    dependencies[1].dstStageMask = shaders;
    dependencies[1].dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    // END EXERCISE

    return lab::create_render_pass(vk, uint32_t(attachments.size()), attachments.data(), subpass, dependencies);
}

VkSamplerCreateInfo depth_sampler_info(bool linear, bool compare) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = info.minFilter = linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    // EXERCISE comparison_sampler: with `compare`, the sampler itself compares the lookup's reference depth (the point's depth from the light) with the stored one and returns 1 (lit) or 0 per texel, before filtering. Which compare op says "lit" for a point no farther than the nearest caster (in which order does the spec put the two operands)? A lookup outside the map (a receiver beyond what the map covers, a PCF tap past its edge) must read "lit": which address mode gives it, in all three coordinates, and which border colour, compared how? Read VkSamplerCreateInfo (addressMode*, borderColor, compareEnable, compareOp), "Wrapping Operation" and "Depth Compare Operation" in the spec. Wrong: everything is lit or shadows are inverted; shadows repeated or smeared beyond the map's edge, or a dark line where it ends. Checked by ComparisonSampler.*, Lab4Shadows.BilinearComparisonMatchesTheReference, Lab4Shadows.DirectionalLightBilinearComparison, Lab4Shadows.ReceiverAtTheShadowMapsEdgeIsLit.
    // STUB: info.compareEnable = compare;
    // STUB: info.compareOp = VK_COMPARE_OP_ALWAYS;  // every texel "lit"; outside the map: repeated
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    info.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    info.compareEnable = compare;
    info.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;  // 1 where reference ≤ stored depth: lit
    // END EXERCISE
    return info;
}

lab::Handle<VkSampler> make_depth_sampler(const lab::VulkanContext& vk, bool linear, bool compare) {
    const VkSamplerCreateInfo info = depth_sampler_info(linear, compare);
    VkSampler sampler;
    VK_CHECK(vkCreateSampler(vk.device(), &info, nullptr, &sampler));
    VkDevice device = vk.device();
    return lab::Handle<VkSampler>(sampler, [device](VkSampler s) { vkDestroySampler(device, s, nullptr); });
}

lab::Handle<VkFramebuffer> make_square_framebuffer(const lab::VulkanContext& vk, VkRenderPass pass,
                                              const std::vector<VkImageView>& views, uint32_t size) {
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = pass;
    info.attachmentCount = uint32_t(views.size());
    info.pAttachments = views.data();
    info.width = info.height = size;
    info.layers = 1;
    VkFramebuffer framebuffer;
    VK_CHECK(vkCreateFramebuffer(vk.device(), &info, nullptr, &framebuffer));
    VkDevice device = vk.device();
    return lab::Handle<VkFramebuffer>(framebuffer, [device](VkFramebuffer f) { vkDestroyFramebuffer(device, f, nullptr); });
}

LayeredTarget& LayeredTarget::operator=(LayeredTarget&& other) noexcept {
    if (this != &other) {
        framebuffers = std::move(other.framebuffers);  // the old ones are destroyed before their views
        layer_views = std::move(other.layer_views);
        faces = std::move(other.faces);
        image = std::move(other.image);
        pass = other.pass;
        size = other.size;
        color = other.color;
    }
    return *this;
}

void LayeredTarget::begin(VkCommandBuffer cmd, uint32_t i, float depth, VkRect2D area, uint32_t used) const {
    begin_offscreen_pass(cmd, pass, framebuffers[i], size, color, depth, area, used);
}

void LayeredTarget::clear(VkCommandBuffer cmd) const {
    for (uint32_t i = 0; i < layers(); ++i) {
        begin(cmd, i);
        vkCmdEndRenderPass(cmd);
    }
}

LayeredTarget create_layered_target(const lab::VulkanContext& vk, VkRenderPass pass, uint32_t size, bool cube, VkFormat format,
                                    VkImageUsageFlags usage, VkImageAspectFlags aspect,
                                    const std::vector<VkImageView>& more) {
    LayeredTarget t;
    t.pass = pass;
    t.size = size;
    t.color = (aspect & VK_IMAGE_ASPECT_COLOR_BIT) != 0;
    t.image = cube ? create_image_cube(vk, size, format, usage, aspect) : create_image_2d(vk, {size, size}, format, usage, aspect);
    for (uint32_t layer = 0; layer < (cube ? 6u : 1u); ++layer) {
        if (cube) t.layer_views.push_back(create_layer_view(vk, t.image.image, format, aspect, layer));
        std::vector<VkImageView> views = {t.layer(layer)};
        views.insert(views.end(), more.begin(), more.end());
        t.framebuffers.push_back(make_square_framebuffer(vk, pass, views, size));
    }
    if (cube) t.faces = create_faces_view(vk, t.image.image, format, aspect);  // the six faces as a 2D array
    return t;
}

void begin_offscreen_pass(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer framebuffer, uint32_t size, bool color,
                          float depth, VkRect2D area, uint32_t used) {
    if (area.extent.width == 0 || area.extent.height == 0) area = {{0, 0}, {size, size}};
    if (used == 0) used = size;
    VkClearValue clears[2];
    clears[0].color = {{1.0f, 1.0f, 0.0f, 0.0f}};  // transmittance 1, nearest translucent depth 1
    clears[color ? 1 : 0].depthStencil = {depth, 0};
    VkRenderPassBeginInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    info.renderPass = pass;
    info.framebuffer = framebuffer;
    info.renderArea = area;
    info.clearValueCount = color ? 2 : 1;
    info.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &info, VK_SUBPASS_CONTENTS_INLINE);
    const VkViewport viewport{0.0f, 0.0f, float(used), float(used), 0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    // Nothing drawn outside the render area, nor outside the used square.
    const int32_t x1 = std::min(area.offset.x + int32_t(area.extent.width), int32_t(used)),
                  y1 = std::min(area.offset.y + int32_t(area.extent.height), int32_t(used));
    const VkRect2D scissor{area.offset, {uint32_t(std::max(x1 - area.offset.x, 0)), uint32_t(std::max(y1 - area.offset.y, 0))}};
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

VkRect2D covered_texels(const glm::dmat4& world_to_clip, const std::vector<lab::Box>& boxes, VkExtent2D extent) {
    const VkRect2D whole{{0, 0}, extent};
    const double w = extent.width, h = extent.height;
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (const lab::Box& box : boxes) {
        int behind = 0;  // corners at or behind the light's plane (w ≤ 0)
        for (int corner = 0; corner < 8; ++corner) {
            const glm::dvec4 p = world_to_clip * glm::dvec4(corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y,
                                                            corner & 4 ? box.hi.z : box.lo.z, 1.0);
            if (p.w <= 1e-9) {
                ++behind;
                continue;
            }
            // The viewport maps x, y in [−1, 1] onto [0, width] and [0, height] (the box's projection
            // holds its contents': projection keeps straight lines straight in front of the plane).
            x0 = std::min(x0, (p.x / p.w + 1.0) * 0.5 * w), x1 = std::max(x1, (p.x / p.w + 1.0) * 0.5 * w);
            y0 = std::min(y0, (p.y / p.w + 1.0) * 0.5 * h), y1 = std::max(y1, (p.y / p.w + 1.0) * 0.5 * h);
        }
        if (behind == 8) continue;  // wholly behind: clipped away (w > 0 holds with depth clamp too)
        if (behind > 0) return whole;  // across the plane: its projection has no bound
    }
    // One texel to spare on each side (the pass rasterizes in float from a float matrix).
    const double left = std::clamp(std::floor(x0) - 1.0, 0.0, w), right = std::clamp(std::ceil(x1) + 1.0, 0.0, w);
    const double top = std::clamp(std::floor(y0) - 1.0, 0.0, h), bottom = std::clamp(std::ceil(y1) + 1.0, 0.0, h);
    if (!(right > left && bottom > top)) return VkRect2D{};  // nothing in front, or all off the map
    return {{int32_t(left), int32_t(top)}, {uint32_t(right - left), uint32_t(bottom - top)}};
}
