#version 450
// Vertex colour times the font atlas (white texels with coverage in alpha; solid shapes use its
// white texel): the same as ImGui's own Vulkan backend.
layout(set = 0, binding = 0) uniform sampler2D font_atlas;

layout(location = 0) in vec4 color;
layout(location = 1) in vec2 uv;
layout(location = 0) out vec4 out_color;

void main() {
    out_color = color * texture(font_atlas, uv);
}
