#version 450
// Lab 2: transform each vertex as in lab 1, and pass the world-space position, normal and
// tangent on for per-pixel lighting — or, with Gouraud shading, light the vertex right here.
#extension GL_GOOGLE_include_directive : require
#include "lighting.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 3) in vec4 in_tangent;

layout(location = 0) out vec3 out_world_position;
layout(location = 1) out vec3 out_world_normal;   // not normalized: interpolates like the model normal
layout(location = 2) out vec3 out_world_tangent;
layout(location = 3) out vec3 out_gouraud_color;  // Gouraud: the lit vertex color (linear RGB)
layout(location = 4) out float out_bad;           // Gouraud + NaN check: 1 if the vertex went bad

void main() {
    const vec4 world = object.model * vec4(in_position, 1.0);
    const mat3 normal_matrix = mat3(object.normal_matrix[0].xyz, object.normal_matrix[1].xyz,
                                    object.normal_matrix[2].xyz);
    out_world_position = world.xyz;
    out_world_normal = normal_matrix * in_normal;
    out_world_tangent = mat3(object.model) * in_tangent.xyz;
    out_gouraud_color = vec3(0.0);
    out_bad = 0.0;
    if (SHADING == SHADING_GOURAUD) {
        const vec3 to_eye = frame.camera_position.xyz - world.xyz;
        // A zero vertex normal has no direction: the vertex faces the viewer.
        const vec3 V0 = safe_normalize(to_eye, vec3(0.0, 0.0, 1.0));
        const vec3 N = safe_normalize(out_world_normal, V0);
        const vec3 V = safe_normalize(to_eye, N);
        out_gouraud_color = shade(materials[object.material], world.xyz, N, V, out_world_tangent);
        out_bad = lab_bad ? 1.0 : 0.0;
    }
    gl_Position = frame.projection * (frame.view * world);
}
