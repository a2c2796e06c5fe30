// test_lab1_render.cpp — the real lab 1 binary, rendering headless, against the CPU reference.
//
// Each test runs
//     lab1_camera --scene FILE --headless --validate --out OUT.png --width W --height H
// as a subprocess, then loads the PNG and compares it with ref::render_reference()
// of the same scene file. The expected image comes only from the reference
// (independent double-precision ray casting), never from an earlier GPU run.
//
// Acceptance: every pixel away from silhouettes within 1/255 per channel, and at
// most 0.5 % of all pixels beyond 1/255 (silhouette pixels whose centre lies a
// rounding error away from an edge may legitimately go either way).
// A failing comparison writes OUT_diff.png (expected | actual | diff) next to the output.
#include "reference/cpu_reference.h"
#include "reference/image_compare.h"
#include "lab_runner.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace {

namespace fs = std::filesystem;

const std::string kOutDir = test_output_dir("lab1");
const std::string kTestScenes = std::string(LAB_SOURCE_DIR) + "/tests/scenes";
const std::string kDefaultScene = std::string(LAB_SOURCE_DIR) + "/scenes/lab1_camera.json";

// Runs lab 1 (see lab_runner.h).
RunResult run_lab(const std::string& args, const std::string& log_path) { return ::run_lab(LAB1_EXE, args, log_path); }

std::string render_args(const std::string& scene, const std::string& png, int w, int h) {
    return "--scene " + quoted(scene) + " --headless --validate --out " + quoted(png) +
           " --width " + std::to_string(w) + " --height " + std::to_string(h);
}

// Renders `scene` with the lab at w × h into test_output/lab1/NAME.png.
// Returns the PNG path ("" after a failed assertion).
std::string render_with_lab(const std::string& scene, const std::string& name, int w, int h) {
    const std::string png = kOutDir + "/" + name + ".png";
    std::error_code ec;
    fs::remove(png, ec);
    const RunResult run = run_lab(render_args(scene, png, w, h), kOutDir + "/" + name + ".log");
    EXPECT_EQ(run.exit_code, 0) << "lab1_camera failed on " << scene << ":\n" << run.log;
    if (run.exit_code != 0) return "";
    EXPECT_TRUE(fs::exists(png)) << "no PNG written: " << png << "\n" << run.log;
    return fs::exists(png) ? png : "";
}

// The whole check: lab render vs reference render of the same file.
void expect_matches_reference(const std::string& scene_file, const std::string& name, int w,
                              int h) {
    ASSERT_TRUE(fs::exists(scene_file)) << "missing scene " << scene_file;
    const std::string png = render_with_lab(scene_file, name, w, h);
    if (png.empty()) return;  // already reported
    const lab::Image8 actual = lab::read_png(png);
    ASSERT_EQ(actual.width, w);
    ASSERT_EQ(actual.height, h);

    const lab::Scene scene = lab::load_scene(scene_file);
    const ref::RefImage reference = ref::render_reference(scene, w, h, ref::shade_unlit);
    // The scene must actually show something, or the comparison proves little.
    size_t covered = 0;
    for (int id : reference.object_id) covered += id >= 0;
    EXPECT_GT(covered, reference.object_id.size() / 20) << "test scene shows almost nothing";

    const ref::CompareResult result =
        ref::compare_and_report(actual, reference, kOutDir + "/" + name + "_diff.png");
    EXPECT_TRUE(result.passed()) << scene_file << "\n" << result.describe();
    std::printf("[ compare ] %s: %s\n", name.c_str(), result.describe().c_str());
    ::testing::Test::RecordProperty("max_diff_interior", result.max_diff_interior);
    ::testing::Test::RecordProperty("percent_differing", std::to_string(100.0 * result.fraction_differing));
}

// --- scenes ---------------------------------------------------------------------

TEST(Lab1Render, DefaultScene) {
    expect_matches_reference(kDefaultScene, "default_640x360", 640, 360);
}

TEST(Lab1Render, EveryPrimitiveAndAModel) {
    // All eight primitives (coarse tessellations, so facets and seams show) and the pawn with
    // its own .mtl material.
    expect_matches_reference(kTestScenes + "/lab1_all_primitives.json", "all_primitives", 640, 360);
}

TEST(Lab1Render, OddImageSize) {
    // 97 × 61: no dimension divides evenly, aspect 1.59.
    expect_matches_reference(kDefaultScene, "default_97x61", 97, 61);
}

