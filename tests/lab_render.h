// lab_render.h — what the render tests (test_labN_render.cpp) share: a lab binary rendering headless
// into the test's output folder, the expectation that the run worked, scene files written there, and
// the check of a picture against a CPU reference image.
//
// A test binds its lab once:
//     const LabUnderTest kLab(LAB1_EXE, "lab1");          // writes into test_output_dir("lab1")
//     const std::string png = kLab.render(scene, "name", 320, 180);  // "" after a failure
// The comparison rules that belong to one lab (lab 3's sampling envelope, lab 4's shadow metric)
// stay in its test file.
#pragma once

#include "lab_runner.h"
#include "reference/cpu_reference.h"
#include "reference/image_compare.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>

// One lab binary and the folder its tests write into, test_output_dir(SUB) (build/test_output/SUB,
// or $LAB_TEST_OUTPUT/SUB under the grader): scene files, PNGs, logs, diff pictures.
class LabUnderTest {
public:
    // `width` × `height`: the size of a render that names none.
    LabUnderTest(std::string exe, const std::string& sub, int width = 320, int height = 180)
        : exe_(std::move(exe)), dir_(test_output_dir(sub)), width_(width), height_(height) {}

    const std::string& exe() const { return exe_; }
    const std::string& dir() const { return dir_; }
    std::string path(const std::string& file) const { return dir_ + "/" + file; }  // DIR/FILE
    // DIR/FILE with its folder created, for a writer that does not create it (lab::write_png).
    std::string make_path(const std::string& file) const {
        const std::string p = path(file);
        std::filesystem::create_directories(std::filesystem::path(p).parent_path());
        return p;
    }
    int width() const { return width_; }
    int height() const { return height_; }

    // Writes `text` to DIR/FILE (creating folders); returns its path.
    std::string write(const std::string& file, const std::string& text) const { return write_file(dir_, file, text); }
    // Writes `text` to DIR/NAME.json; returns its path.
    std::string write_scene(const std::string& name, const std::string& text) const { return write(name + ".json", text); }

    // Renders `scene` into DIR/NAME.png (log DIR/NAME.log) and expects nothing: for runs that
    // should fail, or whose log is the point.
    RenderResult run(const std::string& scene, const std::string& name, const std::string& extra_args = "") const {
        return run(scene, name, width_, height_, extra_args);
    }
    RenderResult run(const std::string& scene, const std::string& name, int width, int height,
                     const std::string& extra_args = "") const {
        // The folder a failing test's hint points at (tests/exercise_hints.cpp): this test's own
        // pictures are there, and a unit test, which renders nothing, gets no such line.
        ::testing::Test::RecordProperty("pictures", dir_);
        return render_lab(exe_, scene, dir_, name, width, height, extra_args);
    }

    // Renders and expects exit code 0 (validation clean) and a PNG; a failure names the command
    // and shows the lab's log. Returns the PNG's path, "" after a failure (already reported).
    std::string render(const std::string& scene, const std::string& name, const std::string& extra_args = "") const {
        return render(scene, name, width_, height_, extra_args);
    }
    std::string render(const std::string& scene, const std::string& name, int width, int height,
                       const std::string& extra_args = "") const {
        const RenderResult r = run(scene, name, width, height, extra_args);
        EXPECT_TRUE(r.ok()) << r.failure();
        return r.ok() ? r.png : "";
    }

private:
    std::string exe_, dir_;
    int width_, height_;
};

// Two renders of the same scene (DIR/determinism_a.png, DIR/determinism_b.png) are the same file,
// byte for byte.
inline void expect_same_run_twice_is_byte_identical(const LabUnderTest& lab, const std::string& scene) {
    const std::string a = lab.render(scene, "determinism_a");
    const std::string b = lab.render(scene, "determinism_b");
    ASSERT_FALSE(a.empty());
    ASSERT_FALSE(b.empty());
    const std::string bytes_a = read_text(a), bytes_b = read_text(b);
    EXPECT_FALSE(bytes_a.empty());
    EXPECT_TRUE(bytes_a == bytes_b) << a << " and " << b << " differ";
}

// A copy of `scene_file` written to DIR/NAME.json, with its relative paths (".obj" meshes, image
// maps) made absolute so that it loads from there, and `edit` applied. Returns the new file.
inline std::string scene_variant(const LabUnderTest& lab, const std::string& scene_file, const std::string& name,
                                 const std::function<void(nlohmann::json&)>& edit = {}) {
    namespace fs = std::filesystem;
    nlohmann::json scene = nlohmann::json::parse(read_text(scene_file));
    const fs::path folder = fs::path(scene_file).parent_path();
    const auto absolute = [&](nlohmann::json& value) {
        const std::string path = value;
        if (fs::path(path).is_relative()) value = (folder / path).string();
    };
    for (nlohmann::json& object : scene["objects"]) {
        const std::string mesh = object["mesh"];
        if (mesh.size() > 4 && mesh.substr(mesh.size() - 4) == ".obj") absolute(object["mesh"]);
    }
    if (scene.contains("materials"))
        for (auto& [key, material] : scene["materials"].items())
            for (const char* map : {"albedo_map", "specular_map", "emissive_map"})
                if (material.contains(map) && material[map].get<std::string>().rfind("procedural:", 0) != 0)
                    absolute(material[map]);
    if (edit) edit(scene);
    return lab.write_scene(name, scene.dump(1));
}

// Pixels of the reference that show an object (not the background).
inline size_t covered_pixels(const ref::RefImage& reference) {
    size_t covered = 0;
    for (int id : reference.object_id) covered += id >= 0;
    return covered;
}

// The check of labs 1 and 2: `actual` (the lab's PNG) against `reference` by ref::compare_images()
// with `options`; on a failure DIR/NAME_diff.png shows expected | actual | diff. The reference must
// show something (over 5 % of the pixels covered), or the comparison proves little. Prints the
// figures and records them in the test's XML report.
inline ref::CompareResult expect_close_to_reference(const LabUnderTest& lab, const std::string& name,
                                                    const std::string& scene_file, const lab::Image8& actual,
                                                    const ref::RefImage& reference,
                                                    const ref::CompareOptions& options = {}) {
    EXPECT_GT(covered_pixels(reference), reference.object_id.size() / 20) << "test scene shows almost nothing";
    const ref::CompareResult result = ref::compare_and_report(actual, reference, lab.path(name + "_diff.png"), options);
    EXPECT_TRUE(result.passed()) << scene_file << "\n" << result.describe();
    std::printf("[ compare ] %s: max interior diff %d/255, %.3f%% of pixels beyond %d/255 (%zu edge pixels)\n",
                name.c_str(), result.max_diff_interior, 100.0 * result.fraction_differing, result.tolerance,
                result.edge_pixels);
    ::testing::Test::RecordProperty("max_diff_interior", result.max_diff_interior);
    ::testing::Test::RecordProperty("percent_differing", std::to_string(100.0 * result.fraction_differing));
    return result;
}
