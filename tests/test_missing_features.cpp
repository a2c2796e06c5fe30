// test_missing_features.cpp — every lab on a device without each optional feature it may use.
//
// `--dev-without-feature NAME` (common/app/dev_options.h) makes the Vulkan context treat NAME as
// unsupported before it enables anything, so a lab takes the path it takes on such a device
// (docs/architecture.md, "Optional features"). Each run has --validate on (any validation message
// fails the run: exit code 1). What a device without each feature gets:
//  - fragmentStoresAndAtomics (lab 4's translucent layers): translucent objects drawn opaque, one
//    warning line; checked on a picture whose colours are known by hand;
//  - samplerAnisotropy (labs 3, 4): no anisotropic sampler, one warning line per clamped sampler;
//  - depthClamp, depthBiasClamp (lab 4's shadow maps): the maps drawn without, one warning line each;
//  - timestamps (every lab's GPU time per pass): --benchmark says so once and prints no gpu_passes line.
// Every lab's default scene renders without each of them; an unknown name is bad input (exit 2).
#include "lab_runner.h"

#include "image_io.h"
#include "pipeline_builder.h"
#include "vk_context.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace {

const std::string kOutDir = test_output_dir("missing_features");

struct LabExe {
    const char* name;
    const char* path;
};
const LabExe kLabs[] = {{"lab1_camera", LAB1_EXE}, {"lab2_lighting", LAB2_EXE}, {"lab3_textures", LAB3_EXE},
                        {"lab4_shadows", LAB4_EXE}};
const char* const kFeatures[] = {"fragmentStoresAndAtomics", "samplerAnisotropy", "depthClamp", "depthBiasClamp",
                                 "timestamps"};

RunResult run_case(const char* exe, const std::string& args, const std::string& name) {
    return run_lab(exe, args, kOutDir + "/" + name + ".log");
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

std::string without(const char* feature) { return std::string(" --dev-without-feature ") + feature; }

// Every lab's default scene, headless, small, validation on: exit 0 and a picture, without each
// feature in turn (labs that do not use a feature must not notice it is gone either).
TEST(MissingFeatures, EveryLabRendersItsDefaultSceneWithoutEachFeature) {
    for (const LabExe& lab : kLabs) {
        for (const char* feature : kFeatures) {
            const std::string name = std::string(lab.name) + "_without_" + feature;
            const std::string png = kOutDir + "/" + name + ".png";
            std::remove(png.c_str());
            const RunResult r = run_case(lab.path, "--headless --validate --width 160 --height 90 --frames 2 --out " +
                                                       quoted(png) + without(feature), name);
            EXPECT_EQ(r.exit_code, 0) << lab.name << " without " << feature << ":\n" << r.log;
            EXPECT_TRUE(std::filesystem::exists(png)) << lab.name << " without " << feature << ": no picture";
        }
    }
}

// Two planes seen from above, no lights, no ambient: each pixel is its material's emissive colour.
// A blue floor, and over the middle a red glass plane of opacity 0.25 (one layer: a plane).
std::string glass_over_blue() {
    return R"({
  "camera": { "position": [0, 4, 2], "target": [0, 0, 0], "fov_y_deg": 40 },
  "background": [0, 0, 0],
  "ambient": { "intensity": 0 },
  "lights": [],
  "materials": {
    "floor": { "albedo": [0, 0, 0], "emissive": [0, 0, 1] },
    "glass": { "albedo": [0, 0, 0], "emissive": [1, 0, 0], "opacity": 0.25 }
  },
  "objects": [
    { "mesh": "plane", "material": "floor", "scale": [20, 1, 20] },
    { "mesh": "plane", "material": "glass", "position": [0, 0.5, 0], "scale": [3, 1, 3] }
  ]
})";
}

// The centre pixel of lab 4's picture of glass_over_blue(), with `extra` on the command line.
std::vector<int> centre_of_glass(const std::string& extra, const std::string& name, std::string* log) {
    const std::string scene = write_file(kOutDir, name + ".json", glass_over_blue());
    const std::string png = kOutDir + "/" + name + ".png";
    const RunResult r = run_case(LAB4_EXE, "--headless --validate --width 64 --height 64 --scene " + quoted(scene) +
                                               " --out " + quoted(png) + extra, name);
    *log = r.log;
    EXPECT_EQ(r.exit_code, 0) << r.log;
    if (r.exit_code != 0) return {};
    const lab::Image8 image = lab::read_png(png);
    const size_t at = 4 * (size_t(image.height / 2) * image.width + image.width / 2);
    return {image.rgba[at], image.rgba[at + 1], image.rgba[at + 2]};
}

