#version 450
// ImGui's triangles: positions in pixels, the font atlas UV, a colour per vertex (already linear).
layout(location = 0) in vec2 in_position;
layout(location = 1) in vec2 in_uv;
layout(location = 2) in vec4 in_color;

// Pixels to clip space: clip = pixel * scale + translate (Vulkan's clip y points down, as ImGui's y).
layout(push_constant) uniform Push {
    vec2 scale;
    vec2 translate;
} push;

layout(location = 0) out vec4 color;
layout(location = 1) out vec2 uv;

void main() {
    color = in_color;
    uv = in_uv;
    gl_Position = vec4(in_position * push.scale + push.translate, 0.0, 1.0);
}
