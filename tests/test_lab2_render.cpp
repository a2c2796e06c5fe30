// test_lab2_render.cpp — the real lab 2 binary, rendering headless, against the CPU reference.
//
// Each test runs
//     lab2_lighting --scene FILE --headless --validate --out OUT.png --width W --height H
// and compares the PNG with ref::render_reference() of the same scene, shaded by
// ref::make_lighting_shader() (tests/reference/cpu_lighting.*: the equation of
// docs/lighting.md in double precision, written independently of the shaders).
//
// Acceptance (per-pixel Phong shading, and also flat and Gouraud, whose reference evaluates
// the same places — face normal per pixel, equation per vertex): every pixel away from edges
// within 2/255 per channel, at most 0.5 % of all pixels beyond it. "Edges" are silhouettes,
// plus the discontinuities a lighting model has by design (toon bands, hard spot edges, the
// N·L = 0 line where a highlight is cut off; ref::discontinuity_key), plus triangle borders
// for flat shading. Flat and Gouraud also print their error against per-pixel Phong: the lesson.
//
// Variants of a scene (another lighting model, ...) are written to test_output/lab2/ with the
// "lighting" section replaced; relative .obj paths are made absolute first.
#include "reference/cpu_lighting.h"
#include "lab_render.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

using json = nlohmann::json;

constexpr int kWidth = 320, kHeight = 180;
const LabUnderTest kLab(LAB2_EXE, "lab2", kWidth, kHeight);  // writes into test_output/lab2/
const std::string kTestScenes = std::string(LAB_SOURCE_DIR) + "/tests/scenes";
const std::string kScenes = std::string(LAB_SOURCE_DIR) + "/scenes";

// `scene_file` with its "lighting" section's keys replaced by `lighting` (a JSON object text),
// written to test_output/lab2/NAME.json. Returns the new file.
std::string variant(const std::string& scene_file, const std::string& name, const std::string& lighting) {
    const json overrides = json::parse(lighting);
    return scene_variant(kLab, scene_file, name, [&](json& scene) {
        for (const auto& [key, value] : overrides.items()) scene["lighting"][key] = value;
    });
}

// The reference with the designed discontinuities folded into the object ids, so that
// ref::edge_mask() treats them like silhouettes.
ref::RefImage reference_of(const lab::Scene& scene, const ref::ShadeFn& shade) {
    ref::RefImage image = ref::render_reference(scene, kWidth, kHeight, shade);
    for (size_t i = 0; i < image.hits.size(); ++i)
        if (image.object_id[i] >= 0)
            image.object_id[i] = (image.object_id[i] * 7919 + ref::discontinuity_key(scene, image.hits[i])) & 0x3fffffff;
    return image;
}

ref::CompareOptions lit_options(const lab::Scene& scene) {
    ref::CompareOptions options;
    options.tolerance = 2;
    options.triangle_edges = scene.lighting.shading == lab::LightingDesc::Shading::Flat;
    options.grazing_cos = 0.05;
    return options;
}

// Renders `scene_file` with the lab and checks it against the reference. Returns the result
// (and the image through `actual`) for further reporting.
ref::CompareResult expect_matches_reference(const std::string& scene_file, const std::string& name,
                                            lab::Image8* actual_out = nullptr) {
    const std::string png = kLab.render(scene_file, name);
    if (png.empty()) return {};
    const lab::Image8 actual = lab::read_png(png);
    const lab::Scene scene = lab::load_scene(scene_file);
    EXPECT_EQ(ref::magenta_pixels(actual), 0u) << "NaN/Inf marker color in " << png;
    const ref::CompareResult result = expect_close_to_reference(
        kLab, name, scene_file, actual, reference_of(scene, ref::make_lighting_shader(scene)), lit_options(scene));
    if (actual_out) *actual_out = actual;
    return result;
}

// Mean and max |difference| (1/255 units) over pixels that are not on the edge mask.
struct ErrorStats {
    double mean = 0.0;
    int max = 0;
    double percent_over_2 = 0.0;
};
ErrorStats error_against(const lab::Image8& actual, const ref::RefImage& reference, const ref::CompareOptions& options) {
    const lab::Image8 expected = ref::encode_srgb(reference);
    const std::vector<uint8_t> mask = ref::edge_mask(reference, options);
    ErrorStats s;
    size_t n = 0, over = 0;
    for (size_t p = 0; p < mask.size(); ++p) {
        if (mask[p]) continue;
        int worst = 0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(actual.rgba[4 * p + c]) - int(expected.rgba[4 * p + c])));
        s.mean += worst;
        s.max = std::max(s.max, worst);
        over += worst > 2;
        ++n;
    }
    if (n > 0) {
        s.mean /= double(n);
        s.percent_over_2 = 100.0 * double(over) / double(n);
    }
    return s;
}