// With the feature: the glass over the floor, blended. Linear (0.25·1, 0, 0.75·1) in sRGB:
// 0.25 → 1.055·0.25^(1/2.4) − 0.055 = 0.5371 → 137; 0.75 → 0.8808 → 225 (±1: rounding).
// Without it: the glass drawn opaque, its own red, (255, 0, 0) exactly; and one warning line.
TEST(MissingFeatures, Lab4WithoutFragmentStoresDrawsTranslucentObjectsOpaque) {
    std::string log;
    const std::vector<int> blended = centre_of_glass("", "glass_with_layers", &log);
    ASSERT_EQ(blended.size(), 3u);
    EXPECT_NEAR(blended[0], 137, 1);
    EXPECT_EQ(blended[1], 0);
    EXPECT_NEAR(blended[2], 225, 1);
    EXPECT_EQ(count(log, "fragmentStoresAndAtomics"), 0u) << log;

    const std::vector<int> opaque = centre_of_glass(without("fragmentStoresAndAtomics"), "glass_without_layers", &log);
    ASSERT_EQ(opaque.size(), 3u);
    EXPECT_EQ(opaque, (std::vector<int>{255, 0, 0}));
    EXPECT_EQ(count(log, "warning: no fragmentStoresAndAtomics on this device: translucent objects are drawn opaque"),
              1u)
        << log;
}

// A sampler asking for 16× anisotropy: the device's own (lavapipe has it) without a warning;
// without the feature, one warning naming the clamp and that there is no anisotropic filtering.
TEST(MissingFeatures, Labs3And4WithoutSamplerAnisotropyClampItAndSaySo) {
    const std::string scene = write_file(kOutDir, "anisotropic.json", R"({
  "camera": { "position": [0, 1, 4], "target": [0, 0, 0] },
  "lights": [ { "type": "directional", "direction": [0, -1, -0.5] } ],
  "materials": { "floor": { "albedo": [1, 1, 1], "albedo_map": "procedural:checker",
                            "sampler": { "anisotropic": "sampler", "anisotropy": 16 } } },
  "objects": [ { "mesh": "plane", "material": "floor", "scale": [20, 1, 20] } ]
})");
    const std::string warning = "warning: anisotropy 16 clamped to 1 (the device limit: no anisotropic filtering)";
    for (const LabExe& lab : {kLabs[2], kLabs[3]}) {
        const std::string args = "--headless --validate --width 64 --height 64 --scene " + quoted(scene);
        const RunResult with = run_case(lab.path, args, std::string(lab.name) + "_anisotropy_with");
        EXPECT_EQ(with.exit_code, 0) << with.log;
        EXPECT_EQ(count(with.log, "clamped"), 0u) << with.log;
        const RunResult without_it =
            run_case(lab.path, args + without("samplerAnisotropy"), std::string(lab.name) + "_anisotropy_without");
        EXPECT_EQ(without_it.exit_code, 0) << without_it.log;
        EXPECT_EQ(count(without_it.log, warning), 1u) << without_it.log;
    }
}

