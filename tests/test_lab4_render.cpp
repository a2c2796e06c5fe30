// test_lab4_render.cpp — the real lab 4 binary, rendering headless, against the ray-traced reference.
//
// Each test writes a small scene (test_output/lab4/NAME.json), runs
//     lab4_shadows --scene FILE --headless --validate --out OUT.png --width 320 --height 180
// (exit 0 = no validation message) and judges the PNG with the shadow error metric
// (docs/testing.md, "The shadow error metric") against ref::render_shadow_reference()
// (tests/reference/cpu_shadow.*: one hard shadow ray per pixel and light, in double). Expected
// pictures never come from the lab itself.
//
// Scenes use flat-faced casters (cubes, icosahedra): a tessellated sphere's terminator is a
// property of its facets that a biased shadow map hides on purpose (test_cpu_shadow covers it).
// The band k is the default kernel's radius plus one texel (docs/testing.md): k = 1 for the default
// 1×1 kernel; the contact test uses the issue's 2 px. Every scene's shadow texels are smaller than
// its pixels.
#include "reference/cpu_shadow.h"
#include "image_io.h"
#include "lab_render.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <string>

namespace {

using json = nlohmann::json;

constexpr int kWidth = 320, kHeight = 180;
const LabUnderTest kLab(LAB4_EXE, "lab4", kWidth, kHeight);  // writes into test_output/lab4/
// k = (N − 1)/2 + 1 for the default N×N kernel (the tests use the default shadow settings).
const int kBand = (lab::ShadowDesc{}.pcf - 1) / 2 + 1;

// --- scenes -------------------------------------------------------------------------------------

json base_scene() {
    return json::parse(R"({
      "camera": {"position": [0, 3.4, 4.4], "target": [0, 0.2, 0], "fov_y_deg": 55, "near": 0.05, "far": 100},
      "background": [0.1, 0.1, 0.12],
      "ambient": {"intensity": 0.1},
      "lighting": {"nan_check": "on"},
      "materials": {"floor": {"albedo": [0.8, 0.8, 0.8]}, "box": {"albedo": [0.8, 0.35, 0.2]},
                    "stone": {"albedo": [0.3, 0.7, 0.4]},
                    "glass": {"albedo": [0.2, 0.4, 0.9], "opacity": 0.4},
                    "amber": {"albedo": [0.9, 0.6, 0.1], "opacity": 0.3},
                    "smoke": {"albedo": [0.5, 0.5, 0.5], "opacity": 0.5}},
      "lights": [], "objects": []})");
}

json floor(double size = 10) { return {{"mesh", "plane"}, {"material", "floor"}, {"scale", {size, 1, size}}}; }

json thing(const std::string& mesh, const std::string& material, std::vector<double> position,
           std::vector<double> scale = {1, 1, 1}, std::vector<double> rotation = {0, 0, 0}) {
    return {{"mesh", mesh}, {"material", material}, {"position", position}, {"scale", scale}, {"rotation_deg", rotation}};
}

json directional(std::vector<double> direction) {
    return {{"type", "directional"}, {"direction", direction}, {"cast_shadows", true}};
}
json spot(std::vector<double> position, std::vector<double> direction, double outer = 35) {
    return {{"type", "spot"}, {"position", position}, {"direction", direction}, {"inner_deg", outer - 10},
            {"outer_deg", outer}, {"cast_shadows", true}};
}
json point(std::vector<double> position) {
    return {{"type", "point"}, {"position", position}, {"cast_shadows", true}};
}

// --- running the lab ----------------------------------------------------------------------------

// Renders `scene` with the lab (exit 0, validation clean, no NaN) and the reference.
struct Judged {
    bool ok = false;
    lab::Image8 actual, shadowed, unshadowed, unlit;
    ref::ShadowReference reference;
    ref::ShadowMetric metric;
};

Judged judge(const std::string& name, const json& scene, int band = kBand) {
    Judged j;
    const std::string file = kLab.write_scene(name, scene.dump(1));
    const std::string png = kLab.render(file, name);
    if (png.empty()) return j;
    j.actual = lab::read_png(png);
    EXPECT_EQ(ref::magenta_pixels(j.actual), 0u) << "NaN/Inf in " << png;
    const lab::Scene s = lab::load_scene(file);
    ref::ShadowMetricOptions options;
    options.band = band;
    j.metric = ref::judge_shadows(s, j.actual, options, &j.reference);
    j.shadowed = ref::encode_srgb(j.reference.shadowed);
    j.unshadowed = ref::encode_srgb(j.reference.unshadowed);
    j.unlit = ref::encode_srgb(j.reference.unlit);
    // For a failure: expected | actual | the metric's picture.
    lab::write_png(kLab.path(name + "_expected.png"), j.shadowed);
    lab::write_png(kLab.path(name + "_metric.png"), ref::shadow_metric_picture(j.shadowed, j.metric));
    j.ok = true;
    return j;
}

std::string describe(const Judged& j, const std::string& name) {
    return j.metric.line() + "\n  see " + kLab.path(name) + "{.png,_expected.png,_metric.png}";
}

// What a look at pixels deep inside one area of the reference found (interior(), below): how many
// were checked and the largest |actual − S| among them.
struct Interior {
    size_t pixels = 0;
    int max_diff = 0;
    std::set<int> levels;  // distinct S values (green channel) seen
};
// Pixels deep inside one area of the reference picture (shadow_interior, flat_interior): `same(i, q)`
// for every pixel q of the (2r+1)² neighbourhood of pixel i, the reference's colour S the same (±1)
// over it, and `shows(x, y)`. The largest |actual − S| there.
Interior interior(const Judged& j, int r, const std::function<bool(size_t, size_t)>& same,
                  const std::function<bool(int, int)>& shows) {
    Interior in;
    const int w = j.shadowed.width, h = j.shadowed.height;
    const auto at = [&](const lab::Image8& im, int x, int y, int ch) { return int(im.rgba[(size_t(y) * w + x) * 4 + ch]); };
    for (int y = r; y < h - r; ++y)
        for (int x = r; x < w - r; ++x) {
            const size_t i = size_t(y) * w + x;
            bool inside = true;
            for (int dy = -r; dy <= r && inside; ++dy)
                for (int dx = -r; dx <= r && inside; ++dx) {
                    inside = same(i, size_t(y + dy) * w + size_t(x + dx));
                    for (int ch = 0; ch < 3 && inside; ++ch)
                        inside = std::abs(at(j.shadowed, x + dx, y + dy, ch) - at(j.shadowed, x, y, ch)) <= 1;
                }
            if (!inside || !shows(x, y)) continue;
            ++in.pixels;
            in.levels.insert(at(j.shadowed, x, y, 1));
            for (int ch = 0; ch < 3; ++ch)
                in.max_diff = std::max(in.max_diff, std::abs(at(j.actual, x, y, ch) - at(j.shadowed, x, y, ch)));
        }
    return in;
}

// The largest of a pixel's three channels of |a − b| (a − b when `signed_difference`).
int channel_difference(const lab::Image8& a, const lab::Image8& b, int x, int y, bool signed_difference = false) {
    int most = 0;
    for (int ch = 0; ch < 3; ++ch) {
        const size_t k = (size_t(y) * size_t(a.width) + size_t(x)) * 4 + size_t(ch);
        const int d = int(a.rgba[k]) - int(b.rgba[k]);
        most = std::max(most, signed_difference ? d : std::abs(d));
    }
    return most;
}

// Inside a shadow of the reference: the opaque surface is `object` (no translucent layer in front),
// the light visibly dimmed there (U − S ≥ 3/255).
Interior shadow_interior(const Judged& j, int object, int r = 4) {
    const std::vector<int>& id = j.reference.shadowed.object_id;
    return interior(j, r, [&](size_t, size_t q) { return id[q] == object; },
                    [&](int x, int y) { return channel_difference(j.unshadowed, j.shadowed, x, y, true) >= 3; });
}