const std::string kAll = kTestScenes + "/lab2_all_lights.json";

// --- light types ----------------------------------------------------------------

TEST(Lab2Render, DirectionalLight) { expect_matches_reference(kTestScenes + "/lab2_directional.json", "directional"); }
TEST(Lab2Render, PointLights) { expect_matches_reference(kTestScenes + "/lab2_point.json", "point"); }
TEST(Lab2Render, SpotLights) { expect_matches_reference(kTestScenes + "/lab2_spot.json", "spot"); }
TEST(Lab2Render, EveryPrimitiveAndAModelLit) {
    // Normals of every primitive (coarse, so hard and smooth edges both show) and of the pawn,
    // whose normals the OBJ loader computes with the crease angle.
    expect_matches_reference(kTestScenes + "/lab2_all_primitives.json", "all_primitives");
}
TEST(Lab2Render, AllLightTypesTogether) { expect_matches_reference(kAll, "all_lights"); }
TEST(Lab2Render, SpotEdgeFalloff) {
    expect_matches_reference(variant(kAll, "spot_edge", R"({"spot_falloff": "edge"})"), "spot_edge");
}
TEST(Lab2Render, DefaultScene) {
    // Markers off: the reference does not draw them.
    expect_matches_reference(variant(kScenes + "/lab2_lighting.json", "default", R"({"markers": false})"), "default");
}
TEST(Lab2Render, AmbientOnly) {
    // No lights: lab 2 takes lab 1's unlit path with e + ambient·a per object.
    expect_matches_reference(variant(kScenes + "/lab2_ambient_only.json", "ambient", R"({"markers": false})"), "ambient");
}
TEST(Lab2Render, ManyLights) {
    expect_matches_reference(variant(kScenes + "/lab2_many_lights.json", "many", R"({"markers": false})"), "many");
}

