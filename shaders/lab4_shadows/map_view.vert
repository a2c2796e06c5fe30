#version 450
// map_view.vert — lab 4's shadow-map view: one screen rectangle per map (per face of a cube
// map), two triangles made from the vertex index (no vertex buffer).

layout(push_constant) uniform ViewConstants {
    vec4 rect;    // x0, y0, x1, y1 in normalized device coordinates
    ivec4 which;  // x: shadow slot, y: cube face (−1: a 2D map), z: 1 for a perspective map
} view;

layout(location = 0) out vec2 out_uv;

void main() {
    const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
    const vec2 c = corners[gl_VertexIndex];
    out_uv = c;
    gl_Position = vec4(mix(view.rect.xy, view.rect.zw, c), 0.0, 1.0);
}
