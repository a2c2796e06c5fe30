// renderer.h — draws the scene's objects, lit: ambient, directional, point and spot lights
// with the lighting and shading model the scene (or the UI) picks; optional light markers.
// Lab 3: materials with texture maps (albedo, specular, emissive), each image uploaded once.
// Lab 4: shadow maps (shadow_maps.h) rendered first; translucent objects drawn last, their layers
// sorted and composed per pixel (translucent_layers.h).
#pragma once

#include "buffer.h"
#include "gpu_mesh.h"
#include "lights.h"
#include "pipeline_builder.h"
#include "render_target.h"
#include "scene.h"
#include "shadow_maps.h"
#include "sampler_cache.h"
#include "texture.h"
#include "translucent_layers.h"

#include <glm/glm.hpp>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

class Renderer {
public:
    Renderer(const lab::VulkanContext& vk, const lab::RenderTarget& target, const lab::Scene& scene,
             const Lighting& lighting, const std::string& shader_dir);

    // Lab 4: before the target's render pass: the shadow maps that need rendering, for the
    // picture the camera (world → clip) takes.
    void draw_shadow_maps(const lab::Frame& frame, const glm::dmat4& camera, const Lighting& lighting);
    // False when the lights casting shadows (or their resolutions) changed: rebuild the renderer.
    bool shadows_match(const Lighting& lighting) const { return shadow_maps_->matches(lighting); }
    int shadow_map_renders() const { return shadow_maps_->renders(); }
    int shadow_maps_rendered_last_frame() const { return shadow_maps_->rendered_last(); }
    std::string shadow_maps_drawn() const { return shadow_maps_->drawn(); }  // texels per side drawn, per map
    std::string shadow_maps_triangles() const { return shadow_maps_->triangles(); }  // at the detail each map drew
    // Lab 4: before the target's render pass too: empties the translucent layers' lists (nothing
    // without translucent objects); a new frame size gets new lists first.
    void clear_translucent_layers(const lab::Frame& frame);
    // The per-pixel lists of translucent layers and what they could not hold; null: no translucent object.
    TranslucentLayers* translucent_layers() { return layers_.get(); }
    const TranslucentLayers* translucent_layers() const { return layers_.get(); }
    // Records the draw commands for one frame (inside the target's render pass).
    void draw(const lab::Frame& frame, const glm::mat4& view, const glm::mat4& projection,
              const glm::vec3& camera_position, const Lighting& lighting);
    // One line per map that could not be read (it shows the checkerboard) or sampler clamped.
    const std::vector<std::string>& texture_warnings() const { return warnings_; }
    size_t sampler_count() const { return samplers_.size(); }
    // What "anisotropic": "auto" picks on this device (the Textures panel shows it).
    std::string anisotropic_auto() const { return samplers_.auto_choice(); }

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
        lab::Box box;  // world-space bounds: the draw order; lab 4: where on screen a translucent object may be
        double far_depth = 0.0;  // this frame's sort key (draw())
    };
    // Lab 4: opaque objects first, then the translucent ones' layers (both faces, into the lists).
    enum class Pass { Opaque, Layers };

    enum class Objects { All, TexturedOnly };  // TexturedOnly: the others were drawn ambient-only
    void draw_lit(VkCommandBuffer cmd, uint32_t slot, const Lighting& lighting, Objects objects,
                  const std::vector<const DrawItem*>& items, Pass pass);
    void load_textures(const Lighting& lighting);
    // The lit pipeline for the current specialization constants (built on first use, then cached).
    const lab::PipelineBuilder::Result& lit_pipeline(const Variant& variant, Pass pass = Pass::Opaque);
    // lab 1's unlit pipeline draws the light markers, and whole scenes without lights.
    void draw_markers(VkCommandBuffer cmd, uint32_t slot, const Lighting& lighting);
    void draw_ambient_only(VkCommandBuffer cmd, uint32_t slot, const Lighting& lighting);
    // Lab 4: the pixels the translucent objects' boxes cover (the whole frame if one reaches behind
    // the near plane), where the layers are composed.
    VkRect2D translucent_area(const glm::mat4& view, const glm::mat4& projection, VkExtent2D extent) const;

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
    lab::Handle<VkShaderModule> textured_fragment_shader_;  // lab 3: lit.frag with the samplers
    lab::Handle<VkShaderModule> layer_fragment_shader_;     // lab 4: lit.frag storing layers (translucent scenes)
    lab::Handle<VkShaderModule> textured_layer_fragment_shader_;  // and with the samplers
    std::map<std::pair<Variant, Pass>, lab::PipelineBuilder::Result> lit_pipelines_;  // [specialization constants]
    // Lab 3: textures. Each map image loaded and uploaded once; per material with maps one
    // descriptor set (set 1), written once; materials without maps bind nothing.
    SamplerCache samplers_;
    using TextureKey = std::pair<std::string, VkFormat>;  // a map, in the format its kind reads it
    std::map<TextureKey, Texture> textures_;
    Texture white_;  // stands in for a map a textured material lacks
    lab::Handle<VkDescriptorSetLayout> texture_layout_;
    lab::Handle<VkDescriptorPool> texture_pool_;
    std::vector<VkDescriptorSet> material_sets_;       // [material]; VK_NULL_HANDLE: no maps
    std::vector<std::array<int32_t, 5>> material_maps_;  // [material]: albedo_map … distorted_sampling, probes
    std::vector<std::string> warnings_;
    // Lab 4: the shadow maps, their per-frame data, the shadow-map view.
    std::unique_ptr<ShadowMaps> shadow_maps_;
    std::vector<lab::Buffer> shadows_;  // [frame slot] GpuShadows
    std::vector<const DrawItem*> opaque_, translucent_;  // this frame's draw order
    DepthView shadow_view_;  // the shadow-map view (depth_view.h)
    std::unique_ptr<TranslucentLayers> layers_;  // lab 4: only when some object is translucent
};
