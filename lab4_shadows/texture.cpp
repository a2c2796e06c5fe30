// texture.cpp — a texture map on the GPU: staging copy, layout transitions, the mip chain.
#include "texture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace {

double srgb_to_linear(uint8_t v) {
    const double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
uint8_t linear_to_srgb(double c) {
    c = std::clamp(c, 0.0, 1.0);
    const double e = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return uint8_t(std::lround(e * 255.0));
}

bool can_blit_linear(const lab::VulkanContext& vk, VkFormat format) {
    const VkFormatProperties fp = vk.format_properties(format);
    const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                        VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    return (fp.optimalTilingFeatures & needed) == needed;
}

// The parent texels a child texel i of `out` covers along one side, with their weights:
// [i·in/out, (i + 1)·in/out) in parent texels, each weighted by how much of it lies inside.
std::vector<std::pair<int, double>> footprint(int i, int in, int out) {
    const double lo = double(i) * in / out, hi = double(i + 1) * in / out;
    std::vector<std::pair<int, double>> taps;
    for (int p = int(std::floor(lo)); p < int(std::ceil(hi)) && p < in; ++p) {
        const double w = std::min(hi, double(p + 1)) - std::max(lo, double(p));
        if (w > 0.0) taps.emplace_back(p, w / (hi - lo));
    }
    return taps;
}

}  // namespace

// The image's format says how the sampler turns a texel's bytes into the numbers a shader
// reads. The bytes are the same whatever the format; only their meaning differs.
VkFormat format_of(MapKind kind) {
    // EXERCISE texel_format: which VkFormat does each of a material's three maps get? For each map, decide what its bytes are (a colour, sRGB-encoded as image files store colours, or plain numbers) from what it does in the lighting equation, then which format makes the sampler hand the shader linear values. Read texture.h's header comment, docs/lighting.md's equation, the Vulkan spec's "Conversion to RGBA" (sRGB). Wrong: textured surfaces look washed out and too bright, their mip levels too light. Checked by TexelFormat.*, Lab3Render.AlbedoImageTimesColour, Lab3Render.AlbedoMapMagnified.
    // STUB: return VK_FORMAT_R8G8B8A8_UNORM;  // every map read as plain numbers
    return kind == MapKind::Specular ? VK_FORMAT_R8G8B8A8_UNORM : VK_FORMAT_R8G8B8A8_SRGB;
    // END EXERCISE
}

uint32_t mip_level_count(uint32_t width, uint32_t height) {
    uint32_t levels = 1;
    for (uint32_t size = std::max(width, height); size > 1; size /= 2) ++levels;
    return levels;
}

bool blit_halves_exactly(uint32_t width, uint32_t height) {
    return (width % 2 == 0 || width == 1) && (height % 2 == 0 || height == 1);
}

lab::Image8 downsample(const lab::Image8& image, TexelEncoding encoding) {
    lab::Image8 out;
    out.width = std::max(image.width / 2, 1);
    out.height = std::max(image.height / 2, 1);
    out.rgba.resize(size_t(out.width) * size_t(out.height) * 4);
    // Decoded once: the parent in linear numbers (a byte has 256 values: a table, not a pow per texel).
    double decode[256];
    for (int v = 0; v < 256; ++v) decode[v] = encoding == TexelEncoding::Srgb ? srgb_to_linear(uint8_t(v)) : v / 255.0;
    std::vector<double> linear(image.rgba.size());
    for (size_t i = 0; i < image.rgba.size(); ++i) linear[i] = i % 4 != 3 ? decode[image.rgba[i]] : image.rgba[i] / 255.0;
    std::vector<std::vector<std::pair<int, double>>> columns(size_t(out.width)), rows(size_t(out.height));
    for (int x = 0; x < out.width; ++x) columns[size_t(x)] = footprint(x, image.width, out.width);
    for (int y = 0; y < out.height; ++y) rows[size_t(y)] = footprint(y, image.height, out.height);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < 4; ++c) {
                double sum = 0.0;
                for (const auto& [py, wy] : rows[size_t(y)])
                    for (const auto& [px, wx] : columns[size_t(x)])
                        sum += wx * wy * linear[(size_t(py) * size_t(image.width) + size_t(px)) * 4 + size_t(c)];
                out.rgba[(size_t(y) * size_t(out.width) + size_t(x)) * 4 + size_t(c)] =
                    encoding == TexelEncoding::Srgb && c != 3 ? linear_to_srgb(sum) : uint8_t(std::lround(std::clamp(sum, 0.0, 1.0) * 255.0));
            }
    return out;
}

