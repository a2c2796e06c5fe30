// test_offscreen.cpp — lab 4's offscreen.h (layered render targets) and depth_view.h (the map view) on a
// real device, validation on: each layer of a cube target cleared to its own depth, shown by the
// depth view, read back at the squares' centres (positions and greys worked out by hand); and the
// part of a square target a set of boxes can cover (covered_texels); the comparison sampler's create
// info against the reference's reading of the spec.
#include "depth_view.h"
#include "headless_target.h"
#include "offscreen.h"
#include "probe.h"
#include "reference/vulkan_reference.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace {

constexpr uint32_t kSize = 200;  // the frame, 200×200: NDC x, y ∈ [−1, 1] → pixel (x + 1) · 100

// What an 8-bit sRGB target stores for linear grey `v`.
int srgb8(double v) {
    const double s = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    return int(std::lround(255.0 * s));
}

int red_at(const lab::Image8& image, int x, int y) { return image.rgba[(size_t(y) * size_t(image.width) + size_t(x)) * 4]; }

// Clears every layer of `target` to depth[layer] (its pass begun and ended on each).
void clear_layers(VkCommandBuffer cmd, const LayeredTarget& target, const std::vector<float>& depth) {
    for (uint32_t layer = 0; layer < target.layers(); ++layer) {
        target.begin(cmd, layer, depth[layer]);
        vkCmdEndRenderPass(cmd);
    }
}

TEST(Offscreen, LayeredTargetsAndTheDepthViewShowEachLayer) {
    int messages = 0;
    {
        lab::ContextOptions options;
        options.validate = true;
        options.message_count = &messages;
        lab::VulkanContext vk(options);
        lab::HeadlessTarget frame_target(vk, {kSize, kSize});
        const VkFormatFeatureFlags use = VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
        const VkFormat format = format_supports(vk, VK_FORMAT_D32_SFLOAT, use) ? VK_FORMAT_D32_SFLOAT : VK_FORMAT_D16_UNORM;
        const lab::Handle<VkRenderPass> pass = make_offscreen_pass(vk, VK_FORMAT_UNDEFINED, format);
        const VkImageUsageFlags usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;

        // A cube: six layers, each with its own 2D view and framebuffer; a 2D target: its view is its layer.
        const LayeredTarget cube = create_layered_target(vk, pass, 4, true, format, usage, VK_IMAGE_ASPECT_DEPTH_BIT);
        ASSERT_EQ(cube.layers(), 6u);
        std::set<VkImageView> views;
        for (uint32_t i = 0; i < 6; ++i) views.insert(cube.layer(i));
        EXPECT_EQ(views.size(), 6u);
        EXPECT_EQ(views.count(cube.image.view.get()), 0u) << "a face is a 2D view, not the cube view";
        LayeredTarget flat = create_layered_target(vk, pass, 8, false, format, usage, VK_IMAGE_ASPECT_DEPTH_BIT);
        ASSERT_EQ(flat.layers(), 1u);
        EXPECT_EQ(flat.layer(0), flat.image.view.get());
        EXPECT_TRUE(cube.pass == pass.get() && cube.size == 4 && flat.size == 8 && !cube.color);

        DepthView depth_view(vk, frame_target.render_pass(), 7, LAB4_SHADER_DIR);
        // Frame 1: layer i of the cube at depth (i + 1) / 8, orthographic (shown as stored).
        // Six squares of 0.42 NDC (84 / 2 rows), three to a row, 0.01 apart, centred:
        // column centres x0 + 0.21 = (c − 1.5) · 0.43 + 0.21 → −0.435, −0.005, 0.425 → pixels 56, 99, 142;
        // the second row ends at y = 0.98, the first 0.43 above it: centres 0.34, 0.77 → pixels 134, 177.
        const std::vector<float> depths = {0.125f, 0.25f, 0.375f, 0.5f, 0.625f, 0.75f};
        lab::Frame frame;
        ASSERT_TRUE(frame_target.begin_frame(glm::vec3(0.0f), frame, [&](const lab::Frame& f) {
            clear_layers(f.cmd, cube, depths);
        }));
        depth_view.draw(frame.cmd, cube, glm::mat4(1.0f), frame.extent);
        frame_target.end_frame();
        lab::Image8 image = frame_target.read_pixels();
        const int xs[3] = {56, 99, 142}, ys[2] = {134, 177};
        for (int i = 0; i < 6; ++i)
            EXPECT_NEAR(red_at(image, xs[i % 3], ys[i / 3]), srgb8(depths[size_t(i)]), 1) << "layer " << i;
        EXPECT_EQ(red_at(image, 5, 5), 0) << "outside the squares: the clear colour";
        EXPECT_EQ(red_at(image, 99, 100), 0) << "above the squares";

        // Frame 2: a perspective map (near 1, far 11), cleared to the depth GLM's projection gives the
        // point 3.5 along the view axis: shown as (z − near) / (far − near) = 0.25. One square of
        // 0.8 NDC: x ∈ [−0.405, 0.395], y ∈ [0.18, 0.98] → centre pixel (99, 158).
        const glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, 1.0f, 11.0f);
        const glm::vec4 clip = projection * glm::vec4(0.0f, 0.0f, -3.5f, 1.0f);
        ASSERT_TRUE(frame_target.begin_frame(glm::vec3(0.0f), frame, [&](const lab::Frame& f) {
            clear_layers(f.cmd, flat, {clip.z / clip.w});
        }));
        depth_view.draw(frame.cmd, flat, glm::inverse(projection), frame.extent);
        frame_target.end_frame();
        image = frame_target.read_pixels();
        EXPECT_NEAR(red_at(image, 99, 158), srgb8(0.25), 1);
        EXPECT_EQ(red_at(image, 56, 134), 0) << "the cube's squares are gone";
    }
    EXPECT_EQ(messages, 0) << "validation messages (see stderr)";
}

}  // namespace