// A scene with long and short shadows of flat-faced casters: a cube, an icosahedron, a thin post.
json casters_scene(const json& light) {
    json s = base_scene();
    s["lights"].push_back(light);
    s["objects"].push_back(floor());
    s["objects"].push_back(thing("cube", "box", {-1.2, 0.5, 0.3}, {1, 1, 1}, {0, 25, 0}));
    s["objects"].push_back(thing("icosahedron", "stone", {1.2, 0.9, -0.6}, {1.2, 1.2, 1.2}));
    s["objects"].push_back(thing("cube", "box", {0.4, 0.9, 1.3}, {0.12, 1.8, 0.12}));
    return s;
}

// --- each light kind against the reference ------------------------------------------------------

void expect_matches_reference(const std::string& name, const json& light) {
    const Judged j = judge(name, casters_scene(light));
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, name));
    EXPECT_GT(j.metric.receivers, 10000u);
    // The reference's picture holds shadows at all (the scene is not vacuous).
    EXPECT_GT(std::count(j.metric.state.begin(), j.metric.state.end(), 2), 500);
    EXPECT_LE(j.metric.wrong_side_share, 0.002);
    EXPECT_LE(j.metric.mae, 2.0);
}

TEST(Lab4Shadows, DirectionalLightMatchesTheReference) {
    expect_matches_reference("directional", directional({-0.6, -1, -0.35}));
}

TEST(Lab4Shadows, SpotLightMatchesTheReference) {
    expect_matches_reference("spot", spot({1.5, 4, 2.5}, {-1.5, -4, -2.5}, 40));
}

TEST(Lab4Shadows, PointLightMatchesTheReference) {
    json light = point({1.5, 2.6, 1.6});
    expect_matches_reference("point", light);
}

// Maps sized to the picture ("fit_to_view", lab 4 README "Maps sized to the picture"): each light
// kind with its map drawn at two texels across each pixel of this 320×180 picture instead of
// 2048² (the run's log says how many it drew: fewer, or the test proves nothing), within the same
// limits as with every texel.
TEST(Lab4Shadows, MapsFittedToThePictureMatchTheReference) {
    const std::vector<std::pair<std::string, json>> lights = {
        {"fit_directional", directional({-0.6, -1, -0.35})},
        {"fit_spot", spot({1.5, 4, 2.5}, {-1.5, -4, -2.5}, 40)},
        {"fit_point", point({1.5, 2.6, 1.6})}};
    for (auto [name, light] : lights) {
        light["shadow"] = {{"fit_to_view", true}};
        expect_matches_reference(name, light);
        // "…: texels per side drawn, of the resolution: light 0: 704 of 2048"
        const std::string log = read_text(kLab.path(name + ".log"));
        const size_t at = log.find("light 0: ");
        ASSERT_NE(at, std::string::npos) << name << ": the run printed no map size";
        const int drawn = std::stoi(log.substr(at + 9));
        EXPECT_GT(drawn, 0) << name;
        EXPECT_LT(drawn, 2048) << name << ": the map was drawn whole";
    }
}

// Casters at the detail the map resolves (lab 4 README; caster_detail.cpp): finely tessellated
// curved casters (a 128 × 64 sphere and torus, a 96-segment cylinder) under each light kind with a
// 512² map, where coarser levels hold and are drawn (the run's log says how many triangles: fewer,
// or the test proves nothing), within the same limits as the hand-made scenes above.
TEST(Lab4Shadows, CastersAtTheMapsDetailMatchTheReference) {
    const std::vector<std::pair<std::string, json>> lights = {
        {"detail_directional", directional({-0.6, -1, -0.35})},
        {"detail_spot", spot({1.5, 4, 2.5}, {-1.5, -4, -2.5}, 40)},
        {"detail_point", point({1.5, 2.6, 1.6})}};
    for (auto [name, light] : lights) {
        light["shadow"] = {{"resolution", 512}};
        json s = base_scene();
        s["lights"].push_back(light);
        s["objects"].push_back(floor());
        json ball = thing("sphere", "stone", {-1.1, 0.7, 0.2}, {1.2, 1.2, 1.2});
        json ring = thing("torus", "box", {1.1, 0.8, -0.4}, {1.8, 1.8, 1.8}, {60, 20, 0});
        json post = thing("cylinder", "box", {0.2, 0.8, 1.2}, {0.3, 1.6, 0.3});
        ball["segments"] = 128, ball["rings"] = 64, ring["segments"] = 128, ring["rings"] = 64, post["segments"] = 96;
        s["objects"].push_back(ball), s["objects"].push_back(ring), s["objects"].push_back(post);
        const Judged j = judge(name, s);
        if (!j.ok) continue;
        SCOPED_TRACE(describe(j, name));
        EXPECT_GT(std::count(j.metric.state.begin(), j.metric.state.end(), 2), 500);
        EXPECT_LE(j.metric.wrong_side_share, 0.002);
        EXPECT_LE(j.metric.mae, 2.0);
        // "…: opaque casters' triangles drawn, of their own: light 0: 6170 of 52.9 k"
        const std::string log = read_text(kLab.path(name + ".log"));
        const size_t at = log.find("of their own: ");
        ASSERT_NE(at, std::string::npos) << name << ": the run printed no triangle count";
        const std::string counts = log.substr(log.find(": ", at + 14) + 2);
        const auto number = [](const std::string& text) {  // "6170" or "52.9 k"
            size_t digits = 0;
            const double n = std::stod(text, &digits);
            return text.compare(digits, 2, " k") == 0 ? 1000.0 * n : n;
        };
        const double drawn = number(counts), own = number(counts.substr(counts.find(" of ") + 4));
        EXPECT_LT(drawn, own) << name << ": every caster drawn at its own detail (" << counts.substr(0, counts.find('\n')) << ")";
    }
}

// The bilinear filter: each PCF tap is one lookup through the comparison sampler (compareEnable,
// a linear filter), which compares the 2×2 texels around the tap and filters the results. Its
// edges are as sharp as the nearest filter's to within a texel (texels here are under a pixel).
// A spot light (its map needs no fitted box) and a directional one, each its own test.
json bilinear(json light) {
    light["shadow"] = {{"filter", "bilinear"}};
    return light;
}
TEST(Lab4Shadows, BilinearComparisonMatchesTheReference) {
    expect_matches_reference("bilinear_spot", bilinear(spot({1.5, 4, 2.5}, {-1.5, -4, -2.5}, 40)));
}
TEST(Lab4Shadows, DirectionalLightBilinearComparison) {
    expect_matches_reference("bilinear_directional", bilinear(directional({-0.6, -1, -0.35})));
}

// --- bias: no acne, no peter-panning -------------------------------------------------------------

TEST(Lab4Shadows, NoAcneOnALitPlaneAt80Degrees) {
    // Only the floor, which casts onto itself; each light 80° from its normal at the centre.
    const double s80 = std::sin(80.0 * M_PI / 180.0), c80 = std::cos(80.0 * M_PI / 180.0);
    const std::vector<std::pair<std::string, json>> lights = {
        {"acne_directional", directional({-s80, -c80, 0})},
        {"acne_spot", spot({-5 * s80, 5 * c80, 0}, {s80, -c80, 0}, 30)},
        {"acne_point", point({-4 * s80, 4 * c80, 0})}};
    for (const auto& [name, light] : lights) {
        json s = base_scene();
        s["lights"].push_back(light);
        s["objects"].push_back(floor(8));
        const Judged j = judge(name, s, 1);
        if (!j.ok) continue;
        SCOPED_TRACE(describe(j, name));
        EXPECT_GT(j.metric.receivers, 5000u);
        EXPECT_EQ(j.metric.wrong_side, 0u);  // acne would darken pixels the reference lights
        EXPECT_LE(j.metric.mae, 2.0);
    }
}

TEST(Lab4Shadows, ContactShadowsStartWithin2PixelsOfTheContactLine) {
    // Cubes standing on the floor: with the default bias the shadow must reach the base (no
    // peter-panning). Every shadow edge within k = 2 px of the reference's.
    json s = base_scene();
    s["lights"].push_back(directional({-1, -1.1, -0.5}));
    s["objects"].push_back(floor());
    s["objects"].push_back(thing("cube", "box", {0, 0.5, 0}, {1, 1, 1}, {0, 20, 0}));
    s["objects"].push_back(thing("cube", "stone", {1.6, 0.25, 1.0}, {0.5, 0.5, 0.5}));
    const Judged j = judge("contact", s, 2);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, "contact"));
    EXPECT_EQ(j.metric.wrong_side, 0u);
}

