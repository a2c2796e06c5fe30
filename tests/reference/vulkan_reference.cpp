// vulkan_reference.cpp — see vulkan_reference.h.
#include "reference/vulkan_reference.h"

#include "buffer.h"
#include "render_target.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ref {

namespace {

// The spec's values for each setting of lab::SamplerDesc ("Samplers": VkFilter,
// VkSamplerAddressMode, VkSamplerMipmapMode; "Level-of-Detail Operation" for the LOD clamp).
VkFilter filter_of(lab::SamplerDesc::Filter f) {
    return f == lab::SamplerDesc::Filter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
}
VkSamplerAddressMode address_mode_of(lab::SamplerDesc::Wrap w) {
    switch (w) {
        case lab::SamplerDesc::Wrap::Repeat: return VK_SAMPLER_ADDRESS_MODE_REPEAT;
        case lab::SamplerDesc::Wrap::Clamp: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        case lab::SamplerDesc::Wrap::Mirror: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    }
    return VK_SAMPLER_ADDRESS_MODE_MAX_ENUM;
}

constexpr const char* kSpec = " (the Vulkan spec, \"Samplers\", and lab::SamplerDesc in scene.h)";
constexpr const char* kCompareSpec =
    " (the Vulkan spec, \"Depth Compare Operation\" and \"Texel Replacement\" for the border, and lab 4's "
    "README: when is a point lit?)";

template <typename T>
void field(std::vector<std::string>& out, const std::string& name, T got, T want, const char* read = kSpec) {
    if (got == want) return;
    std::ostringstream line;
    line << name << " is " << got << ", not what these settings ask for" << read;
    out.push_back(line.str());
}

}  // namespace

std::vector<std::string> sampler_problems(const VkSamplerCreateInfo& got, const lab::SamplerDesc& desc,
                                          float anisotropy, SamplerFields which) {
    std::vector<std::string> out;
    field(out, "sType", int(got.sType), int(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO));
    switch (which) {
        case SamplerFields::Filter:
            field(out, "magFilter", int(got.magFilter), int(filter_of(desc.filter)));
            field(out, "minFilter", int(got.minFilter), int(filter_of(desc.filter)));
            break;
        case SamplerFields::Wrap:
            field(out, "addressModeU", int(got.addressModeU), int(address_mode_of(desc.wrap)));
            field(out, "addressModeV", int(got.addressModeV), int(address_mode_of(desc.wrap)));
            field(out, "addressModeW", int(got.addressModeW), int(address_mode_of(desc.wrap)));
            break;
        case SamplerFields::Mipmaps: {
            field(out, "minLod", double(got.minLod), 0.0);
            if (desc.mipmaps == lab::SamplerDesc::Mipmaps::None) {
                // Level 0 only, with the magnification / minification choice still made from the LOD.
                if (!(got.maxLod <= 0.25f)) field(out, "maxLod", double(got.maxLod), -1.0);
            } else {
                field(out, "mipmapMode", int(got.mipmapMode),
                      int(desc.mipmaps == lab::SamplerDesc::Mipmaps::Linear ? VK_SAMPLER_MIPMAP_MODE_LINEAR
                                                                          : VK_SAMPLER_MIPMAP_MODE_NEAREST));
                const float last_level = std::log2(16384.0f);  // the largest map's levels: 0 … 14
                if (!(got.maxLod >= last_level)) field(out, "maxLod", double(got.maxLod), -1.0);
            }
            break;
        }
        case SamplerFields::Anisotropy:
            field(out, "anisotropyEnable", int(got.anisotropyEnable), int(anisotropy > 1.0f ? VK_TRUE : VK_FALSE));
            if (anisotropy > 1.0f) field(out, "maxAnisotropy", double(got.maxAnisotropy), double(anisotropy));
            break;
    }
    return out;
}

