#version 450
// translucent_shadow.frag — lab 4: translucent casters in a light's transmittance map, drawn
// with their front faces as the light sees them (a convex object counts once). Two pipelines
// share it (translucent_shadows.cpp): one writes g = the nearest such face's depth (depth test on), the
// other multiplies r by 1 − opacity (blending dst·src), so r = Π(1 − opacity) along the ray.

layout(push_constant) uniform ShadowConstants {
    mat4 light_mvp;
    vec4 transmittance;  // x = 1 − opacity
} caster;

layout(location = 0) out vec4 out_value;

void main() {
    out_value = vec4(caster.transmittance.x, gl_FragCoord.z, 0.0, 0.0);
}
