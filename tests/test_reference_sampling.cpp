// test_reference_sampling.cpp — the oracle's texture sampling (tests/reference/cpu_texture.*) by
// hand: wrap modes, nearest and bilinear lookups, the mip chain's box, LOD and trilinear. The
// instructors' check of the reference; a student copy holds the reference prebuilt and leaves this
// file out (docs/solutions.md).
#include "reference/cpu_texture.h"

#include "scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

// --- the reference's sampling, by hand ---------------------------------------------

TEST(ReferenceSampling, WrapModes) {
    using W = lab::SamplerDesc::Wrap;
    // size 4: repeat −1 → 3, 4 → 0; mirror: … 1 0 | 0 1 2 3 | 3 2 …; clamp to [0, 3].
    EXPECT_EQ(ref::wrap_texel(-1, 4, W::Repeat), 3);
    EXPECT_EQ(ref::wrap_texel(4, 4, W::Repeat), 0);
    EXPECT_EQ(ref::wrap_texel(-9, 4, W::Repeat), 3);
    EXPECT_EQ(ref::wrap_texel(-1, 4, W::Mirror), 0);
    EXPECT_EQ(ref::wrap_texel(-2, 4, W::Mirror), 1);
    EXPECT_EQ(ref::wrap_texel(4, 4, W::Mirror), 3);
    EXPECT_EQ(ref::wrap_texel(5, 4, W::Mirror), 2);
    EXPECT_EQ(ref::wrap_texel(8, 4, W::Mirror), 0);
    EXPECT_EQ(ref::wrap_texel(-5, 4, W::Clamp), 0);
    EXPECT_EQ(ref::wrap_texel(7, 4, W::Clamp), 3);
}

namespace {
// A 2×2 texture of sRGB 0, 255 / 255, 0 in red: linear texels 0, 1 / 1, 0.
ref::RefTexture two_by_two(bool mipmaps) {
    return ref::make_texture(2, 2, {0, 0, 0, 255, 255, 0, 0, 255, 255, 0, 0, 255, 0, 0, 0, 255}, mipmaps);
}
}  // namespace

TEST(ReferenceSampling, NearestAndBilinearAtHandPickedPoints) {
    using F = lab::SamplerDesc::Filter;
    using W = lab::SamplerDesc::Wrap;
    const ref::RefTexture t = two_by_two(false);
    const ref::TextureLevel& l = t.levels[0];
    // Texel centres are at (i + ½)/2: u = 0.25 is texel 0's centre.
    EXPECT_DOUBLE_EQ(ref::sample_level(l, {0.25, 0.25}, F::Linear, W::Repeat).r, 0.0);
    EXPECT_DOUBLE_EQ(ref::sample_level(l, {0.75, 0.25}, F::Linear, W::Repeat).r, 1.0);
    // Halfway between centres: the mean of the four (two 1s, two 0s).
    EXPECT_DOUBLE_EQ(ref::sample_level(l, {0.5, 0.5}, F::Linear, W::Repeat).r, 0.5);
    // u = 0.375 (x = 0.75 − 0.5 = 0.25 past texel 0), v = 0.25: 0.75·0 + 0.25·1.
    EXPECT_DOUBLE_EQ(ref::sample_level(l, {0.375, 0.25}, F::Linear, W::Repeat).r, 0.25);
    // At u = 0 repeat blends texel 1 (left neighbour, value 1) and texel 0 half and half;
    // clamp sees only texel 0; mirror reflects texel 0 onto itself.
    EXPECT_DOUBLE_EQ(ref::sample_level(l, {0.0, 0.25}, F::Linear, W::Repeat).r, 0.5);
    EXPECT_DOUBLE_EQ(ref::sample_level(l, {0.0, 0.25}, F::Linear, W::Clamp).r, 0.0);
    EXPECT_DOUBLE_EQ(ref::sample_level(l, {0.0, 0.25}, F::Linear, W::Mirror).r, 0.0);
    // Nearest: floor(u·2).
    EXPECT_DOUBLE_EQ(ref::sample_level(l, {0.49, 0.1}, F::Nearest, W::Repeat).r, 0.0);
    EXPECT_DOUBLE_EQ(ref::sample_level(l, {0.5, 0.1}, F::Nearest, W::Repeat).r, 1.0);
    EXPECT_DOUBLE_EQ(ref::sample_level(l, {-0.1, 0.1}, F::Nearest, W::Repeat).r, 1.0);   // texel −1 → 1
    EXPECT_DOUBLE_EQ(ref::sample_level(l, {1.1, 0.1}, F::Nearest, W::Mirror).r, 1.0);    // texel 2 → 1
    EXPECT_DOUBLE_EQ(ref::sample_level(l, {1.1, 0.1}, F::Nearest, W::Clamp).r, 1.0);
    // Huge coordinates with repeat: 1e6 + 0.25 is texel 0's centre again.
    EXPECT_NEAR(ref::sample_level(l, {1e6 + 0.25, 0.25}, F::Linear, W::Repeat).r, 0.0, 1e-9);
}

