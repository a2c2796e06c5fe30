#version 450
// Lab 2: the lighting equation per pixel (flat and Phong shading), or the interpolated
// vertex color (Gouraud). See docs/lighting.md.
#extension GL_GOOGLE_include_directive : require
#include "lighting.glsl"

layout(location = 0) in vec3 in_world_position;
layout(location = 1) in vec3 in_world_normal;
layout(location = 2) in vec3 in_world_tangent;
layout(location = 3) in vec3 in_gouraud_color;
layout(location = 4) in float in_bad;

layout(location = 0) out vec4 out_color;

void main() {
    vec3 color;
    if (SHADING == SHADING_GOURAUD) {
        color = in_gouraud_color;
        lab_bad = in_bad > 0.0;
    } else {
        const vec3 P = in_world_position;
        const vec3 to_eye = frame.camera_position.xyz - P;
        // EXERCISE face_normal: N for the flat and Phong models (docs/lighting.md "Shading models"). Flat: the triangle's own normal, which no vertex carries and no input gives: what does a fragment shader know about how P changes across the triangle, and which way must the normal point (towards the eye, on the side of the triangle the camera sees, whatever the winding and Vulkan's downward y do to a cross product)? Phong: the interpolated normal, no longer unit, possibly zero. Degenerate cases: safe_normalize(). Read the GLSL spec's "Derivative Functions", docs/lighting.md "Numerical safety". Wrong: no facets under flat shading, black or inverted facets, black spots where the normals cancel. Checked by Lab2Term.FlatFacets, Lab2Shading.FlatVsPhong.
        // STUB: const vec3 N = safe_normalize(in_world_normal, safe_normalize(to_eye, vec3(0.0, 0.0, 1.0)));  // no facets: every model Phong's
        // The triangle's own (geometric) normal from the screen-space derivatives of the
        // position, turned towards the eye: every drawn triangle is a front face.
        vec3 face = safe_normalize(cross(dFdx(P), dFdy(P)), safe_normalize(to_eye, vec3(0.0, 0.0, 1.0)));
        if (dot(face, to_eye) < 0.0) face = -face;
        // Flat: the face normal. Phong: the interpolated normal, renormalized (a zero
        // interpolated normal falls back to the face normal).
        const vec3 N = SHADING == SHADING_FLAT ? face : safe_normalize(in_world_normal, face);
        // END EXERCISE
        const vec3 V = safe_normalize(to_eye, N);  // the eye on the surface: V = N
        color = shade(materials[object.material], P, N, V, in_world_tangent);
    }
    // The self-test proves the check works: a quiet NaN (exponent all ones, top mantissa bit)
    // made from the bits of a uniform (ambient.a = 0), so no compiler can know it is a NaN and
    // fold it away (as it may fold x / x to 1), added to the color like a real bad intermediate.
    if (NAN_CHECK == 2) color += vec3(uintBitsToFloat(0x7fc00000u | floatBitsToUint(frame.ambient.a)));
    if (NAN_CHECK != 0) {
        check(color);
        if (lab_bad) color = vec3(1.0, 0.0, 1.0);
    }
    out_color = vec4(color, 1.0);
}
