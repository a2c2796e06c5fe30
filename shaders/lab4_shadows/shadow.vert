#version 450
// shadow.vert — lab 4's shadow pass: where each caster's triangles land in the light's map.
// Position-only vertex input; opaque casters have no fragment shader at all (the pass writes
// depth only), translucent ones add translucent_shadow.frag.

layout(push_constant) uniform ShadowConstants {
    mat4 light_mvp;      // model → the light's clip space (one face of a cube map)
    vec4 transmittance;  // translucent casters: x = 1 − opacity, y = the layer, z = the peel's slack
} caster;

layout(location = 0) in vec3 in_position;

void main() {
    // precise: no fused multiply-adds that one pipeline's compile may use and another's not. The
    // peel (translucent_shadow.frag) compares a face's depth in one pass with what an earlier pass
    // stored for the same face, so both must compute the same position, bit for bit. (Its
    // pipelines differ only in write masks: TranslucentShadows::peel_slack().) Not `invariant
    // gl_Position`: glslang puts it on a block member, which the validation layers reject.
    precise vec4 position = caster.light_mvp * vec4(in_position, 1.0);
    gl_Position = position;
}
