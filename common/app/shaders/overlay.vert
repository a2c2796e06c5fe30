#version 450
// One panel rectangle as a triangle strip of 4 vertices: corners (0,0), (1,0), (0,1), (1,1)
// of the rectangle given in clip space (x0, y0, x1, y1).
layout(push_constant) uniform Push {
    vec4 rect;
} push;

void main() {
    const vec2 corner = vec2(gl_VertexIndex & 1, (gl_VertexIndex >> 1) & 1);
    gl_Position = vec4(mix(push.rect.xy, push.rect.zw, corner), 0.0, 1.0);
}
