#version 450
// unlit.vert — where each vertex lands on screen (its clip-space position); no lighting.

layout(set = 0, binding = 0) uniform FrameUniforms {
    mat4 view;        // world → camera (the inverse of the camera's pose)
    mat4 projection;  // camera → clip (perspective, Y flipped for Vulkan)
} frame;

layout(push_constant) uniform ObjectConstants {
    mat4 model;   // model → world: T · Rz · Ry · Rx · S
    vec4 albedo;  // linear RGB
} object;

layout(location = 0) in vec3 in_position;

void main() {
    // model → world → camera → clip, a point (w = 1).
    // Right to left, one matrix·vector product per step (P·V·M·p as written would
    // multiply whole matrices for every vertex first).
    gl_Position = frame.projection * (frame.view * (object.model * vec4(in_position, 1.0)));
}