TEST(ReferenceSampling, MipChainIsALinearBox) {
    const ref::RefTexture t = two_by_two(true);
    ASSERT_EQ(t.levels.size(), 2u);
    EXPECT_DOUBLE_EQ(t.levels[1].at(0, 0).r, 0.5);  // linear mean; sRGB 188 when encoded
    // sRGB 128 decodes to 0.21586 (the spec's transfer function).
    EXPECT_NEAR(ref::make_texture(1, 1, {128, 128, 128, 255}, false).levels[0].at(0, 0).g, 0.2158605, 1e-6);
    const ref::RefTexture odd = ref::make_texture(3, 1, {0, 0, 0, 255, 255, 255, 255, 255, 0, 0, 0, 255}, true);
    ASSERT_EQ(odd.levels.size(), 2u);  // 3×1 → 1×1
    EXPECT_EQ(odd.levels[1].width, 1);
    EXPECT_DOUBLE_EQ(odd.levels[1].at(0, 0).r, 1.0 / 3.0);  // all three texels: (0 + 1 + 0) / 3
    // 5 → 2: each child covers 2.5 parent texels: (0 + 1 + ½·0) / 2.5 = 0.4; data, not sRGB.
    const ref::RefTexture five = ref::make_texture(5, 1, {0, 0, 0, 255, 255, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255}, true, false);
    EXPECT_DOUBLE_EQ(five.levels[1].at(0, 0).r, 0.4);
    EXPECT_DOUBLE_EQ(five.levels[1].at(1, 0).r, 0.0);
}

TEST(ReferenceSampling, LodAndTrilinear) {
    const ref::RefTexture t = ref::make_texture(4, 4, std::vector<unsigned char>(64, 255), true);
    // One pixel step moves u by 1/4 = one texel: ρ = 1, λ = 0. Two texels: λ = 1.
    EXPECT_DOUBLE_EQ(ref::lod(t.levels[0], {0.25, 0}, {0, 0.25}), 0.0);
    EXPECT_DOUBLE_EQ(ref::lod(t.levels[0], {0.5, 0}, {0, 0.1}), 1.0);
    EXPECT_DOUBLE_EQ(ref::lod(t.levels[0], {0.3, 0.4}, {0, 0}), std::log2(2.0));  // |(1.2, 1.6)| = 2
    // Trilinear between levels 0 (4×4) and 1 (2×2) of a texture whose levels differ.
    std::vector<unsigned char> px;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) px.insert(px.end(), {(unsigned char)((x < 2) == (y < 2) ? 255 : 0), 0, 0, 255});
    const ref::RefTexture q = ref::make_texture(4, 4, px, true);  // 2×2 quadrants: level 1 = same quadrants
    ASSERT_EQ(q.levels.size(), 3u);
    EXPECT_DOUBLE_EQ(q.levels[1].at(0, 0).r, 1.0);
    EXPECT_DOUBLE_EQ(q.levels[1].at(1, 0).r, 0.0);
    EXPECT_DOUBLE_EQ(q.levels[2].at(0, 0).r, 0.5);
    lab::SamplerDesc s;
    s.anisotropy = 1;
    // λ = log2(3) = 1.585 at the centre of texel (0,0) of level 1 (u = 0.25): level 1 gives 1,
    // level 2 gives 0.5, weight 0.585: 1 − 0.585·0.5 = 0.7075.
    const double lambda = std::log2(3.0), expected = 1.0 - (lambda - 1.0) * 0.5;
    EXPECT_NEAR(ref::sample(q, s, {0.25, 0.25}, {0.75, 0}, {0, 0}).r, expected, 1e-12);
    s.mipmaps = lab::SamplerDesc::Mipmaps::Nearest;  // ceil(1.585 + 0.5) − 1 = 2: level 2 only
    EXPECT_DOUBLE_EQ(ref::sample(q, s, {0.25, 0.25}, {0.75, 0}, {0, 0}).r, 0.5);
    s.mipmaps = lab::SamplerDesc::Mipmaps::None;  // level 0, bilinear at texel (0,0)'s far corner
    EXPECT_DOUBLE_EQ(ref::sample(q, s, {0.25, 0.25}, {0.75, 0}, {0, 0}).r, 1.0);
}