std::vector<std::string> comparison_sampler_problems(const VkSamplerCreateInfo& got) {
    std::vector<std::string> out;
    field(out, "sType", int(got.sType), int(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO));
    field(out, "compareEnable", int(got.compareEnable), int(VK_TRUE), kCompareSpec);
    // The spec's "Depth Compare Operation" applies `D_ref OP D_tex` and returns 1.0 where it holds:
    // lit where ref <= stored, so OP is <=, equality included (a receiver at exactly the stored depth,
    // or at the far plane of a map cleared to 1, is lit).
    field(out, "compareOp", int(got.compareOp), int(VK_COMPARE_OP_LESS_OR_EQUAL), kCompareSpec);
    // Outside the map a CLAMP_TO_BORDER lookup compares against the border colour's R (a depth in
    // [0, 1]): a stored depth of 1, the farthest, so every point there passes <= and is lit.
    const int border = int(VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER);
    field(out, "addressModeU", int(got.addressModeU), border, kCompareSpec);
    field(out, "addressModeV", int(got.addressModeV), border, kCompareSpec);
    field(out, "addressModeW", int(got.addressModeW), border, kCompareSpec);
    field(out, "borderColor", int(got.borderColor), int(VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE), kCompareSpec);
    return out;
}

std::vector<float> texels_as_numbers(const lab::VulkanContext& vk, VkImage image, uint32_t width, uint32_t height) {
    // A nearest blit of the same size into a 32-bit float image converts through both formats
    // (the spec's "Copying Data Between Images"); the float image is copied to a buffer and read.
    const VkExtent2D extent{width, height};
    // (SAMPLED only because create_target_image makes a view, which needs a usage a view can have.)
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    const lab::Image numbers =
        lab::create_target_image(vk, extent, VK_FORMAT_R32G32B32A32_SFLOAT, usage, VK_IMAGE_ASPECT_COLOR_BIT);
    const size_t count = size_t(width) * height * 4;
    lab::Buffer buffer = lab::Buffer::host_visible(vk, count * sizeof(float), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    vk.run_once([&](VkCommandBuffer cmd) {
        const auto copy_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
        lab::target_barrier(cmd, image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                            VK_ACCESS_SHADER_READ_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                            copy_stage);
        lab::target_barrier(cmd, numbers.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                            VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, copy_stage);
        VkImageBlit region{};
        region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.srcOffsets[1] = region.dstOffsets[1] = {int32_t(width), int32_t(height), 1};
        vkCmdBlitImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, numbers.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                       &region, VK_FILTER_NEAREST);
        lab::target_barrier(cmd, numbers.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                            VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, copy_stage, copy_stage);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {width, height, 1};
        vkCmdCopyImageToBuffer(cmd, numbers.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.get(), 1, &copy);
    });
    const float* p = static_cast<const float*>(buffer.mapped());
    return std::vector<float>(p, p + count);
}

std::vector<lab::Image8> read_levels(const lab::VulkanContext& vk, VkImage image, uint32_t width, uint32_t height,
                                     uint32_t levels) {
    std::vector<VkBufferImageCopy> copies;
    VkDeviceSize offset = 0;
    for (uint32_t l = 0; l < levels; ++l) {
        VkBufferImageCopy copy{};
        copy.bufferOffset = offset;
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 1};
        copy.imageExtent = {std::max(width >> l, 1u), std::max(height >> l, 1u), 1};
        copies.push_back(copy);
        offset += VkDeviceSize(copy.imageExtent.width) * copy.imageExtent.height * 4;
    }
    lab::Buffer buffer = lab::Buffer::host_visible(vk, offset, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    // Every level to TRANSFER_SRC and back, each with its memory dependency.
    const auto barrier = [&](VkCommandBuffer cmd, VkImageLayout from, VkImageLayout to, VkAccessFlags src_access,
                             VkAccessFlags dst_access, VkPipelineStageFlags src_stage, VkPipelineStageFlags dst_stage) {
        VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        b.srcAccessMask = src_access;
        b.dstAccessMask = dst_access;
        b.oldLayout = from;
        b.newLayout = to;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, 1};
        vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
    };
    vk.run_once([&](VkCommandBuffer cmd) {
        barrier(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_SHADER_READ_BIT,
                VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.get(), uint32_t(copies.size()),
                               copies.data());
        barrier(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_READ_BIT,
                VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
    });
    std::vector<lab::Image8> out;
    for (const VkBufferImageCopy& c : copies) {
        lab::Image8 im;
        im.width = int(c.imageExtent.width);
        im.height = int(c.imageExtent.height);
        const uint8_t* p = static_cast<const uint8_t*>(buffer.mapped()) + c.bufferOffset;
        im.rgba.assign(p, p + size_t(im.width) * size_t(im.height) * 4);
        out.push_back(std::move(im));
    }
    return out;
}

}  // namespace ref
