#version 450
// The cached UI overlay, one texel per pixel: premultiplied linear colour and coverage. The
// pipeline blends it as out = overlay.rgb + picture * (1 - overlay.a).
layout(set = 0, binding = 0) uniform sampler2D overlay;

layout(location = 0) out vec4 out_color;

void main() {
    out_color = texelFetch(overlay, ivec2(gl_FragCoord.xy), 0);
}
