#include "imgui_renderer.h"

#include "pipeline_builder.h"
#include "render_target.h"
#include "shader.h"

#include <imgui.h>

// SPIR-V of common/app/shaders/*, compiled by CMake into uint32_t arrays.
#include "imgui_frag_spv.h"
#include "imgui_vert_spv.h"
#include "overlay_frag_spv.h"
#include "overlay_vert_spv.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>

namespace lab {

namespace {
static_assert(sizeof(ImDrawIdx) == 2, "the index buffer is bound as VK_INDEX_TYPE_UINT16");

// sRGB transfer function (IEC 61966-2-1), value in [0, 1].
double encode_srgb(double linear) {
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// For each sRGB byte s, the linear byte l whose encoding (what the *_SRGB target writes) comes
// closest to s: the panel shows ImGui's designed colours as exactly as 8-bit vertex colours allow
// (dark tones, where linear bytes are coarse, within 2/255 for the default dark style).
std::array<uint8_t, 256> make_srgb_to_linear_table() {
    std::array<uint8_t, 256> table{};
    int l = 0;
    for (int s = 0; s < 256; ++s) {
        // encode() is increasing: move l up while the next byte encodes closer to s.
        while (l < 255 && std::abs(encode_srgb((l + 1) / 255.0) * 255.0 - s) <=
                              std::abs(encode_srgb(l / 255.0) * 255.0 - s))
            ++l;
        table[size_t(s)] = uint8_t(l);
    }
    return table;
}

// The overlay's render pass: one colour attachment, cleared to transparent, left ready for
// sampling. Its contents before the pass are not needed (the whole drawn area is redrawn).
Handle<VkRenderPass> make_overlay_pass(const VulkanContext& vk, VkFormat format) {
    VkAttachmentDescription color{};
    color.format = format;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    color.finalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;

    VkSubpassDependency dependencies[2] = {};
    // Earlier frames (possibly still in flight) read the overlay in their fragment shaders and
    // copies: those reads must be over before this pass overwrites it (write after read).
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependencies[0].srcAccessMask = 0;
    dependencies[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    // ...and this pass's writes must be done before the frames that blend or copy it read it.
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependencies[1].dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;

    return create_render_pass(vk, 1, &color, subpass, dependencies);
}

// Blending of premultiplied colour: out = src.rgb + dst.rgb · (1 − src.a) (alpha likewise).
VkPipelineColorBlendAttachmentState premultiplied_over() {
    VkPipelineColorBlendAttachmentState state{};
    state.blendEnable = VK_TRUE;
    state.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
    state.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    state.colorBlendOp = VK_BLEND_OP_ADD;
    state.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    state.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    state.alphaBlendOp = VK_BLEND_OP_ADD;
    state.colorWriteMask =
        VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    return state;
}

template <typename T>
void append_bytes(std::vector<uint8_t>& out, const T* data, size_t count) {
    const auto* bytes = reinterpret_cast<const uint8_t*>(data);
    out.insert(out.end(), bytes, bytes + count * sizeof(T));
}
template <typename T>
void append_value(std::vector<uint8_t>& out, const T& value) {
    append_bytes(out, &value, 1);
}

// ImGui's font atlas as a sampled image: one level, copied from a staging buffer. (Lab 3 teaches
// texture uploads; the panels are not a lesson, so they keep their own few lines here.)
Image upload_font_atlas(const VulkanContext& vk, const unsigned char* rgba, uint32_t width, uint32_t height) {
    const VkDeviceSize bytes = VkDeviceSize(width) * height * 4;
    Buffer staging = Buffer::host_visible(vk, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    std::memcpy(staging.mapped(), rgba, size_t(bytes));
    Image atlas = create_target_image(vk, {width, height}, VK_FORMAT_R8G8B8A8_SRGB,
                                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    vk.run_once([&](VkCommandBuffer cmd) {
        target_barrier(cmd, atlas.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                       VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {width, height, 1};
        vkCmdCopyBufferToImage(cmd, staging.get(), atlas.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        target_barrier(cmd, atlas.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                       VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
    });
    return atlas;
}
}  // namespace

// The overlay has the target's format (8-bit sRGB, like the swapchain): dark premultiplied colours
// keep their precision, and its opaque pixels can be copied bit for bit. (On lavapipe blending a
// pixel costs about 40 % of compositing it and reading the overlay 60 %, whatever the overlay's
// format: R8G8B8A8_UNORM, R16G16B16A16_UNORM and _SFLOAT measured the same; copying is far cheaper.)
ImGuiRenderer::ImGuiRenderer(const VulkanContext& vk, VkRenderPass target_pass, VkFormat target_format,
                             bool copy_to_target)
    : vk_(vk), overlay_format_(target_format), copy_to_target_(copy_to_target),
      srgb_to_linear_(make_srgb_to_linear_table()) {
    VkDevice device = vk.device();

    // The font atlas: white texels whose alpha is the glyph's coverage. In the R8G8B8A8_SRGB
    // texture white decodes to exactly 1.0 and alpha is stored linearly, as in a UNORM one.
    unsigned char* pixels = nullptr;
    int width = 0, height = 0;
    ImGui::GetIO().Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
    font_ = upload_font_atlas(vk, pixels, uint32_t(width), uint32_t(height));

    // Nearest filtering: the panels are drawn at one texel per pixel (glyphs start on whole
    // pixels), where linear filtering reads the same texel at four times the cost on a CPU driver.
    VkSamplerCreateInfo sampler_info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sampler_info.magFilter = VK_FILTER_NEAREST;
    sampler_info.minFilter = VK_FILTER_NEAREST;
    sampler_info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    sampler_info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sampler_info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sampler_info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    VkSampler sampler;
    VK_CHECK(vkCreateSampler(device, &sampler_info, nullptr, &sampler));
    nearest_ = Handle<VkSampler>(sampler, [device](VkSampler s) { vkDestroySampler(device, s, nullptr); });

    const std::vector<DescriptorBinding> bindings{{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT}};
    set_layout_ = make_descriptor_set_layout(vk, bindings);
    pool_ = make_descriptor_pool(vk, bindings, 2);
    font_set_ = allocate_descriptor_set(vk, pool_, set_layout_);
    overlay_set_ = allocate_descriptor_set(vk, pool_, set_layout_);
    write_image_descriptor(vk, font_set_, 0, nearest_, font_.view);

    overlay_pass_ = make_overlay_pass(vk, overlay_format_);
    {
        const Handle<VkShaderModule> vert = make_shader_module(vk, imgui_vert_spv, sizeof(imgui_vert_spv));
        const Handle<VkShaderModule> frag = make_shader_module(vk, imgui_frag_spv, sizeof(imgui_frag_spv));
        PipelineBuilder::Result ui = PipelineBuilder()
                                         .shaders(vert, frag)
                                         .vertex_layout(sizeof(ImDrawVert),
                                                        {{0, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(ImDrawVert, pos)},
                                                         {1, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(ImDrawVert, uv)},
                                                         {2, 0, VK_FORMAT_R8G8B8A8_UNORM, offsetof(ImDrawVert, col)}})
                                         .descriptor_set(set_layout_)
                                         .push_constants(VK_SHADER_STAGE_VERTEX_BIT, 4 * sizeof(float))
                                         .cull(VK_CULL_MODE_NONE)
                                         .depth(false, false)
                                         .alpha_blend(true)  // colour src·α + dst·(1−α), alpha α + dst·(1−α)
                                         .build(vk, overlay_pass_);
        ui_layout_ = std::move(ui.layout);
        ui_pipeline_ = std::move(ui.pipeline);
    }
    {
        const Handle<VkShaderModule> vert = make_shader_module(vk, overlay_vert_spv, sizeof(overlay_vert_spv));
        const Handle<VkShaderModule> frag = make_shader_module(vk, overlay_frag_spv, sizeof(overlay_frag_spv));
        PipelineBuilder::Result composite = PipelineBuilder()
                                                .shaders(vert, frag)
                                                .vertex_attributes(0)  // no vertex buffer
                                                .topology(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP)
                                                .descriptor_set(set_layout_)
                                                .push_constants(VK_SHADER_STAGE_VERTEX_BIT, 4 * sizeof(float))
                                                .cull(VK_CULL_MODE_NONE)
                                                .depth(false, false)
                                                .color_blend(premultiplied_over())
                                                .build(vk, target_pass);
        composite_layout_ = std::move(composite.layout);
        composite_pipeline_ = std::move(composite.pipeline);
    }
}

ImGuiRenderer::~ImGuiRenderer() = default;

void ImGuiRenderer::make_overlay(VkExtent2D extent) {
    if (overlay_.image) VK_CHECK(vkDeviceWaitIdle(vk_.device()));  // frames in flight still read it (a resize: rare)
    overlay_framebuffer_ = {};
    overlay_ = create_target_image(vk_, extent, overlay_format_,
                                   VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                       VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                   VK_IMAGE_ASPECT_COLOR_BIT);
    overlay_framebuffer_ = make_framebuffer(vk_, overlay_pass_, {overlay_.view}, extent);
    write_image_descriptor(vk_, overlay_set_, 0, nearest_, overlay_.view);
    overlay_extent_ = extent;
    overlay_valid_ = false;
}

bool ImGuiRenderer::same_as_last(const ImDrawData& draw_data, VkExtent2D extent) {
    // Everything the overlay's pixels depend on, as bytes: the framebuffer, the display, and
    // each draw list's vertices, indices and commands (clip rectangles, ranges).
    current_.clear();
    append_value(current_, extent);
    append_value(current_, draw_data.DisplayPos);
    append_value(current_, draw_data.DisplaySize);
    append_value(current_, draw_data.FramebufferScale);
    append_value(current_, draw_data.CmdListsCount);
    for (int i = 0; i < draw_data.CmdListsCount; ++i) {
        const ImDrawList& list = *draw_data.CmdLists[i];
        append_value(current_, list.VtxBuffer.Size);
        append_value(current_, list.IdxBuffer.Size);
        append_value(current_, list.CmdBuffer.Size);
        append_bytes(current_, list.VtxBuffer.Data, size_t(list.VtxBuffer.Size));
        append_bytes(current_, list.IdxBuffer.Data, size_t(list.IdxBuffer.Size));
        for (const ImDrawCmd& c : list.CmdBuffer) {
            append_value(current_, c.ClipRect);
            append_value(current_, c.TextureId);
            append_value(current_, c.VtxOffset);
            append_value(current_, c.IdxOffset);
            append_value(current_, c.ElemCount);
            append_value(current_, c.UserCallback);
        }
    }
    const bool same = overlay_valid_ && current_ == last_;
    std::swap(current_, last_);
    return same;
}

void ImGuiRenderer::upload(uint32_t slot, const ImDrawData& draw_data) {
    const VkDeviceSize vertex_bytes = VkDeviceSize(draw_data.TotalVtxCount) * sizeof(ImDrawVert);
    const VkDeviceSize index_bytes = VkDeviceSize(draw_data.TotalIdxCount) * sizeof(ImDrawIdx);
    // Grown to the next power of two (at least 64 KiB), never shrunk: a few reallocations at most.
    const auto grow = [&](Buffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage) {
        if (buffer.get() && buffer.size() >= bytes) return;
        VkDeviceSize size = 64 * 1024;
        while (size < bytes) size *= 2;
        buffer = Buffer::host_visible(vk_, size, usage);
    };
    grow(vertices_[slot], vertex_bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    grow(indices_[slot], index_bytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);

    auto* vertex_out = static_cast<ImDrawVert*>(vertices_[slot].mapped());
    auto* index_out = static_cast<ImDrawIdx*>(indices_[slot].mapped());
    for (int i = 0; i < draw_data.CmdListsCount; ++i) {
        const ImDrawList& list = *draw_data.CmdLists[i];
        // ImGui 1.86 designs its colours (style, widgets, the labs' own) in sRGB and has no
        // option for an sRGB target: without this the target would encode them a second time
        // (washed-out panels). Alpha is coverage, not colour: left alone. (Blending happens in
        // linear space, so translucent panels differ slightly from ImGui's gamma-space design.)
        for (const ImDrawVert& v : list.VtxBuffer) {
            ImDrawVert out = v;
            const ImU32 c = v.col;
            out.col = ImU32(srgb_to_linear_[(c >> IM_COL32_R_SHIFT) & 0xFF]) << IM_COL32_R_SHIFT |
                      ImU32(srgb_to_linear_[(c >> IM_COL32_G_SHIFT) & 0xFF]) << IM_COL32_G_SHIFT |
                      ImU32(srgb_to_linear_[(c >> IM_COL32_B_SHIFT) & 0xFF]) << IM_COL32_B_SHIFT |
                      (c & IM_COL32_A_MASK);
            *vertex_out++ = out;
        }
        std::memcpy(index_out, list.IdxBuffer.Data, size_t(list.IdxBuffer.Size) * sizeof(ImDrawIdx));
        index_out += list.IdxBuffer.Size;
    }
}

void ImGuiRenderer::draw_overlay(VkCommandBuffer cmd, uint32_t slot, const ImDrawData& draw_data) {
    VkClearValue clear{};  // transparent: colour 0, coverage 0
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = overlay_pass_;
    begin.framebuffer = overlay_framebuffer_;
    begin.renderArea = {{regions_.bounds.x0, regions_.bounds.y0},
                        {uint32_t(regions_.bounds.x1 - regions_.bounds.x0), uint32_t(regions_.bounds.y1 - regions_.bounds.y0)}};
    begin.clearValueCount = 1;
    begin.pClearValues = &clear;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);

    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, ui_pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, ui_layout_, 0, 1, &font_set_, 0, nullptr);
    const VkBuffer vertex_buffer = vertices_[slot].get();
    const VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &zero);
    vkCmdBindIndexBuffer(cmd, indices_[slot].get(), 0, VK_INDEX_TYPE_UINT16);
    const VkViewport viewport{0.0f, 0.0f, float(overlay_extent_.width), float(overlay_extent_.height), 0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    // ImGui's display coordinates to clip space.
    const float scale[2] = {2.0f / draw_data.DisplaySize.x, 2.0f / draw_data.DisplaySize.y};
    const float push[4] = {scale[0], scale[1], -1.0f - draw_data.DisplayPos.x * scale[0],
                           -1.0f - draw_data.DisplayPos.y * scale[1]};
    vkCmdPushConstants(cmd, ui_layout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), push);

    const ImVec2 origin = draw_data.DisplayPos, fb_scale = draw_data.FramebufferScale;
    uint32_t vertex_base = 0, index_base = 0;
    for (int i = 0; i < draw_data.CmdListsCount; ++i) {
        const ImDrawList& list = *draw_data.CmdLists[i];
        for (const ImDrawCmd& c : list.CmdBuffer) {
            if (c.UserCallback) continue;  // the labs add no callbacks
            // The clip rectangle in framebuffer pixels, inside the render area.
            const int32_t x0 = std::max(regions_.bounds.x0, int32_t(std::floor((c.ClipRect.x - origin.x) * fb_scale.x)));
            const int32_t y0 = std::max(regions_.bounds.y0, int32_t(std::floor((c.ClipRect.y - origin.y) * fb_scale.y)));
            const int32_t x1 = std::min(regions_.bounds.x1, int32_t(std::ceil((c.ClipRect.z - origin.x) * fb_scale.x)));
            const int32_t y1 = std::min(regions_.bounds.y1, int32_t(std::ceil((c.ClipRect.w - origin.y) * fb_scale.y)));
            if (x0 >= x1 || y0 >= y1 || c.ElemCount == 0) continue;
            const VkRect2D scissor{{x0, y0}, {uint32_t(x1 - x0), uint32_t(y1 - y0)}};
            vkCmdSetScissor(cmd, 0, 1, &scissor);
            vkCmdDrawIndexed(cmd, c.ElemCount, 1, c.IdxOffset + index_base, int32_t(c.VtxOffset + vertex_base), 0);
        }
        vertex_base += uint32_t(list.VtxBuffer.Size);
        index_base += uint32_t(list.IdxBuffer.Size);
    }
    vkCmdEndRenderPass(cmd);
}

void ImGuiRenderer::prepare(VkCommandBuffer cmd, uint32_t slot, VkExtent2D extent, const ImDrawData& draw_data) {
    if (!overlay_.image || extent.width != overlay_extent_.width || extent.height != overlay_extent_.height)
        make_overlay(extent);
    if (same_as_last(draw_data, extent)) return;  // the overlay already shows these panels
    regions_ = find_ui_regions(draw_data, int32_t(extent.width), int32_t(extent.height),
                               ImGui::GetIO().Fonts->TexUvWhitePixel, copy_to_target_);
    copies_.clear();  // the copy regions as vkCmdCopyImage takes them, reused until the panels change
    for (const PixelRect& r : regions_.copy) {
        VkImageCopy copy{};
        copy.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.dstSubresource = copy.srcSubresource;
        copy.srcOffset = {r.x0, r.y0, 0};
        copy.dstOffset = copy.srcOffset;
        copy.extent = {uint32_t(r.x1 - r.x0), uint32_t(r.y1 - r.y0), 1};
        copies_.push_back(copy);
    }
    if (!regions_.bounds.empty()) {
        upload(slot, draw_data);
        draw_overlay(cmd, slot, draw_data);
    }
    overlay_valid_ = true;
    ++redraws_;
}

void ImGuiRenderer::composite(VkCommandBuffer cmd) const {
    if (regions_.blend.empty()) return;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, composite_pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, composite_layout_, 0, 1, &overlay_set_, 0, nullptr);
    const VkViewport viewport{0.0f, 0.0f, float(overlay_extent_.width), float(overlay_extent_.height), 0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    const VkRect2D scissor{{0, 0}, overlay_extent_};
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    const float sx = 2.0f / float(overlay_extent_.width), sy = 2.0f / float(overlay_extent_.height);
    for (const PixelRect& r : regions_.blend) {
        // The rectangle in clip space, drawn as two triangles: exactly its pixels are shaded.
        const float rect[4] = {float(r.x0) * sx - 1.0f, float(r.y0) * sy - 1.0f, float(r.x1) * sx - 1.0f,
                               float(r.y1) * sy - 1.0f};
        vkCmdPushConstants(cmd, composite_layout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(rect), rect);
        vkCmdDraw(cmd, 4, 1, 0, 0);
    }
}

void ImGuiRenderer::copy_opaque(VkCommandBuffer cmd, VkImage target_image) const {
    if (copies_.empty()) return;
    // The overlay is kept in the layout for sampling; for the copy it moves to the one for copying
    // from, and back (a frame's composite has read it; the next frame's may read it again).
    target_barrier(cmd, overlay_.image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, 0,
                   VK_ACCESS_TRANSFER_READ_BIT,
                   VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                   VK_PIPELINE_STAGE_TRANSFER_BIT);
    vkCmdCopyImage(cmd, overlay_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target_image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, uint32_t(copies_.size()), copies_.data());
    target_barrier(cmd, overlay_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0,
                   VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
}

}  // namespace lab
