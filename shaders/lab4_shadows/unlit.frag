#version 450
// unlit.frag — no lighting: every pixel is the colour pushed with the object, `albedo`
// (linear RGB; the *_SRGB render target encodes it for display).

layout(push_constant) uniform ObjectConstants {
    mat4 model;
    vec4 albedo;
} object;

layout(location = 0) out vec4 out_color;

void main() {
    out_color = vec4(object.albedo.rgb, 1.0);
}
