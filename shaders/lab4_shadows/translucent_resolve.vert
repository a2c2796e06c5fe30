#version 450
// translucent_resolve.vert — one triangle that covers the whole screen, made from the vertex index
// (no vertex buffer): corners (−1, −1), (3, −1), (−1, 3) in normalized device coordinates. The
// scissor (lab4_shadows/translucent_layers.cpp) cuts it down to where translucent objects are.

void main() {
    const vec2 corner = vec2(float((gl_VertexIndex & 1) << 2), float((gl_VertexIndex & 2) << 1)) - 1.0;
    gl_Position = vec4(corner, 0.0, 1.0);
}