TEST(Lab1Render, TransformCameraYawPitchRoll) {
    expect_matches_reference(kTestScenes + "/lab1_transform_camera.json", "transform_camera", 320,
                             180);
}

TEST(Lab1Render, TopDownLookAt) {
    // Looking straight down with up = +Y: the documented fallback makes world −Z
    // the top of the image. The scene is asymmetric, so any other choice differs.
    expect_matches_reference(kTestScenes + "/lab1_top_down.json", "top_down", 320, 180);
}

TEST(Lab1Render, TinyObjectsNearPlane) {
    // Millimetre-sized objects (scale 1e-3) seen from a few millimetres, near = 1e-3.
    expect_matches_reference(kTestScenes + "/lab1_tiny_near.json", "tiny_near", 320, 180);
}

TEST(Lab1Render, HugeFloorFarPlane) {
    // A 10 km floor (scale 1e4) and far = 1e5.
    expect_matches_reference(kTestScenes + "/lab1_huge_far.json", "huge_far", 320, 180);
}

TEST(Lab1Render, NonUniformNegativeScaleAndRotations) {
    // Non-uniform scales, rotations about all three axes, and mirrored objects
    // (a negative scale reverses the winding: the GPU culls by the transformed winding).
    expect_matches_reference(kTestScenes + "/lab1_scale_rotation.json", "scale_rotation", 320,
                             180);
}

TEST(Lab1Render, NearAndFarPlanesCutThroughObjects) {
    // near slices a cube and a sphere open (their inside faces are back faces, so
    // the floor shows through), far cuts the floor in the middle of the image.
    expect_matches_reference(kTestScenes + "/lab1_clip_planes.json", "clip_planes", 320, 180);
}

// --- behaviour ------------------------------------------------------------------

TEST(Lab1Render, SameRunTwiceIsByteIdentical) {
    const std::string a = render_with_lab(kDefaultScene, "determinism_a", 320, 180);
    const std::string b = render_with_lab(kDefaultScene, "determinism_b", 320, 180);
    ASSERT_FALSE(a.empty());
    ASSERT_FALSE(b.empty());
    const std::string bytes_a = read_text(a), bytes_b = read_text(b);
    EXPECT_FALSE(bytes_a.empty());
    EXPECT_TRUE(bytes_a == bytes_b) << a << " and " << b << " differ";
}

TEST(Lab1Render, InvalidSceneExitsWithCode2AndWritesNoPng) {
    const std::string scene = kTestScenes + "/lab1_invalid.json";
    ASSERT_TRUE(fs::exists(scene));
    // The test scene really is invalid for the loader (a typo'd key).
    EXPECT_THROW(lab::load_scene(scene), lab::SceneError);

    const std::string png = kOutDir + "/invalid_scene.png";
    std::error_code ec;
    fs::remove(png, ec);
    const RunResult run = run_lab(render_args(scene, png, 64, 64), kOutDir + "/invalid_scene.log");
    EXPECT_EQ(run.exit_code, 2) << run.log;
    EXPECT_FALSE(fs::exists(png)) << "a PNG was written for an invalid scene";
    // The message names the file (one line "FILE: PATH: reason").
    EXPECT_NE(run.log.find("lab1_invalid.json"), std::string::npos) << run.log;
}

TEST(Lab1Render, MissingSceneFileExitsWithCode2) {
    const std::string png = kOutDir + "/missing_scene.png";
    std::error_code ec;
    fs::remove(png, ec);
    const RunResult run = run_lab(render_args(kTestScenes + "/does_not_exist.json", png, 64, 64),
                                  kOutDir + "/missing_scene.log");
    EXPECT_EQ(run.exit_code, 2) << run.log;
    EXPECT_FALSE(fs::exists(png));
}

TEST(Lab1Render, OutputIntoAMissingFolderExitsWithCode2BeforeRendering) {
    const RunResult run = run_lab(render_args(kDefaultScene, kOutDir + "/no_such_folder/x.png", 64, 64),
                                  kOutDir + "/missing_folder.log");
    EXPECT_EQ(run.exit_code, 2) << run.log;
    EXPECT_NE(run.log.find("no_such_folder"), std::string::npos) << run.log;
    EXPECT_EQ(run.log.find("rendered"), std::string::npos) << run.log;  // nothing was rendered
    EXPECT_FALSE(fs::exists(kOutDir + "/no_such_folder"));
}

}  // namespace
