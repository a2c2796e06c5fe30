// cpu_shadow.h — lab 4's shadows and translucency for the CPU reference: ray-traced hard shadows.
//
// Written from the rule in docs/scene-format.md ("Shadows (lab 4)") and /lab4_shadows/README.md,
// independent of the lab's shadow maps:
//
//   * Shadow ray: from the shaded point P toward the light — to the light's position for point and
//     spot lights (a caster beyond the light does nothing), along −direction to infinity for a
//     directional light — against every triangle of every object with cast_shadows (the same
//     lab::make_mesh triangles the primary rays see, in world space, double precision).
//   * Avoiding self-intersection: the ray starts at P + ε·n, n the geometric normal of the shaded
//     side turned to the light's side of the triangle's plane, ε = 1e-6 · (1 + max|P|) (a millionth
//     of the scene's size, far above double rounding and far below a pixel). No other bias: a
//     triangle facing away from the light is shadowed by its own mesh (a tessellated sphere's
//     terminator follows its facets).
//   * Light let through = Π over translucent casters of (1 − opacity) per crossing of a face whose
//     front side looks at the light (a convex object counts once; crossings at the same distance —
//     a ray through a shared edge — count once); an opaque caster hit from either side gives 0.
//   * Translucent surfaces (opacity < 1) in the picture: every layer on the primary ray in front of
//     the nearest opaque front face is shaded (back faces with the normal flipped towards the eye)
//     and blended in depth order, c = α·layer + (1 − α)·c, in linear colour.
#pragma once

#include "reference/cpu_reference.h"
#include "reference/image_compare.h"

#include <glm/glm.hpp>

#include <memory>
#include <vector>

namespace ref {

// The shadow casters of a scene, ready to trace shadow rays against. Thread-safe to query.
class ShadowCasters {
public:
    explicit ShadowCasters(const lab::Scene& scene);

    // The fraction of `light`'s light that reaches world point P (1 = unshadowed, 0 = blocked),
    // whatever the light's cast_shadows says. `normal`: the shaded side's geometric normal (unit or not;
    // only its line matters: the ray starts on the light's side).
    double transmittance(const lab::LightDesc& light, const glm::dvec3& P, const glm::dvec3& normal) const;

    // ε of the start offset at P (see the file comment).
    static double offset(const glm::dvec3& P);

private:
    std::vector<double> opacity_;  // per object; < 0: casts nothing
    std::shared_ptr<const SceneGeometry> geometry_;
};

// The direction from P toward the light (unit) and the distance to it (infinity for directional).
void toward_light(const lab::LightDesc& light, const glm::dvec3& P, glm::dvec3* L, double* distance);

// Lab 4's reference picture: lab 3's textured shading (ref::make_texture_shader) where every light
// with cast_shadows is multiplied by ShadowCasters::transmittance, plus translucent blending.
// `shadows` false: the same picture with every shadow off (lights unoccluded), for the error metric.
// `margin` > 0: the picture is (width + 2·margin) × (height + 2·margin), the same camera and pixel
// grid extended past the frame (rays through pixel centres x + 0.5 for x = −margin … width − 1 + margin),
// so that crop_margin(picture, margin) is the plain picture bit for bit. The shadow metric's band
// then sees reference edges just outside the frame (ShadowMetricOptions::margin).
RefImage render_shadowed(const lab::Scene& scene, int width, int height, bool shadows = true, int margin = 0);

// The width × height centre of a picture rendered with `margin` (every per-pixel field cropped).
RefImage crop_margin(const RefImage& image, int margin);

// The three pictures the shadow error metric needs (image_compare.h, shadow_error()):
//   shadowed   = render_shadowed(scene);
//   unshadowed = every light unoccluded;
//   unlit      = the lights with cast_shadows turned off completely (intensity 0).
struct ShadowReference {
    RefImage shadowed, unshadowed, unlit;
};
ShadowReference render_shadow_reference(const lab::Scene& scene, int width, int height, int margin = 0);

// The shadow error metric of `actual` (the lab's picture of `scene`) against the reference, which
// is rendered options.band pixels larger on every side (options.margin = band): the band then
// also holds the pixels near a shadow edge just outside the frame. `*reference` is set to the
// frame's pictures (cropped). Every test that judges a shadow picture goes through here.
ShadowMetric judge_shadows(const lab::Scene& scene, const lab::Image8& actual, ShadowMetricOptions options,
                           ShadowReference* reference);

}  // namespace ref