Texture upload_texture(const lab::VulkanContext& vk, const lab::Image8& pixels, bool mipmaps, MipSource source, VkFormat format) {
    Texture t;
    t.width = uint32_t(pixels.width);
    t.height = uint32_t(pixels.height);
    t.levels = mipmaps ? mip_level_count(t.width, t.height) : 1;
    // The CPU's box filter averages what the sampler will read: an _SRGB image's texels decoded.
    const TexelEncoding encoding = format == VK_FORMAT_R8G8B8A8_SRGB ? TexelEncoding::Srgb : TexelEncoding::Linear;
    // Blits only when each level is exactly the 2×2 box of the one above: both sides even (or 1)
    // at every step. Otherwise (wood.png, 100×60: 25×15 → 12×7 is a 2.08-texel box) the CPU box.
    bool exact = true;
    for (uint32_t level = 0, w = t.width, h = t.height; level + 1 < t.levels; ++level, w = std::max(w / 2, 1u), h = std::max(h / 2, 1u))
        exact = exact && blit_halves_exactly(w, h);
    const bool gpu_mips = t.levels > 1 && source == MipSource::Auto && exact && can_blit_linear(vk, format);

    // The CPU fallback computes every level here; the GPU path uploads level 0 only.
    std::vector<lab::Image8> chain{pixels};
    if (t.levels > 1 && !gpu_mips)
        while (chain.size() < t.levels) chain.push_back(downsample(chain.back(), encoding));
    VkDeviceSize bytes = 0;
    for (const lab::Image8& level : chain) bytes += level.rgba.size();
    lab::Buffer staging = lab::Buffer::host_visible(vk, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    std::vector<VkBufferImageCopy> copies;
    VkDeviceSize offset = 0;
    for (uint32_t level = 0; level < chain.size(); ++level) {
        std::memcpy(static_cast<char*>(staging.mapped()) + offset, chain[level].rgba.data(), chain[level].rgba.size());
        VkBufferImageCopy copy{};
        copy.bufferOffset = offset;
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
        copy.imageExtent = {uint32_t(chain[level].width), uint32_t(chain[level].height), 1};
        copies.push_back(copy);
        offset += chain[level].rgba.size();
    }

    // The image lives in device memory the CPU cannot write (on a GPU: fast, not mappable), so the
    // pixels travel through a host-visible staging buffer and a copy command. Its usage says
    // everything it will be: sampled, a copy's destination, and TRANSFER_SRC (the blits read the
    // levels above; tests read every level back).
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    t.image = create_image_2d(vk, {t.width, t.height}, format, usage, VK_IMAGE_ASPECT_COLOR_BIT, t.levels);
    const VkImage image = t.image.image;
    vk.run_once([&](VkCommandBuffer cmd) {
        const auto transfer = VK_PIPELINE_STAGE_TRANSFER_BIT;
        // A new image's layout is UNDEFINED (its contents may be discarded); a copy writes only
        // into TRANSFER_DST_OPTIMAL. The barrier changes the layout of every level and orders the
        // change before the copy's writes.
        image_barrier(cmd, image, 0, t.levels, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, transfer);
        vkCmdCopyBufferToImage(cmd, staging.get(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, uint32_t(copies.size()),
                               copies.data());
        // A level is done when it is in SHADER_READ_ONLY_OPTIMAL, its last write (copy or blit)
        // made visible to the fragment shader's reads.
        const auto to_shader = [&](uint32_t level, VkImageLayout from, VkAccessFlags access) {
            image_barrier(cmd, image, level, 1, from, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, access,
                    VK_ACCESS_SHADER_READ_BIT, transfer, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
        };
        if (!gpu_mips) {
            for (uint32_t level = 0; level < t.levels; ++level)
                to_shader(level, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT);
            return;
        }
        // Each level is a linear-filtered blit of the one above at half the size: for even sizes
        // exactly the 2×2 box (an sRGB blit decodes, filters in linear colour, encodes).
        // EXERCISE mip_chain: record the chain: for each level from 1 up, what must happen to the level above before a blit may read it, which rectangle goes to which, and when is a level done (ready for the fragment shader)? Read vkCmdBlitImage and VkImageBlit in the spec ("Copying Data Between Images"), and what to_shader() above does. Wrong: the far floor turns black or noisy (levels 1+ never written), or the validation layer reports a layout mismatch. Checked by MipChain.DataMapLevelsAreBoxesOfTheLevelAbove, MipChain.EveryLevelIsTheBoxOfTheLevelAboveOnBothPaths, Lab3Render.MinifiedFloorTrilinear.
        // STUB: for (uint32_t level = 0; level < t.levels; ++level)  // only level 0 holds pixels
        // STUB:     to_shader(level, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT);
        int32_t w = int32_t(t.width), h = int32_t(t.height);
        for (uint32_t level = 1; level < t.levels; ++level) {
            image_barrier(cmd, image, level - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, transfer, transfer);
            const int32_t nw = std::max(w / 2, 1), nh = std::max(h / 2, 1);
            VkImageBlit blit{};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, 1};
            blit.srcOffsets[1] = {w, h, 1};
            blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
            blit.dstOffsets[1] = {nw, nh, 1};
            vkCmdBlitImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           1, &blit, VK_FILTER_LINEAR);
            to_shader(level - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_TRANSFER_READ_BIT);
            w = nw;
            h = nh;
        }
        to_shader(t.levels - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT);
        // END EXERCISE
    });
    return t;
}