// --- translucent shadows --------------------------------------------------------------------------

TEST(Lab4Shadows, TranslucentShadowInteriorWithin2Of255) {
    json s = base_scene();
    s["lights"].push_back(directional({-0.3, -1, -0.2}));
    s["objects"].push_back(floor());
    s["objects"].push_back(thing("cube", "glass", {0, 1.2, 0}, {1.6, 0.6, 1.6}));
    const Judged j = judge("translucent", s);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, "translucent"));
    const Interior in = shadow_interior(j, 0);
    EXPECT_GT(in.pixels, 300u) << "no translucent shadow interior to check";
    EXPECT_LE(in.max_diff, 2);
}

TEST(Lab4Shadows, TwoOverlappingTranslucentObjectsMultiply) {
    // Two quads facing the light (α 0.3 and 0.5) overlapping in the middle: three shadow levels,
    // the overlap letting 0.7 · 0.5 through.
    json s = base_scene();
    s["lights"].push_back(directional({0, -1, -0.15}));
    s["objects"].push_back(floor());
    s["objects"].push_back(thing("plane", "amber", {-0.6, 1.0, 0}, {2, 1, 1.6}));
    s["objects"].push_back(thing("plane", "smoke", {0.6, 1.6, 0}, {2, 1, 1.6}));
    const Judged j = judge("overlap", s);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, "overlap"));
    const Interior in = shadow_interior(j, 0);
    EXPECT_GE(in.levels.size(), 3u) << "the three shadow levels (α 0.3, 0.5 and both) must all be in view";
    EXPECT_GT(in.pixels, 300u);
    EXPECT_LE(in.max_diff, 2);
}

// The default casters 300 units from the origin and 14 units to the side of a floor 40 across,
// under a directional light: the light's box sits off the floor's centre, so its y translation
// must flip with the rest of the y row (before: no shadow at all), and a float would lose the
// digits of world → clip out here unless the lookup is relative to the box.
TEST(Lab4Stress, DirectionalLightOverCastersFarFromTheOrigin) {
    json s = casters_scene(directional({-0.6, -1, -0.35}));
    const glm::dvec3 floor_at(300, 40, -120), aside(12, 0, 8);
    const auto move = [](json& v, const glm::dvec3& by) {
        const std::vector<double> p = v.is_null() ? std::vector<double>{0, 0, 0} : v.get<std::vector<double>>();
        v = {p[0] + by.x, p[1] + by.y, p[2] + by.z};
    };
    s["objects"][0]["scale"] = {40, 1, 40};
    s["objects"][0]["cast_shadows"] = false;  // as in the default scene: the box fits the casters alone
    move(s["objects"][0]["position"], floor_at);
    for (size_t i = 1; i < s["objects"].size(); ++i) move(s["objects"][i]["position"], floor_at + aside);
    move(s["camera"]["position"], floor_at + aside);
    move(s["camera"]["target"], floor_at + aside);
    const Judged j = judge("directional_off_centre", s);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, "directional_off_centre"));
    EXPECT_GT(std::count(j.metric.state.begin(), j.metric.state.end(), 2), 500);
    EXPECT_LE(j.metric.wrong_side_share, 0.002);
}

// A point light 2 units above a floor 3000 across, a cube 1 unit under the light: the map's depth
// range is fitted to the cube, not to the floor (before: near ≈ 3, the cube clipped away).
TEST(Lab4Stress, PointLightBesideACasterOverAHugeFloor) {
    json s = base_scene();
    s["lights"].push_back(point({0, 2.0, 0}));
    s["objects"].push_back(floor(3000));
    s["objects"].push_back(thing("cube", "box", {0.3, 0.9, 0.2}, {0.4, 0.4, 0.4}, {0, 30, 0}));
    const Judged j = judge("point_huge_floor", s);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, "point_huge_floor"));
    EXPECT_GT(std::count(j.metric.state.begin(), j.metric.state.end(), 2), 500);
    EXPECT_LE(j.metric.wrong_side_share, 0.002);
}

// A spot light 10⁵ units away (0.1° cone) over a translucent slab (3 × 0.2 × 20) whose top is 2
// units above the floor, lit at 60° from the vertical: its shadow falls 3.5 units aside, beside the
// slab. The test that tells "behind the nearest translucent caster" used to be 1e-4 in
// perspective depth, ≈ 3.4 units here (δ/D times the map's depth slope): the floor 2 units behind
// was not darkened. Now it is 2 texels in world units (~0.3 here).
TEST(Lab4Shadows, TranslucentShadowFromAFarSpot) {
    json s = base_scene();
    s["camera"] = {{"position", {-3, 16, 14}}, {"target", {-3, 0, 0}}, {"fov_y_deg", 50}, {"near", 0.5}, {"far", 1000}};
    const double d = 1e5, sin60 = std::sqrt(0.75);
    const std::vector<double> dir = {-sin60, -0.5, 0.0};  // the way the light travels
    s["lights"].push_back({{"type", "spot"}, {"position", {sin60 * d, 0.5 * d, 0}}, {"direction", dir},
                           {"outer_deg", 0.1}, {"inner_deg", 0.05}, {"cast_shadows", true}});
    s["objects"].push_back(floor(400));
    s["objects"].push_back(thing("cube", "glass", {0, 2.0, 0}, {3, 0.2, 20}));
    const Judged j = judge("translucent_far_spot", s);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, "translucent_far_spot"));
    const Interior in = shadow_interior(j, 0);
    EXPECT_GT(in.pixels, 300u) << "no translucent shadow interior to check";
    EXPECT_LE(in.max_diff, 2);
    EXPECT_LE(j.metric.wrong_side_share, 0.001);
}

// A translucent cube under a mirroring transform (one negative scale: inside out, its far faces
// wind counter-clockwise) beside an unmirrored one: both shadows and both cubes, seen through
// each other's layers, match the reference. The camera pass draws a mirrored object's front
// faces first (they are its far ones); in the other order the cube was darker than the reference.
TEST(Lab4Shadows, MirroredTranslucentCubeMatchesTheReference) {
    json s = base_scene();
    s["lights"].push_back(point({0.5, 3.0, 1.2}));
    s["objects"].push_back(floor());
    s["objects"].push_back(thing("cube", "glass", {-0.7, 0.8, 0.2}, {1.1, -0.9, 1.0}, {20, 35, 10}));
    s["objects"].push_back(thing("cube", "amber", {0.9, 0.7, -0.3}, {0.9, 0.8, 0.9}, {-15, 20, 5}));
    const Judged j = judge("mirrored_translucent", s, 2);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, "mirrored_translucent"));
    // Where a translucent layer shows (ids above the objects' own: the layers mix into them), the
    // picture is the reference's within the render tests' rounding, on average and nearly everywhere.
    size_t layered = 0, off = 0;
    double sum = 0.0;
    for (size_t i = 0; i < j.reference.shadowed.object_id.size(); ++i) {
        if (j.reference.shadowed.object_id[i] <= 3) continue;
        ++layered;
        int diff = 0;
        for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(int(j.actual.rgba[4 * i + c]) - int(j.shadowed.rgba[4 * i + c])));
        sum += diff;
        off += diff > 4;
    }
    EXPECT_GT(layered, 2000u);
    EXPECT_LE(sum / double(std::max<size_t>(layered, 1)), 1.0) << "mean difference where the cubes show";
    EXPECT_LE(off, layered / 100) << "pixels of the cubes more than 4/255 off";
    EXPECT_LE(j.metric.wrong_side_share, 0.001);
    EXPECT_LE(j.metric.mae, 1.0);
}

// A 178° spot cone (outer 89°, near the format's 90° limit) with casters near the edge of its
// cone: it gets a cube map (one perspective map would stop at 170°) and every shadow is there.
TEST(Lab4Shadows, SpotConeOf178Degrees) {
    json s = base_scene();
    s["lights"].push_back(spot({0, 1.2, 0}, {0, -1, 0}, 89));
    s["objects"].push_back(floor(30));
    s["objects"].push_back(thing("cube", "box", {2.6, 0.6, 0.3}, {0.4, 0.4, 0.4}));      // 65° off the axis
    s["objects"].push_back(thing("cube", "stone", {-0.4, 1.0, -2.4}, {0.3, 0.3, 0.3}));  // 85° off the axis
    const Judged j = judge("spot_178", s, 2);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, "spot_178"));
    EXPECT_GT(std::count(j.metric.state.begin(), j.metric.state.end(), 2), 300);
    EXPECT_LE(j.metric.wrong_side_share, 0.001);
}