// Lab 4's shadow maps without depth clamp or the depth-bias clamp: drawn, and one line each
// saying what the maps lose; not a word about either where the device has them, nor where no
// light casts shadows (lab 3's scene: nothing lost).
TEST(MissingFeatures, Lab4WithoutDepthClampOrDepthBiasClampSaysWhatTheMapsLose) {
    const std::string args = "--headless --validate --width 64 --height 64";
    const RunResult with = run_case(LAB4_EXE, args, "maps_with");
    EXPECT_EQ(with.exit_code, 0) << with.log;
    EXPECT_EQ(count(with.log, "depthClamp") + count(with.log, "depthBiasClamp"), 0u) << with.log;
    const RunResult no_clamp = run_case(LAB4_EXE, args + without("depthClamp"), "maps_without_depth_clamp");
    EXPECT_EQ(no_clamp.exit_code, 0) << no_clamp.log;
    EXPECT_EQ(count(no_clamp.log, "warning: no depthClamp on this device: a caster nearer a light"), 1u) << no_clamp.log;
    const RunResult no_bias = run_case(LAB4_EXE, args + without("depthBiasClamp"), "maps_without_bias_clamp");
    EXPECT_EQ(no_bias.exit_code, 0) << no_bias.log;
    EXPECT_EQ(count(no_bias.log, "warning: no depthBiasClamp on this device: the shadow maps' depth bias"), 1u)
        << no_bias.log;
    const RunResult no_maps = run_case(LAB4_EXE, args + " --scene " + quoted(std::string(LAB_SOURCE_DIR) + "/scenes/lab3_textures.json") +
                                                     without("depthClamp") + without("depthBiasClamp"),
                                       "no_maps_without_clamps");
    EXPECT_EQ(no_maps.exit_code, 0) << no_maps.log;
    EXPECT_EQ(count(no_maps.log, "warning: no depth"), 0u) << no_maps.log;
}

// --benchmark on a device without timestamps: the benchmark line, no gpu_passes line, and one
// line saying why; with them (lavapipe has them) the gpu_passes line is there.
TEST(MissingFeatures, EveryLabBenchmarksWithoutTimestampsAndSaysSo) {
    for (const LabExe& lab : kLabs) {
        const std::string args = "--benchmark 3 --dev-warmup-ms 0 --validate --width 64 --height 64";
        const RunResult with = run_case(lab.path, args, std::string(lab.name) + "_timestamps_with");
        EXPECT_EQ(with.exit_code, 0) << with.log;
        EXPECT_EQ(count(with.log, "\ngpu_passes "), 1u) << with.log;
        const RunResult none = run_case(lab.path, args + without("timestamps"), std::string(lab.name) + "_timestamps_without");
        EXPECT_EQ(none.exit_code, 0) << none.log;
        EXPECT_EQ(count(none.log, "benchmark lab="), 1u) << none.log;
        EXPECT_EQ(count(none.log, "gpu_passes"), 0u) << none.log;
        EXPECT_EQ(count(none.log, "GPU time: this device has no timestamps"), 1u) << none.log;
    }
}

// A name the option does not know is bad input: one line naming it and the known ones, exit 2.
TEST(MissingFeatures, AnUnknownFeatureIsBadInput) {
    const RunResult r = run_case(LAB1_EXE, "--headless --dev-without-feature wideLines", "unknown_feature");
    EXPECT_EQ(r.exit_code, 2) << r.log;
    EXPECT_EQ(count(r.log, "\n"), 1u) << r.log;
    EXPECT_NE(r.log.find("--dev-without-feature: unknown feature 'wideLines' (one of fragmentStoresAndAtomics, "),
              std::string::npos)
        << r.log;
}

// --- limits: a device at the specification's least ------------------------------------------
// `--dev-minimum-limits` lowers the device's limits to the table "Required Limits" of the Vulkan
// specification (lab::minimum_limits). Every descriptor set layout is checked against them before
// Vulkan sees it (lab::descriptor_limit_problem): a set past them is refused with one line.

VkPhysicalDeviceLimits spec_minimums() {
    VkPhysicalDeviceLimits generous{};
    generous.maxImageDimension2D = generous.maxImageDimensionCube = 1u << 15;
    generous.maxFramebufferWidth = generous.maxFramebufferHeight = 1u << 15;
    generous.maxUniformBufferRange = generous.maxStorageBufferRange = UINT32_MAX;
    generous.maxPushConstantsSize = generous.maxBoundDescriptorSets = generous.maxColorAttachments = 1000;
    generous.maxPerStageDescriptorSamplers = generous.maxPerStageDescriptorUniformBuffers = 1000;
    generous.maxPerStageDescriptorStorageBuffers = generous.maxPerStageDescriptorSampledImages = 1000;
    generous.maxPerStageResources = generous.maxDescriptorSetSamplers = generous.maxDescriptorSetUniformBuffers = 1000;
    generous.maxDescriptorSetStorageBuffers = generous.maxDescriptorSetSampledImages = 1000;
    generous.maxSamplerAnisotropy = 64.0f;
    return lab::minimum_limits(generous);
}

