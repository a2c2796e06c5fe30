#version 450
// depth_view.frag — a depth image as grey: near = black, far = white. A perspective map's depth
// is turned back into distance first, else everything looks white.

layout(set = 0, binding = 0) uniform sampler2D depth_map;

layout(push_constant) uniform ViewConstants {
    vec4 rect;
    mat4 clip_to_view;  // the map's projection, inverted (identity: the depth shown as stored)
    vec4 used;          // x: the share of the image the map pass drew (a square at its corner)
} view;

layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_color;

// The distance along the view axis of the point on that axis whose stored depth is `depth`: the
// clip-space point (0, 0, depth, 1) taken back through the projection (w divides last).
float distance_of(float depth) {
    const vec4 p = view.clip_to_view * vec4(0.0, 0.0, depth, 1.0);
    return -p.z / p.w;  // the view looks along −z
}

void main() {
    const float near = distance_of(0.0), far = distance_of(1.0);
    const float z = distance_of(texture(depth_map, in_uv).r);
    out_color = vec4(vec3(clamp((z - near) / (far - near), 0.0, 1.0)), 1.0);
}