// --- translucent layers ---------------------------------------------------------------------------
// Several translucent objects over each other, on screen and in a light's view: the camera pass must
// blend every layer in depth order per pixel, whatever the order of the objects list (objects that
// intersect or nest have no order of their own), and the light reaching a point is Π(1 − α) over the
// translucent faces between it and the light (never its own face, never a layer behind it). The
// expected values are the reference's (cpu_shadow.h); the classifications below (which layer a pixel
// shows first, what light reaches it) are the reference's geometry too.

// Materials with colours far apart, so that blending two layers in the wrong order shows.
json layered_scene() {
    json s = base_scene();
    s["materials"]["ruby"] = {{"albedo", {0.85, 0.1, 0.15}}, {"opacity", 0.55}};
    s["materials"]["jade"] = {{"albedo", {0.1, 0.75, 0.3}}, {"opacity", 0.5}};
    s["materials"]["sky"] = {{"albedo", {0.2, 0.4, 0.95}}, {"opacity", 0.45}};
    return s;
}

// What the reference's primary ray through pixel i crosses, as render_shadowed sees it: the
// translucent layers (near to far) in front of the nearest opaque front face, and that face.
struct Surface {
    int object = -1;
    bool front = true;  // crossed from its front side (the side the camera sees)
    glm::dvec3 position{0.0}, normal{0.0};
};
struct PixelLayers {
    std::vector<Surface> layers;
    Surface base;  // object −1: the background
};
std::vector<PixelLayers> pixel_layers(const lab::Scene& scene, int width, int height) {
    const ref::SceneGeometry geometry(scene);
    const ref::Camera camera = ref::make_camera(scene.camera);
    std::vector<double> opacity;
    for (const lab::ObjectDesc& o : scene.objects) {
        const auto it = scene.materials.find(o.material);
        opacity.push_back(it == scene.materials.end() ? 1.0 : double(it->second.opacity));
    }
    std::vector<PixelLayers> out(size_t(width) * size_t(height));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const ref::Ray ray = ref::primary_ray(camera, width, height, x + 0.5, y + 0.5);
            std::vector<ref::CrossedTriangle> crossed;
            geometry.for_each_hit(ray, camera.near_plane, camera.far_plane, [&](const ref::CrossedTriangle& c) {
                crossed.push_back(c);
                return true;
            });
            std::sort(crossed.begin(), crossed.end(), [](const auto& a, const auto& b) { return a.t < b.t; });
            PixelLayers& p = out[size_t(y) * size_t(width) + size_t(x)];
            for (const ref::CrossedTriangle& c : crossed) {
                const ref::Hit h = geometry.hit_of(c);
                const Surface s{c.object_id, c.front, h.position, h.geometric_normal};
                if (opacity[size_t(c.object_id)] < 1.0) {
                    if (p.layers.empty() || p.layers.back().object != s.object || p.layers.back().front != s.front ||
                        glm::length(p.layers.back().position - s.position) > 1e-9 * (1.0 + glm::length(s.position)))
                        p.layers.push_back(s);
                } else if (c.front) {
                    p.base = s;
                    break;
                }
            }
        }
    return out;
}

// Inside one area where `mask` is set: the same surfaces over the neighbourhood (object_id, which
// also encodes the translucent layers in front) and a light that shows (|U − Z| ≥ 3/255).
Interior flat_interior(const Judged& j, const std::vector<uint8_t>& mask, int r = 4) {
    const std::vector<int>& id = j.reference.shadowed.object_id;
    return interior(j, r, [&](size_t i, size_t q) { return mask[i] && mask[q] && id[q] == id[i]; },
                    [&](int x, int y) { return channel_difference(j.unshadowed, j.unlit, x, y) >= 3; });
}

// The camera pass where translucent layers show, against the reference, with the edge mask left out
// (ref::edge_mask: a 3×3 neighbourhood whose reference ids differ — object and layer boundaries): the
// per-pixel difference (largest channel, 1/255) on average and how many pixels are more than 4/255
// off, over the pixels showing `fewest` … `most` different translucent objects.
struct LayeredDiff {
    size_t pixels = 0, off = 0;
    double mean = 0.0;
    int max_diff = 0;
    std::string line() const {
        return "pixels=" + std::to_string(pixels) + " mean=" + std::to_string(mean) + " max=" + std::to_string(max_diff) +
               " over_4=" + std::to_string(off);
    }
};
LayeredDiff layered_diff(const Judged& j, int fewest, int most) {
    const std::vector<uint8_t> edges = ref::edge_mask(j.reference.shadowed);
    LayeredDiff d;
    double sum = 0.0;
    for (size_t i = 0; i < edges.size(); ++i) {
        const int objects = j.reference.shadowed.translucent_objects[i];
        if (edges[i] || objects < fewest || objects > most) continue;
        int diff = 0;
        for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(int(j.actual.rgba[4 * i + c]) - int(j.shadowed.rgba[4 * i + c])));
        ++d.pixels;
        sum += diff;
        d.off += diff > 4;
        d.max_diff = std::max(d.max_diff, diff);
    }
    d.mean = sum / double(std::max<size_t>(d.pixels, 1));
    return d;
}

// Renders `objects` (translucent ones, over a floor) in the order given and compares the camera
// pass where they show with the reference: within the render tests' rounding (the thresholds of
// MirroredTranslucentCubeMatchesTheReference) where one object shows and where two or more do
// (at least `min_overlap` such pixels). The lights cast no shadow: this is the blending order alone.
void expect_layers_match(const std::string& name, const std::vector<json>& objects, size_t min_overlap) {
    json s = layered_scene();
    s["camera"] = {{"position", {0.3, 2.3, 2.9}}, {"target", {0, 0.85, 0}}, {"fov_y_deg", 55}, {"near", 0.05}, {"far", 100}};
    s["lights"].push_back({{"type", "directional"}, {"direction", {-0.4, -1, -0.5}}, {"intensity", 0.7}, {"cast_shadows", false}});
    s["lights"].push_back({{"type", "point"}, {"position", {1.5, 2.5, 2.0}}, {"intensity", 0.4}, {"cast_shadows", false}});
    s["objects"].push_back(floor());
    for (const json& o : objects) s["objects"].push_back(o);
    const Judged j = judge(name, s);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, name));
    const LayeredDiff one = layered_diff(j, 1, 1), two = layered_diff(j, 2, 255);
    SCOPED_TRACE("where a translucent object shows: " + one.line() + "; where two or more overlap: " + two.line());
    EXPECT_GT(two.pixels, min_overlap) << "the translucent objects must overlap on screen";
    EXPECT_LE(one.mean, 1.0) << "mean difference where translucent objects show";
    EXPECT_LE(one.off, one.pixels / 100) << "pixels more than 4/255 off where translucent objects show";
    EXPECT_LE(two.mean, 1.0) << "mean difference where two or more translucent objects overlap";
    EXPECT_LE(two.off, two.pixels / 100) << "pixels more than 4/255 off where two or more translucent objects overlap";
}

// Two translucent cubes that cut into each other: where they intersect, a ray crosses A's front
// face, B's front face, A's back face, B's back face — no order of whole objects gives that.
TEST(Lab4Translucency, TwoIntersectingTranslucentCubesInEitherOrder) {
    const json a = thing("cube", "ruby", {-0.35, 0.9, 0.1}, {1.2, 1.2, 1.2}, {10, 30, 0});
    const json b = thing("cube", "jade", {0.35, 0.8, -0.2}, {1.1, 1.1, 1.1}, {0, -25, 15});
    {
        SCOPED_TRACE("ruby first");
        expect_layers_match("layers_two_cubes_ab", {a, b}, 1000);
    }
    SCOPED_TRACE("jade first");
    expect_layers_match("layers_two_cubes_ba", {b, a}, 1000);
}

