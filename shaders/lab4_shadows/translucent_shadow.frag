#version 450
// translucent_shadow.frag — lab 4: translucent casters in a light's transmittance map, drawn
// with their front faces as the light sees them (a convex object counts once), one layer per
// pass (translucent_shadows.cpp). The peel: the pass of layer k sees only the faces beyond layer
// k − 1 — a face no farther than the one that layer holds was peeled off already. Among those a
// depth-only draw finds the nearest, and a second draw (depth test ≤, blended dst · src into the
// cleared r = g = 1) stores its 1 − α in r and its depth in g; in the last layer r = Π(1 − α) of them
// all (drawn before the depth-only draw) and g the nearest depth. "No farther" is exact with 32-bit
// layers (slack 0): every pass computes a face's depth the same way, bit for bit
// (TranslucentShadows::peel_slack() says which invariance rule makes it so).

layout(push_constant) uniform ShadowConstants {
    mat4 light_mvp;
    vec4 transmittance;  // x = 1 − opacity, y = the layer k, z = the peel's slack (0: 32-bit layers)
} caster;

layout(set = 0, binding = 0) uniform sampler2D previous;  // layer k − 1 (k = 0: a 1×1 "nothing")

layout(location = 0) out vec4 out_value;

void main() {
    if (caster.transmittance.y > 0.5) {  // k ≥ 1: the same for every fragment of the draw
        const float peeled = texelFetch(previous, ivec2(gl_FragCoord.xy), 0).g;
        if (gl_FragCoord.z <= peeled * (1.0 + caster.transmittance.z)) discard;
    }
    out_value = vec4(caster.transmittance.x, gl_FragCoord.z, 0.0, 0.0);
}
