#version 450
// map_view.frag — lab 4's shadow-map view: the stored depth as grey (near = black, far = white;
// a perspective map's depth is turned back into distance first, else everything looks white).
#extension GL_GOOGLE_include_directive : require
#include "shadows.glsl"

layout(push_constant) uniform ViewConstants {
    vec4 rect;
    ivec4 which;
} view;

layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_color;

// The direction a cube face's texel (s, t) stands for (Vulkan's cube map face layout).
vec3 face_direction(int face, vec2 st) {
    const vec2 c = st * 2.0 - 1.0;
    if (face == 0) return vec3(1.0, -c.y, -c.x);
    if (face == 1) return vec3(-1.0, -c.y, c.x);
    if (face == 2) return vec3(c.x, 1.0, c.y);
    if (face == 3) return vec3(c.x, -1.0, -c.y);
    if (face == 4) return vec3(c.x, -c.y, 1.0);
    return vec3(-c.x, -c.y, -1.0);
}

float stored_depth(int slot, int face, vec2 uv) {
    const vec3 d = face_direction(face, uv);
    switch (slot) {
        case 0: return face < 0 ? texture(shadow_depth[0], uv).r : texture(cube_depth[0], d).r;
        case 1: return face < 0 ? texture(shadow_depth[1], uv).r : texture(cube_depth[1], d).r;
        case 2: return face < 0 ? texture(shadow_depth[2], uv).r : texture(cube_depth[2], d).r;
        case 3: return face < 0 ? texture(shadow_depth[3], uv).r : texture(cube_depth[3], d).r;
    }
    return 1.0;
}

void main() {
    const int slot = view.which.x;
    float depth = stored_depth(slot, view.which.y, in_uv);
    if (view.which.z != 0) {  // perspective: depth = a − b / z  →  z, then (z − near) / (far − near)
        const float a = shadow_slots[slot].params.y, b = shadow_slots[slot].params.z;
        const float z = b / max(a - depth, 1e-30), near = b / a, far = b / (a - 1.0);
        depth = clamp((z - near) / (far - near), 0.0, 1.0);
    }
    out_color = vec4(vec3(depth), 1.0);
}