// --- one exercise per picture ----------------------------------------------------------
// Each scene keeps every code path but one exercise's where that exercise's stub and its answer
// agree: the Lambert model (no highlight at all), objects unturned at uniform scale (the normals
// only turn and stretch with the object; the floor's (8, 1, 8) keeps its normal's direction),
// point and spot lights without falloff ([1, 0, 0]), per-pixel shading. One of these is changed:
// the thing the test is about.
std::string one_term(const std::string& scene_file, const std::string& name, bool turned, const std::string& model = "lambert",
                     const std::string& shading = "phong", bool falloff = false) {
    return scene_variant(kLab, scene_file, name, [&](json& scene) {
        scene["lighting"]["model"] = model;
        scene["lighting"]["shading"] = shading;
        if (!falloff)
            for (json& light : scene["lights"])
                if (light["type"] != "directional") light["attenuation"] = {1, 0, 0};
        if (!turned)
            for (json& object : scene["objects"])
                if (object["mesh"] != "plane") {
                    object.erase("rotation_deg");
                    object["scale"] = {1, 1, 1};
                }
    });
}
// normal_matrix: turned, non-uniformly scaled objects under a directional light.
TEST(Lab2Term, TurnedAndSquashedObjects) {
    expect_matches_reference(one_term(kTestScenes + "/lab2_directional.json", "term_normals", true), "term_normals");
}
// attenuation: two point lights with their falloff.
// The second picture gives one light k = (0, 0, 0) (docs/scene-format.md: no falloff at all).
TEST(Lab2Term, PointLightFalloff) {
    const std::string file = one_term(kTestScenes + "/lab2_point.json", "term_falloff", false, "lambert", "phong", true);
    expect_matches_reference(file, "term_falloff");
    expect_matches_reference(scene_variant(kLab, file, "term_no_falloff",
                                           [](json& scene) { scene["lights"][1]["attenuation"] = {0, 0, 0}; }),
                             "term_no_falloff");
}
// spot_cone: two spot lights, no falloff with distance; the second picture gives one of them
// inner_deg = outer_deg (docs/scene-format.md: a hard edge).
TEST(Lab2Term, SpotCones) {
    const std::string file = one_term(kTestScenes + "/lab2_spot.json", "term_spots", false);
    expect_matches_reference(file, "term_spots");
    expect_matches_reference(scene_variant(kLab, file, "term_spot_hard_edge",
                                           [](json& scene) {
                                               scene["lights"][1]["inner_deg"] = 20;
                                               scene["lights"][1]["outer_deg"] = 20;
                                           }),
                             "term_spot_hard_edge");
}
// blinn_phong: the highlights of the default model under a directional light.
TEST(Lab2Term, BlinnPhongHighlights) {
    expect_matches_reference(one_term(kTestScenes + "/lab2_directional.json", "term_highlights", false, "blinn_phong"),
                             "term_highlights");
}
// blinn_phong: Phong's own highlight (L's mirror image about N, against V) under the same light.
TEST(Lab2Term, PhongHighlights) {
    expect_matches_reference(one_term(kTestScenes + "/lab2_directional.json", "term_phong_highlights", false, "phong"),
                             "term_phong_highlights");
}
// face_normal: flat shading of coarse, turned and squashed objects (a sphere and a torus of 10 × 5
// quads), Lambert under a directional light: each triangle one normal, its own, whatever the
// vertex normals and the normal matrix say. (The reference takes (v1 − v0) × (v2 − v0) of the hit
// triangle in world space.)
TEST(Lab2Term, FlatFacets) {
    expect_matches_reference(scene_variant(kLab, one_term(kTestScenes + "/lab2_directional.json", "term_flat", true, "lambert", "flat"),
                                           "term_flat",
                                           [](json& scene) {
                                               for (json& object : scene["objects"])
                                                   if (object.contains("segments")) object["segments"] = 10, object["rings"] = 5;
                                           }),
                             "term_flat");
}
// Gouraud: the same equation per vertex (lit.vert). The floor is stretched along its normal to
// (8, 16, 8), which a plane (all at y = 0) does not show: its normal keeps its direction (+Y) but,
// with the normal matrix scaled so its largest element is 1 (docs/lighting.md "The default
// equation"), reaches lit.vert at length 0.5. Only a shader that normalizes N lights the floor
// like the reference (N·L, not N·L / 2).
TEST(Lab2Term, GouraudShading) {
    const std::string file = one_term(kTestScenes + "/lab2_directional.json", "term_gouraud", false, "lambert", "gouraud");
    expect_matches_reference(scene_variant(kLab, file, "term_gouraud",
                                           [](json& scene) {
                                               for (json& object : scene["objects"])
                                                   if (object["mesh"] == "plane") object["scale"] = {8, 16, 8};
                                           }),
                             "term_gouraud");
}

// --- lighting models (per-pixel shading) ----------------------------------------------

class Lab2Model : public ::testing::TestWithParam<std::string> {};
TEST_P(Lab2Model, MatchesReference) {
    const std::string model = GetParam();
    std::string lighting = R"({"model": ")" + model + R"("})";
    if (model == "cook_torrance_beckmann") lighting = R"({"model": "cook_torrance", "distribution": "beckmann"})";
    expect_matches_reference(variant(kAll, "model_" + model, lighting), "model_" + model);
}
INSTANTIATE_TEST_SUITE_P(AllModels, Lab2Model,
                         ::testing::Values("lambert", "phong", "blinn_phong", "toon", "oren_nayar", "minnaert",
                                           "cook_torrance", "cook_torrance_beckmann", "ward"),
                         [](const auto& info) { return info.param; });

// --- shading models: each against its own reference, and the error vs per-pixel Phong ---

void shading_lesson(const char* shading) {
    const std::string name = std::string("shading_") + shading;
    const std::string file = variant(kAll, name, std::string(R"({"shading": ")") + shading + "\"}");
    lab::Image8 actual;
    expect_matches_reference(file, name, &actual);
    if (actual.rgba.empty()) return;
    const lab::Scene scene = lab::load_scene(file);
    const ref::RefImage phong = reference_of(scene, ref::make_lighting_shader(scene, lab::LightingDesc::Shading::Phong));
    ref::CompareOptions options = lit_options(scene);
    options.triangle_edges = false;
    const ErrorStats e = error_against(actual, phong, options);
    std::printf("[ lesson  ] %s vs per-pixel Phong: mean %.2f/255, max %d/255, %.1f%% of pixels beyond 2/255\n",
                shading, e.mean, e.max, e.percent_over_2);
    ::testing::Test::RecordProperty("mean_error_vs_phong", std::to_string(e.mean));
    ::testing::Test::RecordProperty("max_error_vs_phong", e.max);
    EXPECT_GT(e.max, 2) << "expected " << shading << " shading to differ visibly from per-pixel Phong";
}
TEST(Lab2Shading, FlatVsPhong) { shading_lesson("flat"); }
TEST(Lab2Shading, GouraudVsPhong) { shading_lesson("gouraud"); }

