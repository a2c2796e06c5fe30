#version 450
// depth_view.frag — a depth image as grey: near = black, far = white. A perspective map's depth
// is turned back into distance first, else everything looks white.

layout(set = 0, binding = 0) uniform sampler2D depth_map;

layout(push_constant) uniform ViewConstants {
    vec4 rect;
    vec4 perspective;  // x, y: a, b of the stored depth a − b / z; b = 0: shown as stored
} view;

layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_color;

void main() {
    float depth = texture(depth_map, in_uv).r;
    if (view.perspective.y > 0.0) {  // the stored depth →  z, then (z − near) / (far − near)
        const float a = view.perspective.x, b = view.perspective.y;
        const float z = b / max(a - depth, 1e-30), near = b / a, far = b / (a - 1.0);
        depth = clamp((z - near) / (far - near), 0.0, 1.0);
    }
    out_color = vec4(vec3(depth), 1.0);
}