// The numbers by hand from the specification's table: 16 samplers and 16 sampled images, 12
// uniform buffers and 4 storage buffers per stage; 96 samplers in a set.
TEST(MinimumLimits, DescriptorCountsAreCheckedPerStageAndPerSet) {
    const VkPhysicalDeviceLimits limits = spec_minimums();
    EXPECT_EQ(limits.maxPerStageDescriptorSamplers, 16u);
    EXPECT_EQ(limits.maxDescriptorSetSamplers, 96u);
    EXPECT_EQ(limits.maxImageDimension2D, 4096u);
    EXPECT_EQ(limits.maxStorageBufferRange, 1u << 27);
    const VkShaderStageFlags fs = VK_SHADER_STAGE_FRAGMENT_BIT, vs = VK_SHADER_STAGE_VERTEX_BIT;
    using B = lab::DescriptorBinding;
    const B ubo{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, vs | fs};
    // 16 combined image samplers in the fragment stage fit exactly; the 17th is one too many.
    EXPECT_EQ(lab::descriptor_limit_problem(limits, {ubo, B{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs, 16}}), "");
    EXPECT_EQ(lab::descriptor_limit_problem(limits, {ubo, B{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs, 15},
                                                     B{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs, 2}}),
              "a descriptor set needs 17 samplers in the fragment stage; this device allows 16 "
              "(maxPerStageDescriptorSamplers)");
    // Stages count apart: 16 in each of two stages fit.
    EXPECT_EQ(lab::descriptor_limit_problem(limits, {B{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, vs, 16},
                                                     B{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs, 16}}),
              "");
    // Five storage buffers in the vertex stage: the fifth is over 4.
    EXPECT_EQ(lab::descriptor_limit_problem(limits, {B{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, vs, 5}}),
              "a descriptor set needs 5 storage buffers in the vertex stage; this device allows 4 "
              "(maxPerStageDescriptorStorageBuffers)");
    // The per-set limit on its own: per-stage limits raised, 97 samplers over two stages.
    VkPhysicalDeviceLimits wide = limits;
    wide.maxPerStageDescriptorSamplers = wide.maxPerStageDescriptorSampledImages = wide.maxPerStageResources = 1000;
    EXPECT_EQ(lab::descriptor_limit_problem(wide, {B{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, vs, 48},
                                                   B{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs, 49}}),
              "a descriptor set needs 97 samplers in one set; this device allows 96 (maxDescriptorSetSamplers)");
}

// Labs 1-3 fit the least limits and render; lab 4's shared set (ShadowMaps::bindings(): the
// arrays of flat and cube depth and transmittance maps, 24 samplers) does not: one line naming the limit, exit 1 (a device that
// cannot run it), no picture.
TEST(MinimumLimits, LabsOneToThreeRenderAndLabFourSaysWhichLimitItPasses) {
    for (const LabExe& lab : kLabs) {
        const std::string name = std::string(lab.name) + "_minimum_limits";
        const std::string png = kOutDir + "/" + name + ".png";
        std::remove(png.c_str());
        const RunResult r = run_case(lab.path, "--headless --validate --width 160 --height 90 --dev-minimum-limits --out " +
                                                   quoted(png), name);
        if (std::string(lab.name) != "lab4_shadows") {
            EXPECT_EQ(r.exit_code, 0) << lab.name << ":\n" << r.log;
            EXPECT_TRUE(std::filesystem::exists(png)) << lab.name;
        } else {
            EXPECT_EQ(r.exit_code, 1) << r.log;
            EXPECT_EQ(count(r.log, "\n"), 1u) << r.log;
            EXPECT_NE(r.log.find("lab4_shadows: error: a descriptor set needs "), std::string::npos) << r.log;
            EXPECT_NE(r.log.find("this device allows 16 (maxPerStageDescriptorSamplers)"), std::string::npos) << r.log;
            EXPECT_FALSE(std::filesystem::exists(png)) << "nothing half-written";
        }
    }
    // The picture's size is checked against the lowered limits too: 4096 is the least maxImageDimension2D.
    const RunResult wide = run_case(LAB1_EXE, "--headless --dev-minimum-limits --width 4097 --height 90", "minimum_limits_width");
    EXPECT_EQ(wide.exit_code, 2) << wide.log;
    EXPECT_NE(wide.log.find("--width 4097: the device allows at most 4096"), std::string::npos) << wide.log;
}

}  // namespace
