// test_lighting_math.cpp — lab 2's packing of lights for the GPU (lab2_lighting/lights.cpp) against
// the reference: the spot cone it packs, the counts, radiance and dropped extras. (The reference's
// own lighting against hand calculation: test_reference_lighting.cpp, instructors only.)
#include "reference/cpu_lighting.h"

#include "lights.h"
#include "probe.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

constexpr double kPi = 3.14159265358979323846;
double cos_deg(double d) { return std::cos(d * kPi / 180.0); }
using Falloff = lab::LightingDesc::SpotFalloff;

TEST(SpotFactor, LabPacksTheSameCone) {
    // The pair lights.cpp packs for the shader, read as the reference reads it, gives the reference's cone.
    for (Falloff falloff : {Falloff::Smooth, Falloff::Edge})
        for (auto [inner, outer] : {std::pair{10.0f, 20.0f}, std::pair{0.0f, 45.0f}, std::pair{25.0f, 25.0f},
                                    std::pair{89.0f, 90.0f}}) {
            lab::LightDesc spot;
            spot.type = lab::LightDesc::Type::Spot;
            spot.inner_deg = inner;
            spot.outer_deg = outer;
            const glm::vec2 cone = LAB_PROBE(spot_cone(spot, falloff));  // probe.h: what the lab computed
            for (double angle = 0.0; angle <= 95.0; angle += 0.7) {
                const double c = cos_deg(angle);
                const double gpu = ref::packed_spot_factor(glm::dvec2(cone), c);
                EXPECT_NEAR(gpu, ref::spot_factor(inner, outer, falloff, c), 1e-5) << inner << " " << outer << " " << angle;
            }
        }
}

// --- the lab's GPU packing ---

TEST(LightBuffer, PacksCountsRadianceAndDropsExtras) {
    lab::Scene scene;
    scene.ambient.color = {0.5f, 1.0f, 1.0f};
    scene.ambient.intensity = 0.2f;
    for (int i = 0; i < 40; ++i) {
        lab::LightDesc l;
        l.type = lab::LightDesc::Type::Point;
        l.color = {1.0f, 0.5f, 0.25f};
        l.intensity = 4.0f;
        scene.lights.push_back(l);
    }
    lab::LightDesc sun;
    sun.direction = {0, -2, 0};
    scene.lights.push_back(sun);
    const Lighting lighting = Lighting::from_scene(scene);
    const GpuLights g = lighting.pack_lights();
    EXPECT_EQ(g.counts, glm::uvec4(1, kMaxPoint, 0, 0));
    EXPECT_FLOAT_EQ(lighting.ambient_radiance().r, 0.1f);
    EXPECT_FLOAT_EQ(g.point[31].radiance.g, 2.0f);
    EXPECT_FLOAT_EQ(g.directional[0].direction.y, -1.0f);  // normalized
    const Variant v = variant_of(lighting);
    EXPECT_EQ(v[2], 1);          // one directional light
    EXPECT_EQ(v[3], kMaxPoint);  // the extra point lights were dropped
    EXPECT_EQ(v[4], 0);          // no spot: the spot loop is compiled out
    static_assert(sizeof(GpuLights) == 16 + 8 * 32 + 32 * 48 + 32 * 80, "std430 layout of lighting.glsl");
}

}  // namespace
