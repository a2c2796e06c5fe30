#version 450
// depth_view.vert — one square of the depth view (lab4_shadows/depth_view.h): two triangles made from
// the vertex index (no vertex buffer) over the rectangle given in normalized device coordinates.

layout(push_constant) uniform ViewConstants {
    vec4 rect;          // x0, y0, x1, y1
    mat4 clip_to_view;  // depth_view.frag
    vec4 used;          // x: the share of the image the map pass drew (a square at its corner)
} view;

layout(location = 0) out vec2 out_uv;

void main() {
    const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
    const vec2 c = corners[gl_VertexIndex];
    out_uv = c * view.used.x;  // the drawn square only
    gl_Position = vec4(mix(view.rect.xy, view.rect.zw, c), 0.0, 1.0);
}