// A translucent icosahedron inside a bigger translucent cube, the same centre: the cube's back,
// the icosahedron (back, front), the cube's front. Whole objects sorted by centre tie here.
TEST(Lab4Translucency, TranslucentIcosahedronInsideATranslucentCubeInEitherOrder) {
    const json cube = thing("cube", "sky", {0, 0.95, 0}, {1.8, 1.8, 1.8}, {0, 20, 0});
    const json ico = thing("icosahedron", "ruby", {0, 0.95, 0}, {1.1, 1.1, 1.1}, {15, 10, 0});
    {
        SCOPED_TRACE("cube first");
        expect_layers_match("layers_nested_cube_ico", {cube, ico}, 1000);
    }
    SCOPED_TRACE("icosahedron first");
    expect_layers_match("layers_nested_ico_cube", {ico, cube}, 1000);
}

// Three translucent objects over each other — two intersecting cubes and a tilted quad through
// both — in all six orders of the objects list: the same, correct picture every time.
TEST(Lab4Translucency, ThreeOverlappingTranslucentObjectsInAllSixOrders) {
    const std::vector<json> objects = {thing("cube", "ruby", {-0.45, 0.85, 0.1}, {1.1, 1.1, 1.1}, {10, 30, 0}),
                                       thing("icosahedron", "jade", {0.4, 0.9, -0.1}, {1.3, 1.3, 1.3}, {0, 15, 20}),
                                       thing("plane", "sky", {0, 0.9, 0.1}, {2.8, 1, 1.6}, {70, 0, 10})};
    std::vector<int> order = {0, 1, 2};
    do {
        std::string name = "layers_three";
        std::vector<json> list;
        for (const int k : order) {
            name += "_" + std::to_string(k);
            list.push_back(objects[size_t(k)]);
        }
        SCOPED_TRACE("objects in the order " + name.substr(13));
        expect_layers_match(name, list, 3000);
    } while (std::next_permutation(order.begin(), order.end()));
}

// Translucent receivers and casters stacked under one light, for each light type. `stack`: the
// objects over the floor (object 0), from the light down; `areas`: what to check, each a set of
// pixels chosen on the reference's geometry.
struct Area {
    std::string what;
    std::function<bool(const PixelLayers&, const ref::ShadowCasters&, const lab::LightDesc&)> holds;
};
bool near_value(double a, double b) { return std::abs(a - b) <= 1e-6; }

// The lights of the stacks, each with its light travelling towards +x and down, so that a slab's
// shadow falls beside it (on the next slab down, on the floor), where the camera (on the +z side)
// sees it directly.
std::vector<std::pair<std::string, json>> stack_lights(const std::string& prefix) {
    return {{prefix + "_directional", directional({0.6, -1, 0.05})},
            {prefix + "_spot", spot({-2.2, 4.4, 0.3}, {2.5, -4.4, -0.2}, 50)},
            {prefix + "_point", point({-2.4, 4.2, 0.0})}};
}

void expect_stack_matches(const std::string& name, const json& light, const std::vector<json>& stack,
                          const std::vector<Area>& areas) {
    json s = layered_scene();
    s["camera"] = {{"position", {0.4, 3.1, 3.0}}, {"target", {0.3, 0.9, 0.0}}, {"fov_y_deg", 55}, {"near", 0.05}, {"far", 100}};
    s["lights"].push_back(light);
    s["objects"].push_back(floor());
    for (const json& o : stack) s["objects"].push_back(o);
    const Judged j = judge(name, s);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, name));
    const lab::Scene scene = lab::load_scene(kLab.path(name + ".json"));
    const ref::ShadowCasters casters(scene);
    const std::vector<PixelLayers> layers = pixel_layers(scene, kWidth, kHeight);
    for (const Area& area : areas) {
        std::vector<uint8_t> mask(layers.size(), 0);
        for (size_t i = 0; i < layers.size(); ++i) mask[i] = area.holds(layers[i], casters, scene.lights[0]);
        const Interior in = flat_interior(j, mask);
        SCOPED_TRACE(area.what + ": " + std::to_string(std::count(mask.begin(), mask.end(), 1)) + " pixels, " +
                     std::to_string(in.pixels) + " inside, largest difference " + std::to_string(in.max_diff));
        EXPECT_GT(in.pixels, 300u) << "too little of it in view to check";
        EXPECT_LE(in.max_diff, 2);
    }
    EXPECT_LE(j.metric.wrong_side_share, 0.002);
}

// The light reaching a surface (the reference's shadow ray from it).
double light_at(const ref::ShadowCasters& casters, const lab::LightDesc& light, const Surface& s) {
    return casters.transmittance(light, s.position, s.normal);
}
bool first_layer_is(const PixelLayers& p, int object) {
    return !p.layers.empty() && p.layers[0].object == object && p.layers[0].front;
}
bool floor_seen_directly(const PixelLayers& p) { return p.layers.empty() && p.base.object == 0; }

// A translucent slab (upper, ruby α 0.55) beside and above a bigger one (lower, jade α 0.5) over the
// floor: the lower slab's lit face gets 1 − 0.55 where the upper one shadows it (not 0.45 · 0.5: its
// own face never counts), the floor under both 0.45 · 0.5, under the lower one alone 0.5.
TEST(Lab4Translucency, TranslucentReceiverUnderATranslucentCaster) {
    const double upper = 1 - 0.55, lower = 1 - 0.5;
    const std::vector<json> stack = {thing("cube", "ruby", {-1.0, 2.0, 0.0}, {1.2, 0.06, 1.6}),
                                     thing("cube", "jade", {0.6, 1.0, 0.0}, {2.0, 0.06, 2.0})};
    const std::vector<Area> areas = {
        {"the lower slab's lit face in the upper one's shadow",
         [&](const PixelLayers& p, const ref::ShadowCasters& c, const lab::LightDesc& l) {
             return first_layer_is(p, 2) && near_value(light_at(c, l, p.layers[0]), upper);
         }},
        {"the lower slab's lit face in full light",
         [&](const PixelLayers& p, const ref::ShadowCasters& c, const lab::LightDesc& l) {
             return first_layer_is(p, 2) && near_value(light_at(c, l, p.layers[0]), 1.0);
         }},
        {"the floor under both slabs, seen directly",
         [&](const PixelLayers& p, const ref::ShadowCasters& c, const lab::LightDesc& l) {
             return floor_seen_directly(p) && near_value(light_at(c, l, p.base), upper * lower);
         }},
        {"the floor under the lower slab alone, seen directly",
         [&](const PixelLayers& p, const ref::ShadowCasters& c, const lab::LightDesc& l) {
             return floor_seen_directly(p) && near_value(light_at(c, l, p.base), lower);
         }}};
    for (const auto& [name, light] : stack_lights("stack_translucent")) {
        SCOPED_TRACE(name);
        expect_stack_matches(name, light, stack, areas);
    }
}

// An opaque plate between two translucent slabs (ruby above, jade below): the plate's lit face gets
// 1 − 0.55 where the ruby slab shadows it — the jade slab lies behind it and must not count.
TEST(Lab4Translucency, ReceiverBetweenTwoTranslucentCasters) {
    const double upper = 1 - 0.55;
    const std::vector<json> stack = {thing("cube", "ruby", {-1.0, 2.2, 0.0}, {1.2, 0.06, 1.6}),
                                     thing("cube", "box", {0.25, 1.5, 0.1}, {1.7, 0.06, 1.3}, {0, 15, 0}),
                                     thing("cube", "jade", {0.8, 0.7, 0.0}, {2.4, 0.06, 2.0})};
    const std::vector<Area> areas = {
        {"the plate's lit face in the upper slab's shadow",
         [&](const PixelLayers& p, const ref::ShadowCasters& c, const lab::LightDesc& l) {
             return p.layers.empty() && p.base.object == 2 && near_value(light_at(c, l, p.base), upper);
         }},
        {"the plate's lit face in full light",
         [&](const PixelLayers& p, const ref::ShadowCasters& c, const lab::LightDesc& l) {
             return p.layers.empty() && p.base.object == 2 && near_value(light_at(c, l, p.base), 1.0);
         }}};
    for (const auto& [name, light] : stack_lights("stack_between")) {
        SCOPED_TRACE(name);
        expect_stack_matches(name, light, stack, areas);
    }
}

