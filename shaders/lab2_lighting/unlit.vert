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
    // EXERCISE mvp: the clip-space position of in_position: which spaces does it pass through (what do object.model, frame.view, frame.projection map from and to), in which order, with what w? Read the comments on FrameUniforms, ObjectConstants and the Vulkan spec's "Coordinate Transformations". Wrong: objects piled at the centre, the camera ignored, or a smeared mess. Checked by Lab1Render.DefaultScene.
    // STUB: gl_Position = vec4(in_position, 1.0);  // model space taken for clip space
    // Right to left, one matrix·vector product per step (P·V·M·p as written would
    // multiply whole matrices for every vertex first).
    gl_Position = frame.projection * (frame.view * (object.model * vec4(in_position, 1.0)));
    // END EXERCISE
}
