// renderer.h — draws the scene's objects, lit: ambient, directional, point and spot lights
// with the lighting and shading model the scene (or the UI) picks; optional light markers.
#pragma once

#include "buffer.h"
#include "gpu_mesh.h"
#include "lights.h"
#include "pipeline_builder.h"
#include "render_target.h"
#include "scene.h"

#include <glm/glm.hpp>

#include <map>
#include <string>
#include <vector>

class Renderer {
public:
    Renderer(const lab::VulkanContext& vk, const lab::RenderTarget& target, const lab::Scene& scene,
             const Lighting& lighting, const std::string& shader_dir);

    // Records the draw commands for one frame (inside the target's render pass).
    void draw(const lab::Frame& frame, const glm::mat4& view, const glm::mat4& projection,
              const glm::vec3& camera_position, const Lighting& lighting);

private:
    // Per-frame data, one uniform buffer per frame in flight (std140 layout).
    struct FrameUniforms {
        glm::mat4 view;
        glm::mat4 projection;
        glm::vec4 camera_position;  // xyz: the eye, for the view direction V
        glm::vec4 ambient;          // rgb: ambient color × intensity
    };
    // Per-object data, pushed with each draw.
    struct ObjectConstants {
        glm::mat4 model;
        glm::vec4 albedo;
    };
    // Per-object data of the lit pipeline (116 of the 128 bytes every GPU allows).
    struct LitConstants {
        glm::mat4 model;
        glm::vec4 normal_matrix[3];  // columns of the normal matrix (normal_matrix())
        uint32_t material;           // index into the material buffer
    };
    struct DrawItem {
        const lab::GpuMesh* mesh;
        ObjectConstants constants;
        LitConstants lit{};
        lab::Box box;  // world-space bounds: the draw order
        double far_depth = 0.0;  // this frame's sort key (draw())
    };

    void draw_lit(VkCommandBuffer cmd, uint32_t slot, const Lighting& lighting);
    // The lit pipeline for the current specialization constants (built on first use, then cached).
    const lab::PipelineBuilder::Result& lit_pipeline(const Variant& variant);
    // lab 1's unlit pipeline draws the light markers, and whole scenes without lights.
    void draw_markers(VkCommandBuffer cmd, uint32_t slot, const Lighting& lighting);
    void draw_ambient_only(VkCommandBuffer cmd, uint32_t slot, const Lighting& lighting);

    const lab::VulkanContext& vk_;
    VkRenderPass render_pass_;
    std::map<std::string, lab::GpuMesh> meshes_;  // one upload per distinct mesh
    std::vector<DrawItem> items_;
    lab::Handle<VkDescriptorSetLayout> set_layout_;
    lab::Handle<VkDescriptorPool> pool_;
    std::vector<lab::Buffer> uniforms_;        // [frame slot]
    std::vector<lab::Buffer> lights_;          // [frame slot] GpuLights
    std::vector<lab::Buffer> materials_;       // [frame slot] GpuMaterial[kMaxMaterials]
    std::vector<VkDescriptorSet> sets_;        // [frame slot]
    lab::Handle<VkShaderModule> vertex_shader_;
    lab::Handle<VkShaderModule> fragment_shader_;
    lab::PipelineBuilder::Result pipeline_;
    lab::Handle<VkShaderModule> lit_vertex_shader_;
    lab::Handle<VkShaderModule> lit_fragment_shader_;
    std::map<Variant, lab::PipelineBuilder::Result> lit_pipelines_;  // [specialization constants]
};