// A translucent cube's own lit faces, with no normal offset (the lookup at P itself): the face
// P lies on is the nearest layer of P's texel, stored at the texel's centre, up to tan θ · √2/2
// texels (θ: the face's angle to the light) nearer than P in depth. The lookup must tell that it
// is P's own face (less than 2 texels in front, translucent_shadows.glsl), or about half the
// face's pixels get its own 1 − α (acne in the layer). Light along (0.8, −1, −0.7): the lit
// faces stand at 47°, 57° and 61° to it, at most 1.3 texels of that. The reference lights them
// fully (its own face never counts).
TEST(Lab4Translucency, TranslucentCubesLitFacesDoNotShadowThemselves) {
    const std::vector<json> stack = {thing("cube", "ruby", {0.3, 0.9, 0.0}, {1.0, 1.0, 1.0})};
    const std::vector<Area> areas = {
        {"the cube's lit faces, seen first",
         [&](const PixelLayers& p, const ref::ShadowCasters& c, const lab::LightDesc& l) {
             return first_layer_is(p, 1) && near_value(light_at(c, l, p.layers[0]), 1.0);
         }}};
    const glm::dvec3 d(0.8, -1, -0.7), at(0.3, 0.9, 0.0), from = at - 3.0 * d;
    const json no_offset = {{"normal_offset", 0}};
    json sun = directional({d.x, d.y, d.z}), lamp = spot({from.x, from.y, from.z}, {d.x, d.y, d.z}, 40);
    sun["shadow"] = no_offset;
    lamp["shadow"] = no_offset;
    for (const auto& [name, light] : std::vector<std::pair<std::string, json>>{{"own_face_directional", sun},
                                                                               {"own_face_spot", lamp}}) {
        SCOPED_TRACE(name);
        expect_stack_matches(name, light, stack, areas);
    }
}

// --- the limits of the layers and of the peel --------------------------------------------------------
// Each limit reached on purpose, its documented behaviour (lab4_shadows/translucent_layers.h,
// translucent_shadows.h) asserted from the reference or by hand, and the headless warning's counts.

// "translucent layers: up to 16 per pixel exact; N px over 16, M fragments dropped (pool full)"
// from the run's log: N and M (−1, −1: no such line).
std::pair<long, long> layer_counts(const std::string& log) {
    const std::string over = " px over ", dropped = " fragments dropped (pool full)";
    const size_t o = log.find(over), d = log.find(dropped);
    if (o == std::string::npos || d == std::string::npos) return {-1, -1};
    const size_t n = log.rfind(' ', o - 1) + 1, m = log.rfind(' ', d - 1) + 1;
    return {std::stol(log.substr(n, o - n)), std::stol(log.substr(m, d - m))};
}

// Panes facing the camera (+z) at z = 0, −0.05, …, one `material` each, in front of a lit opaque
// backdrop at z = −2; the camera on the z axis, the light from behind it (no shadows).
json panes_scene(const std::vector<std::string>& materials, double size) {
    json s = layered_scene();
    s["materials"]["black_glass"] = {{"albedo", {0, 0, 0}}, {"opacity", 0.1}};
    s["camera"] = {{"position", {0, 0, 4}}, {"target", {0, 0, 0}}, {"fov_y_deg", 55}, {"near", 0.05}, {"far", 100}};
    s["lights"].push_back({{"type", "directional"}, {"direction", {0, 0, -1}}, {"cast_shadows", false}});
    s["objects"].push_back(thing("plane", "floor", {0, 0, -2}, {40, 1, 40}, {90, 0, 0}));
    for (size_t i = 0; i < materials.size(); ++i)
        s["objects"].push_back(thing("plane", materials[i], {0, 0, -0.05 * double(i)}, {size, 1, size}, {90, 0, 0}));
    return s;
}

// Pixels whose 3×3 neighbourhood in the reference crosses the same number of translucent layers
// (the frame's border left out): away from the panes' edges, where a pixel centre is not near a
// triangle edge and the rasterizer and the reference's ray agree.
std::vector<uint8_t> same_layer_count(const std::vector<PixelLayers>& layers, int w, int h) {
    std::vector<uint8_t> inside(layers.size(), 0);
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            bool same = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    same = same && layers[size_t(y + dy) * w + size_t(x + dx)].layers.size() == layers[size_t(y) * w + size_t(x)].layers.size();
            inside[size_t(y) * w + size_t(x)] = same;
        }
    return inside;
}

// 20 black panes (α 0.1) behind a ruby one and a sky one: 22 layers where they all overlap, more
// than K = 16. The resolve composes the 16 nearest and keeps the 6 farther ones' (1 − α): the
// backdrop is dimmed by all 22, as in the reference (before: by 16 alone, 0.9⁶ = 0.53 too little
// dimming). The dropped layers are black, so their colour (the part the resolve drops) is 0 in the
// reference too: the picture must be the reference's within the render tests' 2/255. The warning
// counts the pixels over 16 (the reference's count, give or take the pixels at the panes' edges).
TEST(Lab4Translucency, MoreThan16LayersKeepTheFartherOnesTransmittance) {
    std::vector<std::string> materials = {"ruby", "sky"};
    materials.resize(22, "black_glass");
    const json s = panes_scene(materials, 1.2);
    const std::string name = "limit_22_layers";
    const Judged j = judge(name, s);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, name));
    const lab::Scene scene = lab::load_scene(kLab.path(name + ".json"));
    const std::vector<PixelLayers> layers = pixel_layers(scene, kWidth, kHeight);
    const std::vector<uint8_t> inside = same_layer_count(layers, kWidth, kHeight);
    size_t over = 0, over_inside = 0, checked = 0;
    int most = 0;
    for (size_t i = 0; i < layers.size(); ++i) {
        if (layers[i].layers.size() <= 16) continue;
        ++over;
        if (!inside[i]) continue;
        ++over_inside;
        EXPECT_EQ(layers[i].layers.size(), 22u);
        ++checked;
        most = std::max(most, channel_difference(j.actual, j.shadowed, int(i % kWidth), int(i / kWidth)));
    }
    const std::string figures = std::to_string(checked) + " pixels behind 22 layers checked, largest difference " +
                                std::to_string(most) + "; " + std::to_string(over) + " over 16 in the reference";
    std::printf("[ limit ] %s\n", figures.c_str());
    SCOPED_TRACE(figures);
    EXPECT_GT(checked, 1000u) << "too little of the stack in view";
    EXPECT_LE(most, 2);
    const auto [n, m] = layer_counts(read_text(kLab.path(name + ".log")));
    std::printf("[ limit ] warning: %ld px over 16, %ld fragments dropped\n", n, m);
    EXPECT_GE(n, long(over_inside)) << "pixels over 16 in the warning";
    EXPECT_LE(n, long(over + (over - over_inside))) << "pixels over 16 in the warning";
    EXPECT_EQ(m, 0) << "fragments dropped: 22 layers over a 1.2-unit square fill " << over << " of 57600 pixels";
}

