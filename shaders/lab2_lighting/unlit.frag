#version 450
// Lab 1: no lighting yet — every pixel is its material's albedo (linear RGB;
// the *_SRGB render target encodes it for display).

layout(push_constant) uniform ObjectConstants {
    mat4 model;
    vec4 albedo;
} object;

layout(location = 0) out vec4 out_color;

void main() {
    out_color = vec4(object.albedo.rgb, 1.0);
}
