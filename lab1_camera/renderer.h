// renderer.h — draws the scene's objects, unlit: every pixel is its material's albedo.
#pragma once

#include "buffer.h"
#include "gpu_mesh.h"
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
             const std::string& shader_dir);

    // Records the draw commands for one frame (inside the target's render pass).
    void draw(const lab::Frame& frame, const glm::mat4& view, const glm::mat4& projection);

private:
    // Per-frame data, one uniform buffer per frame in flight (std140 layout).
    struct FrameUniforms {
        glm::mat4 view;
        glm::mat4 projection;
    };
    // Per-object data, pushed with each draw.
    struct ObjectConstants {
        glm::mat4 model;
        glm::vec4 albedo;
    };
    struct DrawItem {
        const lab::GpuMesh* mesh;
        ObjectConstants constants;
        lab::Box box;  // world-space bounds: the draw order
        double far_depth = 0.0;  // this frame's sort key (draw())
    };

    const lab::VulkanContext& vk_;
    std::map<std::string, lab::GpuMesh> meshes_;  // one upload per distinct mesh
    std::vector<DrawItem> items_;
    lab::Handle<VkDescriptorSetLayout> set_layout_;
    lab::Handle<VkDescriptorPool> pool_;
    std::vector<lab::Buffer> uniforms_;        // [frame slot]
    std::vector<VkDescriptorSet> sets_;        // [frame slot]
    lab::Handle<VkShaderModule> vertex_shader_;
    lab::Handle<VkShaderModule> fragment_shader_;
    lab::PipelineBuilder::Result pipeline_;
};