// Six panes (α 0.3 … 0.55, coloured) over the whole frame: 6 · 57600 fragments for a pool of
// 4 · 57600 nodes, so 115200 are not stored (the hand count: every pixel crosses all six). Which
// ones depends on the GPU's order; the documented behaviour: a pixel that lost one shows only its
// layers' whole transmittance, T · backdrop — the reference of the same scene with the panes black
// — and every other pixel the exact composition, the reference. Every pixel must be one of the two
// (2/255), at least 115200 / 6 = 19200 the first (a pixel loses at most its six), and the warning
// counts 115200 dropped fragments, no pixel over 16.
TEST(Lab4Translucency, AFullPoolKeepsEveryLayersOpacity) {
    const std::vector<std::string> materials = {"ruby", "jade", "sky", "ruby", "jade", "sky"};
    const json s = panes_scene(materials, 60);
    json black = s;
    for (const char* m : {"ruby", "jade", "sky"}) black["materials"][m]["albedo"] = {0, 0, 0};
    const std::string name = "limit_pool_full";
    const RenderResult r = kLab.run(kLab.write_scene(name, s.dump(1)), name);
    ASSERT_TRUE(r.ok()) << r.failure();
    const lab::Image8 actual = lab::read_png(r.png);
    const lab::Image8 exact = ref::encode_srgb(ref::render_shadowed(lab::load_scene(r.scene), kWidth, kHeight));
    const lab::Image8 opacity_only = ref::encode_srgb(
        ref::render_shadowed(lab::load_scene(kLab.write_scene(name + "_black", black.dump(1))), kWidth, kHeight));
    size_t as_exact = 0, as_lost = 0, neither = 0;
    int apart = 255;  // the two references' smallest difference: the test must tell them apart
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            apart = std::min(apart, channel_difference(exact, opacity_only, x, y));
            if (channel_difference(actual, exact, x, y) <= 2) ++as_exact;
            else if (channel_difference(actual, opacity_only, x, y) <= 2) ++as_lost;
            else ++neither;
        }
    const std::string figures = "exact " + std::to_string(as_exact) + ", opacity only " + std::to_string(as_lost) +
                                ", neither " + std::to_string(neither) + "; the references at least " +
                                std::to_string(apart) + "/255 apart";
    std::printf("[ limit ] %s\n", figures.c_str());
    SCOPED_TRACE(figures);
    EXPECT_GE(apart, 5);
    EXPECT_EQ(neither, 0u);
    EXPECT_GE(as_lost, 19200u);
    const auto [n, m] = layer_counts(r.log);
    std::printf("[ limit ] warning: %ld px over 16, %ld fragments dropped\n", n, m);
    EXPECT_EQ(n, 0);
    EXPECT_EQ(m, 115200);
}

// Five translucent slabs between a light and the floor, the light's transmittance map of K = 4
// layers: layers 0–2 hold the first three faces, the last one the product of the fourth and fifth
// at the fourth's depth. An opaque plate between the fourth and fifth slab is "a receiver among the
// far faces": documented, it gets the product of all five, (0.7)⁴ · 0.5 = 0.12, where the
// reference (behind four) gets (0.7)⁴ = 0.24 — too little light, never too much. Expected: the
// reference's unlit + 0.12 · (unshadowed − unlit) on the plate, in linear colour.
TEST(Lab4Translucency, PastFourPeelLayersAReceiverAmongTheFarFacesGetsTheirProduct) {
    json s = layered_scene();
    s["materials"]["clear"] = {{"albedo", {0.7, 0.7, 0.75}}, {"opacity", 0.3}};
    s["camera"] = {{"position", {3.6, 2.7, 0.5}}, {"target", {0, 1.2, 0}}, {"fov_y_deg", 55}, {"near", 0.05}, {"far", 100}};
    s["lights"].push_back(directional({0.5, -1, 0}));
    s["objects"].push_back(floor());
    for (const double h : {3.0, 2.65, 2.3, 1.95})  // over the plate along the light: x = −0.5 (h − 1.4)
        s["objects"].push_back(thing("cube", "clear", {-0.5 * (h - 1.4), h, 0}, {1.6, 0.06, 2.0}));
    s["objects"].push_back(thing("cube", "box", {0, 1.4, 0}, {1.4, 0.06, 1.6}));    // the plate, object 5
    s["objects"].push_back(thing("cube", "jade", {0.2, 1.0, 0}, {2.4, 0.06, 2.4}));  // the fifth slab, α 0.5
    const std::string name = "limit_peel_layers";
    const Judged j = judge(name, s);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, name));
    const lab::Scene scene = lab::load_scene(kLab.path(name + ".json"));
    const ref::ShadowCasters casters(scene);
    const std::vector<PixelLayers> layers = pixel_layers(scene, kWidth, kHeight);
    const double four = std::pow(0.7, 4), documented = four * 0.5;
    std::vector<uint8_t> mask(layers.size(), 0);
    for (size_t i = 0; i < layers.size(); ++i)
        mask[i] = layers[i].layers.empty() && layers[i].base.object == 5 &&
                  near_value(light_at(casters, scene.lights[0], layers[i].base), four);
    ref::RefImage expected = j.reference.unshadowed;
    for (size_t i = 0; i < expected.linear.size(); ++i)
        expected.linear[i] = j.reference.unlit.linear[i] + documented * (j.reference.unshadowed.linear[i] - j.reference.unlit.linear[i]);
    const lab::Image8 expected8 = ref::encode_srgb(expected);
    size_t pixels = 0;
    int most = 0, least_apart = 255;
    for (int y = 4; y < kHeight - 4; ++y)
        for (int x = 4; x < kWidth - 4; ++x) {
            bool inside = true;  // the whole 9×9 neighbourhood in the area: no shadow edge near
            for (int dy = -4; dy <= 4 && inside; ++dy)
                for (int dx = -4; dx <= 4 && inside; ++dx) inside = mask[size_t(y + dy) * kWidth + size_t(x + dx)];
            if (!inside) continue;
            ++pixels;
            most = std::max(most, channel_difference(j.actual, expected8, x, y));
            least_apart = std::min(least_apart, channel_difference(j.shadowed, expected8, x, y));
        }
    const std::string figures = std::to_string(pixels) + " plate pixels behind four slabs, largest difference " +
                                std::to_string(most) + ", the reference at least " + std::to_string(least_apart) + "/255 brighter";
    std::printf("[ limit ] %s\n", figures.c_str());
    SCOPED_TRACE(figures);
    EXPECT_GT(pixels, 300u) << "too little of the plate in view";
    EXPECT_GE(least_apart, 5) << "the documented and the exact light must differ visibly";
    EXPECT_LE(most, 2);
}

// --- coverage -------------------------------------------------------------------------------------

TEST(Lab4Shadows, CasterBehindTheLightCastsNothing) {
    // An opaque plate above each light: the floor below is fully lit.
    const std::vector<std::pair<std::string, json>> lights = {
        {"behind_spot", spot({0, 2, 0}, {0, -1, 0}, 60)}, {"behind_point", point({0, 2, 0})}};
    for (const auto& [name, light] : lights) {
        json s = base_scene();
        s["lights"].push_back(light);
        s["objects"].push_back(floor());
        s["objects"].push_back(thing("plane", "box", {0, 3, 0}, {6, 1, 6}));
        const Judged j = judge(name, s, 1);
        if (!j.ok) continue;
        SCOPED_TRACE(describe(j, name));
        EXPECT_GT(j.metric.receivers, 5000u);
        EXPECT_EQ(j.metric.wrong_side, 0u);
        EXPECT_LE(j.metric.mae, 2.0);
    }
}

TEST(Lab4Shadows, ReceiverOutsideTheShadowMapsCoverageIsLit) {
    // A 60 m floor that casts nothing and one small caster: a map fitted to the casters does not
    // reach most of the floor, which must come out lit (not black), and the cube's shadow right.
    // Bilinear, so the gathers at the map's edge read the comparison sampler's border (a band
    // half a texel wide here: ReceiverAtTheShadowMapsEdgeIsLit is the test of that border).
    json s = base_scene();
    s["camera"] = {{"position", {0, 2.5, 9}}, {"target", {0, 0, -6}}, {"fov_y_deg", 60}, {"near", 0.05}, {"far", 200}};
    s["lights"].push_back(bilinear(directional({-0.5, -1, -0.4})));
    json big_floor = floor(60);
    big_floor["cast_shadows"] = false;
    s["objects"].push_back(big_floor);
    s["objects"].push_back(thing("cube", "box", {0, 0.5, 2}));
    const Judged j = judge("coverage", s);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, "coverage"));
    EXPECT_GT(j.metric.receivers, 20000u);
    EXPECT_LE(j.metric.wrong_side_share, 0.002);
    EXPECT_LE(j.metric.mae, 2.0);
}

