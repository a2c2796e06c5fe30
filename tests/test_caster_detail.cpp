// Casters at the detail the map resolves (lab4_shadows/caster_detail.cpp): the distance of a
// tessellation to the true shape against the sagitta by hand, half a texel against the angle
// between two rays, and the level picked at each distance against the measured distance of the
// levels around it.
#include "caster_detail.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {
constexpr double kPi = 3.14159265358979323846;

lab::ObjectDesc shape(const std::string& name, int segments, int rings) {
    lab::ObjectDesc o;
    o.mesh = name;
    o.segments = segments;
    o.rings = rings;
    return o;
}
double error_of(const lab::ObjectDesc& o) { return surface_error(o.mesh, lab::make_mesh(o)); }
}  // namespace

// Hand calculations: a UV sphere of 4 segments and 2 rings is the regular octahedron (circumradius
// 0.5: its faces' centres lie 0.5 / √3 from the centre); a cylinder's side is a polygon whose
// edges' middles lie 0.5 cos(π / s) from the axis (its caps are flat, drawn exactly).
TEST(CasterDetail, SurfaceErrorIsTheSagittaByHand) {
    EXPECT_NEAR(error_of(shape("sphere", 4, 2)), 0.5 - 0.5 / std::sqrt(3.0), 1e-6);
    EXPECT_NEAR(error_of(shape("cylinder", 6, 1)), 0.5 * (1.0 - std::cos(kPi / 6.0)), 1e-6);
    EXPECT_NEAR(error_of(shape("cylinder", 6, 4)), 0.5 * (1.0 - std::cos(kPi / 6.0)), 1e-6);  // bands change nothing
    EXPECT_NEAR(error_of(shape("cone", 8, 1)), 0.5 * (1.0 - std::cos(kPi / 8.0)), 1e-6);    // widest at the base
    // The torus: at least the larger of its two sagittas (around Y at the outer equator, around
    // the tube), at most their sum.
    const double around = 0.5 * (1.0 - std::cos(kPi / 12.0)), tube = 0.15 * (1.0 - std::cos(kPi / 6.0));
    const double torus = error_of(shape("torus", 12, 6));
    EXPECT_GE(torus, std::max(around, tube) - 1e-9);
    EXPECT_LE(torus, around + tube + 1e-9);
    // Shapes that have no coarser tessellation: drawn as they are.
    for (const char* name : {"plane", "cube", "icosahedron"}) EXPECT_TRUE(coarser_levels(shape(name, 0, 0)).empty()) << name;
}

// Each level has fewer triangles and a larger distance to the shape than the one before it, and
// the first is coarser than the object's own mesh (defaults included: segments 0).
TEST(CasterDetail, LevelsGetCoarser) {
    for (const lab::ObjectDesc& o : {shape("sphere", 128, 64), shape("torus", 0, 0), shape("cylinder", 64, 8),
                                     shape("cone", 0, 0), shape("icosphere", 5, 0), shape("sphere", 0, 0)}) {
        SCOPED_TRACE(o.mesh + " " + std::to_string(o.segments) + " × " + std::to_string(o.rings));
        const std::vector<lab::ObjectDesc> levels = coarser_levels(o);
        ASSERT_FALSE(levels.empty());
        size_t triangles = lab::make_mesh(o).indices.size();
        double error = error_of(o);
        for (const lab::ObjectDesc& level : levels) {
            const size_t n = lab::make_mesh(level).indices.size();
            const double e = error_of(level);
            EXPECT_LT(n, triangles) << level.segments << " × " << level.rings;
            EXPECT_GE(e, error - 1e-12) << level.segments << " × " << level.rings;
            triangles = n;
            error = e;
        }
    }
}

// Half a texel: a directional map's is the same everywhere; a perspective map's is the angle
// between two neighbouring texels' rays at the map's corner, times the caster's distance, halved.
TEST(CasterDetail, HalfATexelIsTheSmallestTexelAtTheCaster) {
    LightFrustum ortho;
    ortho.texel = 12.0;  // 12 world units across the map
    EXPECT_DOUBLE_EQ(half_texel(ortho, 1024, lab::Box{{5, 5, 5}, {6, 6, 6}}), 0.5 * 12.0 / 1024.0);

    for (const double half_fov_deg : {45.0, 20.0, 60.0}) {
        LightFrustum f;
        f.perspective = true;
        f.origin = {1.0, 2.0, 3.0};
        const double t = std::tan(half_fov_deg * kPi / 180.0);
        f.texel = 2.0 * t;  // the image plane at distance 1 spans 2t
        const uint32_t used = 512;
        // The angle between the rays through two neighbouring texels at the corner (t, t).
        const double du = 2.0 * t / used;
        const glm::dvec3 a = glm::normalize(glm::dvec3(t, t, 1.0)), b = glm::normalize(glm::dvec3(t - du, t, 1.0));
        const double angle = std::acos(glm::dot(a, b));
        const lab::Box caster{f.origin + glm::dvec3(3.0, 0.0, 4.0), f.origin + glm::dvec3(4.0, 1.0, 5.0)};  // nearest point 5 away
        EXPECT_NEAR(half_texel(f, used, caster), 0.5 * 5.0 * angle, 0.5 * 5.0 * angle * 2e-3) << half_fov_deg;
        // A light inside the caster's box: no distance, no coarser level.
        EXPECT_EQ(half_texel(f, used, lab::Box{f.origin - 1.0, f.origin + 1.0}), 0.0);
    }
}

// The level a map draws, at every distance: within half a texel of the object's own mesh (its
// distance to the shape plus the own mesh's), and the next coarser level is not. A picker that
// took a whole texel, or ignored the scale, picks a level that fails here.
TEST(CasterDetail, PickedLevelIsTheCoarsestWithinHalfATexel) {
    for (const lab::ObjectDesc& o : {shape("sphere", 128, 64), shape("torus", 128, 64), shape("cylinder", 96, 1)}) {
        std::vector<double> errors = {error_of(o)};
        for (const lab::ObjectDesc& level : coarser_levels(o)) errors.push_back(error_of(level));
        for (const double scale : {0.01, 1.8, 300.0})
            for (const double tolerance : {1e-5, 1e-3, 3e-3, 0.01, 0.05, 0.5, 5.0}) {
                SCOPED_TRACE(o.mesh + " scale " + std::to_string(scale) + " tolerance " + std::to_string(tolerance));
                const size_t k = pick_level(errors, scale, tolerance);
                ASSERT_LT(k, errors.size());
                if (k > 0) {
                    EXPECT_LE((errors[k] + errors[0]) * scale, tolerance);
                }
                for (size_t coarser = k + 1; coarser < errors.size(); ++coarser)
                    EXPECT_GT((errors[coarser] + errors[0]) * scale, tolerance) << "level " << coarser;
            }
    }
    // By hand: errors 0.001 (own), 0.01, 0.1; scale 2.
    EXPECT_EQ(pick_level({0.001, 0.01, 0.1}, 2.0, 0.021), 0u);  // 0.022 > 0.021: the own mesh
    EXPECT_EQ(pick_level({0.001, 0.01, 0.1}, 2.0, 0.022), 1u);
    EXPECT_EQ(pick_level({0.001, 0.01, 0.1}, 2.0, 1.0), 2u);
}
