#version 450
// Lab 1: transform each vertex model → world → camera → clip space.

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
    // Right to left, one matrix·vector product per step (P·V·M·p as written would
    // multiply whole matrices for every vertex first).
    gl_Position = frame.projection * (frame.view * (object.model * vec4(in_position, 1.0)));
}