// Receivers just inside the map's edge: a bilinear 3×3 PCF footprint reaches 2 texels past P's
// texel, so within 1.5 texels of the edge some of its comparisons fall outside the map and read
// the comparison sampler's border colour (its depth: R), compared like a stored depth; the lookup
// returns 1 only for P outside the map. Three posts far apart, a floor that casts nothing: the map
// fitted to the posts ends on lit floor, away from their shadows; 128 texels across the ~5-unit
// box, a texel 1–3 pixels on the floor, so that strip is pixels wide. The reference lights that
// floor fully; deep in the light (no shadow edge of the reference within 6 px, the band: more than
// the 2-texel blur) the picture must be the reference's. The posts' shadows must be there too.
TEST(Lab4Shadows, ReceiverAtTheShadowMapsEdgeIsLit) {
    json s = base_scene();
    json light = bilinear(directional({-0.9, -1, 0.3}));
    light["intensity"] = 0.7;  // the lit floor well under white: a darkened pixel shows
    light["shadow"]["pcf"] = 3;
    light["shadow"]["resolution"] = 128;
    s["lights"].push_back(light);
    json lit_floor = floor();
    lit_floor["cast_shadows"] = false;
    s["objects"].push_back(lit_floor);
    s["objects"].push_back(thing("cube", "box", {-2.0, 0.7, -1.5}, {0.7, 1.4, 0.7}, {0, 30, 0}));
    s["objects"].push_back(thing("cube", "stone", {2.0, 0.7, -1.0}, {0.7, 1.4, 0.7}, {0, 10, 0}));
    s["objects"].push_back(thing("cube", "box", {0.0, 0.7, 1.4}, {0.7, 1.4, 0.7}, {0, 50, 0}));
    const Judged j = judge("map_edge", s, 6);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, "map_edge"));
    // The cubes' shadows, outside the band (wrong_side_share, below, judges them).
    size_t shadow = 0;
    for (size_t i = 0; i < j.metric.state.size(); ++i) shadow += j.metric.state[i] == 2 && !j.metric.band[i];
    EXPECT_GT(shadow, 500u) << "too little of the cubes' shadows outside the band";
    const std::vector<int>& id = j.reference.shadowed.object_id;
    // The floor, fully lit in the reference (S = U) and its light showing (U − Z ≥ 3/255).
    const auto fully_lit = [&](size_t i) {
        const int x = int(i % size_t(kWidth)), y = int(i / size_t(kWidth));
        return id[i] == 0 && channel_difference(j.unshadowed, j.shadowed, x, y) == 0;
    };
    const Interior in = interior(j, 6, [&](size_t i, size_t q) { return fully_lit(i) && fully_lit(q); },
                                 [&](int x, int y) { return channel_difference(j.unshadowed, j.unlit, x, y) >= 3; });
    EXPECT_GT(in.pixels, 20000u) << "too little lit floor in view";
    EXPECT_LE(in.max_diff, 2) << "lit floor (" << in.pixels << " px checked) darker or lighter than the reference";
    EXPECT_LE(j.metric.wrong_side_share, 0.002);
}

TEST(Lab4Shadows, PointLightCubeSeamsShowNoCracks) {
    // Light 1.5 above the floor: the cube map's face borders meet the floor where |x| = 1.5,
    // |z| = 1.5 and, beyond, where |x| = |z|. Casters straddle them; the lit floor between must show
    // neither a lit crack in a shadow nor a dark line across the light.
    json s = base_scene();
    s["camera"] = {{"position", {0, 9, 3}}, {"target", {0, 0, 0}}, {"fov_y_deg", 60}, {"near", 0.05}, {"far", 100}};
    s["lights"].push_back(point({0, 1.5, 0}));
    s["objects"].push_back(floor(12));
    s["objects"].push_back(thing("cube", "box", {1.5, 0.2, 0.3}, {0.4, 0.4, 0.4}));
    s["objects"].push_back(thing("cube", "stone", {2.2, 0.2, 2.2}, {0.4, 0.4, 0.4}, {0, 45, 0}));
    s["objects"].push_back(thing("cube", "box", {-0.4, 0.2, -1.5}, {0.4, 0.4, 0.4}));
    const Judged j = judge("cube_seams", s);
    if (!j.ok) return;
    SCOPED_TRACE(describe(j, "cube_seams"));
    EXPECT_GT(j.metric.receivers, 20000u);
    EXPECT_EQ(j.metric.wrong_side, 0u);
    EXPECT_LE(j.metric.mae, 2.0);
}

// --- stress: exit 0, no validation message, no NaN, a picture -------------------------------------

void expect_survives(const std::string& name, const json& scene, int w = 160, int h = 90) {
    const std::string png = kLab.render(kLab.write_scene(name, scene.dump(1)), name, w, h);
    if (png.empty()) return;
    const lab::Image8 image = lab::read_png(png);
    EXPECT_EQ(ref::magenta_pixels(image), 0u) << "NaN/Inf in " << png;
    int brightest = 0;
    for (size_t i = 0; i < image.rgba.size(); i += 4)
        brightest = std::max({brightest, int(image.rgba[i]), int(image.rgba[i + 1]), int(image.rgba[i + 2])});
    EXPECT_GT(brightest, 40) << "a black picture: " << png;
}

TEST(Lab4Stress, LightAlongPlusAndMinusY) {
    // The fitted frustum's up vector degenerates when the light travels exactly along ±Y.
    expect_survives("along_minus_y", casters_scene(directional({0, -1, 0})));
    expect_survives("along_plus_y", casters_scene(directional({0, 1, 0})));
    expect_survives("spot_down", casters_scene(spot({0, 4, 0}, {0, -1, 0})));
}

TEST(Lab4Stress, LightInsideAnObject) {
    for (const auto& [name, light] : std::vector<std::pair<std::string, json>>{
             {"inside_point", point({-1.2, 0.5, 0.3})}, {"inside_spot", spot({-1.2, 0.5, 0.3}, {0, -1, 0})}}) {
        json s = casters_scene(light);
        s["lights"].push_back({{"type", "directional"}, {"direction", {-1, -1, -1}}});  // something to see
        expect_survives(name, s);
    }
}

TEST(Lab4Stress, CasterTouchingTheSpotLightsNearPlane) {
    json s = casters_scene(spot({0, 2, 0}, {0, -1, 0}, 45));
    // A cube right under the light, its top face 0.05 and 0.01 below it and exactly at it.
    s["objects"].push_back(thing("cube", "stone", {0, 1.7, 0}, {0.5, 0.5, 0.5}));
    s["lights"].push_back({{"type", "directional"}, {"direction", {-1, -1, -1}}});  // something to see
    for (const auto& [suffix, y] : std::vector<std::pair<std::string, double>>{{"005", 1.7}, {"001", 1.74}, {"0", 1.75}}) {
        s["objects"][4]["position"] = {0, y, 0};
        expect_survives("spot_near_plane_" + suffix, s);
    }
}

TEST(Lab4Stress, ResolutionOneAndTheDeviceMaximum) {
    for (const int resolution : {1, 16384}) {
        std::vector<std::pair<std::string, json>> lights = {{"dir", directional({-0.6, -1, -0.35})},
                                                           {"spot", spot({1.5, 4, 2.5}, {-1.5, -4, -2.5}, 40)}};
        if (resolution == 1) lights.push_back({"point", point({1.5, 2.6, 1.6})});  // 6 faces of 16384² exceed memory
        for (auto& [kind, light] : lights) {
            light["shadow"] = {{"resolution", resolution}};
            expect_survives("resolution_" + std::to_string(resolution) + "_" + kind, casters_scene(light));
        }
    }
}

TEST(Lab4Stress, ZeroAndHugeBiases) {
    for (const double bias : {0.0, 1e6}) {
        for (auto [kind, light] : std::vector<std::pair<std::string, json>>{
                 {"dir", directional({-0.6, -1, -0.35})}, {"spot", spot({1.5, 4, 2.5}, {-1.5, -4, -2.5}, 40)},
                 {"point", point({1.5, 2.6, 1.6})}}) {
            light["shadow"] = {{"bias", bias}, {"slope_bias", bias}, {"normal_offset", bias}};
            if (bias > 0) {  // the widest kernel too: every tap of a 15×15 PCF past the map's edge
                light["shadow"]["pcf"] = 15;
                if (kind == "point") light["shadow"]["filter"] = "nearest";
            }
            expect_survives(std::string("bias_") + (bias > 0 ? "huge_" : "zero_") + kind, casters_scene(light));
        }
    }
}

}  // namespace