// comparison_sampler: the fields that decide what a lookup returns (compare op, address modes, border
// colour), as the reference reads the spec and the lesson's rule; nearest and linear, as the lab makes
// both. The render tests see the same choice only where a reference depth equals a stored one.
TEST(ComparisonSampler, ComparesAndBordersAsTheLessonAsks) {
    for (const bool linear : {false, true}) {
        std::string text;
        // The lab's sampler info (LAB_PROBE, probe.h); its pNext is the lab's own pointer, not compared.
        VkSamplerCreateInfo info = LAB_PROBE(depth_sampler_info(linear, true));
        info.pNext = nullptr;
        for (const std::string& problem : ref::comparison_sampler_problems(info))
            text += "\n  " + problem;
        EXPECT_TRUE(text.empty()) << (linear ? "linear" : "nearest") << " comparison sampler:" << text;
    }
}

// covered_texels: the texels a pass must cover (worked out by hand:
// a 100² map, NDC x, y ∈ [−1, 1] → texel (x + 1) · 50, then a texel to spare on each side).
TEST(CoveredTexels, CoversTheBoxesProjectionAndNoMore) {
    const glm::dmat4 ortho(1.0);  // world = clip, w = 1
    // x ∈ [−0.5, 0.5] → [25, 75] → [24, 76]; y ∈ [−0.25, 0.25] → [37.5, 62.5] → [36, 64].
    const VkRect2D r = covered_texels(ortho, {lab::Box{{-0.5, -0.25, 0.0}, {0.5, 0.25, 0.5}}}, 100);
    EXPECT_EQ(r.offset.x, 24);
    EXPECT_EQ(r.offset.y, 36);
    EXPECT_EQ(r.extent.width, 52u);
    EXPECT_EQ(r.extent.height, 28u);
    // Two boxes: the rectangle around both; one reaching past the map: cut at its edge.
    const VkRect2D two = covered_texels(
        ortho, {lab::Box{{-0.5, -0.25, 0.0}, {0.5, 0.25, 0.5}}, lab::Box{{0.8, 0.5, 0.0}, {1.5, 0.6, 0.1}}}, 100);
    EXPECT_EQ(two.offset.x, 24);
    EXPECT_EQ(two.offset.y, 36);
    EXPECT_EQ(two.extent.width, 76u);  // to 100
    EXPECT_EQ(two.extent.height, 45u);  // to ceil(80) + 1 = 81
    // No box, or a box wholly off the map: nothing to draw.
    EXPECT_EQ(covered_texels(ortho, {}, 100).extent.width, 0u);
    EXPECT_EQ(covered_texels(ortho, {lab::Box{{2.0, 2.0, 0.0}, {3.0, 3.0, 1.0}}}, 100).extent.width, 0u);
}

TEST(CoveredTexels, PerspectiveBoxesBehindOrAcrossTheLight) {
    // A perspective map looking down −z from the origin (90°, near 0.1, far 10): w = −z.
    const glm::dmat4 look = glm::perspectiveRH_ZO(glm::radians(90.0), 1.0, 0.1, 10.0);
    // In front, at z = −2: x ∈ [−1.1, 0.9] → NDC [−0.55, 0.45] → [22.5, 72.5] → [21, 74].
    const VkRect2D front = covered_texels(look, {lab::Box{{-1.1, -1.0, -2.0}, {0.9, 1.0, -2.0}}}, 100);
    EXPECT_EQ(front.offset.x, 21);
    EXPECT_EQ(front.extent.width, 53u);
    // Wholly behind the light (z > 0): clipped away, nothing.
    EXPECT_EQ(covered_texels(look, {lab::Box{{-1.0, -1.0, 1.0}, {1.0, 1.0, 2.0}}}, 100).extent.width, 0u);
    // Across the light's plane: its projection has no bound, so the whole map.
    const VkRect2D across = covered_texels(look, {lab::Box{{0.5, 0.5, -1.0}, {0.6, 0.6, 1.0}}}, 100);
    EXPECT_EQ(across.offset.x, 0);
    EXPECT_EQ(across.offset.y, 0);
    EXPECT_EQ(across.extent.width, 100u);
    EXPECT_EQ(across.extent.height, 100u);
}
