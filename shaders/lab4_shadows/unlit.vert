#version 450
// unlit.vert — transform each vertex model → world → camera → clip space.

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
    // EXERCISE mvp: model space → world (model) → camera (view) → clip space (projection). Checked by Lab1Render.DefaultScene.
    // STUB: gl_Position = vec4(in_position, 1.0);  // model space taken for clip space
    // Right to left, one matrix·vector product per step (P·V·M·p as written would
    // multiply whole matrices for every vertex first).
    gl_Position = frame.projection * (frame.view * (object.model * vec4(in_position, 1.0)));
    // END EXERCISE
}
