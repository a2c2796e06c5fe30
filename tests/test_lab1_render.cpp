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
#include "lab_render.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace {

namespace fs = std::filesystem;

const LabUnderTest kLab(LAB1_EXE, "lab1");  // writes into test_output/lab1/
const std::string kTestScenes = std::string(LAB_SOURCE_DIR) + "/tests/scenes";
const std::string kDefaultScene = std::string(LAB_SOURCE_DIR) + "/scenes/lab1_camera.json";

// The whole check: lab render vs reference render of the same file.
void expect_matches_reference(const std::string& scene_file, const std::string& name, int w,
                              int h) {
    ASSERT_TRUE(fs::exists(scene_file)) << "missing scene " << scene_file;
    const std::string png = kLab.render(scene_file, name, w, h);
    if (png.empty()) return;  // already reported
    const lab::Image8 actual = lab::read_png(png);
    ASSERT_EQ(actual.width, w);
    ASSERT_EQ(actual.height, h);
    const lab::Scene scene = lab::load_scene(scene_file);
    expect_close_to_reference(kLab, name, scene_file, actual, ref::render_reference(scene, w, h, ref::shade_unlit));
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
    expect_same_run_twice_is_byte_identical(kLab, kDefaultScene);
}

TEST(Lab1Render, InvalidSceneExitsWithCode2AndWritesNoPng) {
    const std::string scene = kTestScenes + "/lab1_invalid.json";
    ASSERT_TRUE(fs::exists(scene));
    // The test scene really is invalid for the loader (a typo'd key).
    EXPECT_THROW(lab::load_scene(scene), lab::SceneError);

    const RenderResult run = kLab.run(scene, "invalid_scene", 64, 64);
    EXPECT_EQ(run.exit_code, 2) << run.log;
    EXPECT_FALSE(run.wrote_png) << "a PNG was written for an invalid scene";
    // The message names the file (one line "FILE: PATH: reason").
    EXPECT_NE(run.log.find("lab1_invalid.json"), std::string::npos) << run.log;
}

TEST(Lab1Render, MissingSceneFileExitsWithCode2) {
    const RenderResult run = kLab.run(kTestScenes + "/does_not_exist.json", "missing_scene", 64, 64);
    EXPECT_EQ(run.exit_code, 2) << run.log;
    EXPECT_FALSE(run.wrote_png);
}

TEST(Lab1Render, OutputIntoAMissingFolderExitsWithCode2BeforeRendering) {
    // (run_lab, not kLab.run: the log must not go into the missing folder, which would create it)
    const RunResult run = run_lab(kLab.exe(), render_args(kDefaultScene, kLab.path("no_such_folder/x.png"), 64, 64),
                                  kLab.path("missing_folder.log"));
    EXPECT_EQ(run.exit_code, 2) << run.log;
    EXPECT_NE(run.log.find("no_such_folder"), std::string::npos) << run.log;
    EXPECT_EQ(run.log.find("rendered"), std::string::npos) << run.log;  // nothing was rendered
    EXPECT_FALSE(fs::exists(kLab.path("no_such_folder")));
}

}  // namespace