// --- stress: no NaN / Inf may reach a pixel ---------------------------------------------------
//
// With "nan_check": "on" the shaders test every intermediate (isnan / isinf) and paint the
// pixel magenta (255, 0, 255) if any is bad; the stress scenes must have no magenta pixel and
// match the reference (which documents what each case renders). "self_test" injects a 0/0
// into every lit pixel to show the detector really fires on this driver.

TEST(Lab2Stress, NumbersMatchReferenceWithoutNaN) {
    expect_matches_reference(variant(kTestScenes + "/lab2_stress_numbers.json", "stress_numbers", R"({"nan_check": "on"})"),
                             "stress_numbers");
}
TEST(Lab2Stress, GeometryMatchesReferenceWithoutNaN) {
    // A light inside a sphere and inside a cube, a spot with a 90° cone, the camera exactly
    // on the floor plane, and a quad whose interpolated normal passes through zero.
    expect_matches_reference(variant(kTestScenes + "/lab2_stress_geometry.json", "stress_geometry", R"({"nan_check": "on"})"),
                             "stress_geometry");
}

// A point light with k = (0, 0, 1) exactly at a corner of the floor, Gouraud-shaded: that vertex is
// lit from d = 0, where this falloff has no finite value. docs/lighting.md, "Numerical safety", asks
// what the falloff must be there; with the NaN check on, an Inf or a NaN at the vertex spreads over
// its triangles and shows as magenta.
TEST(Lab2Stress, PointLightAtAVertexStaysFinite) {
    expect_matches_reference(scene_variant(kLab, kTestScenes + "/lab2_point.json", "stress_light_at_vertex",
                                           [](json& scene) {
                                               scene["lighting"]["nan_check"] = "on";
                                               scene["lighting"]["shading"] = "gouraud";
                                               scene["lights"][1]["position"] = {4, 0, -4};  // the floor's corner
                                               scene["lights"][1]["attenuation"] = {0, 0, 1};
                                           }),
                             "stress_light_at_vertex");
}

class Lab2StressModels : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};
TEST_P(Lab2StressModels, NoNaN) {
    // Every model × shading on the stress scene: not one magenta pixel.
    const auto [model, shading] = GetParam();
    const std::string name = "stress_" + model + "_" + shading;
    const std::string file = variant(kTestScenes + "/lab2_stress_numbers.json", name,
                                     R"({"nan_check": "on", "model": ")" + model + R"(", "shading": ")" + shading + "\"}");
    const std::string png = kLab.render(file, name);
    if (png.empty()) return;
    EXPECT_EQ(ref::magenta_pixels(lab::read_png(png)), 0u) << "NaN/Inf reached a pixel: " << png;
}
INSTANTIATE_TEST_SUITE_P(AllModels, Lab2StressModels,
                         ::testing::Combine(::testing::Values<std::string>("lambert", "phong", "blinn_phong", "toon", "oren_nayar",
                                                              "minnaert", "cook_torrance", "ward"),
                                            ::testing::Values<std::string>("flat", "gouraud", "phong")),
                         [](const auto& info) { return std::get<0>(info.param) + "_" + std::get<1>(info.param); });

TEST(Lab2Stress, DetectorFiresOnInjectedNaN) {
    const std::string file = variant(kTestScenes + "/lab2_stress_numbers.json", "nan_self_test", R"({"nan_check": "self_test"})");
    const std::string png = kLab.render(file, "nan_self_test");
    if (png.empty()) return;
    const lab::Scene scene = lab::load_scene(file);
    const ref::RefImage reference = ref::render_reference(scene, kWidth, kHeight);
    // Every drawn pixel is magenta; silhouette pixels may go either way.
    EXPECT_GT(ref::magenta_pixels(lab::read_png(png)), covered_pixels(reference) * 95 / 100);
}

}  // namespace

namespace {
TEST(Lab2Render, SameRunTwiceIsByteIdentical) {
    expect_same_run_twice_is_byte_identical(kLab, kScenes + "/lab2_lighting.json");  // markers on: the whole default frame
}
}  // namespace
