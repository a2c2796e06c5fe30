// shadow_maps.h — lab 4's first pass: each shadow-casting light (up to kMaxShadowLights) renders
// the scene's casters from its own point of view into a depth map — 2D for a directional or spot
// light, a cube (six faces) for a point light — before the camera's pass reads them
// (shaders/lab4_shadows/shadows.glsl). When the scene has translucent casters, each map gets a
// transmittance map beside it. A map is rendered again only when its light, or a caster in its
// volume, changed: a static scene renders its maps once.
#pragma once

#include "depth_view.h"
#include "offscreen.h"
#include "pass_timer.h"
#include "pipeline_builder.h"
#include "translucent_shadows.h"
#include "gpu_mesh.h"
#include "light_frustum.h"
#include "lights.h"

#include <glm/glm.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

// Per shadow slot, what the lookup needs (std140, see shadows.glsl).
struct GpuShadow {
    glm::mat4 view_projection;  // (world − origin) → the map's clip space (2D maps)
    glm::vec4 origin;           // xyz: the light (spot, cube), the fitted box's centre (directional)
    glm::vec4 params;           // x: normal offset (world; perspective: per unit distance), y, z: a perspective map's depth constants (shadows.glsl)
    glm::vec4 translucent;      // x: the translucent tolerance in depth (perspective: times 1 / distance)
};
using GpuShadows = std::array<GpuShadow, kMaxShadowLights>;  // [slot]

// An object as the shadow pass sees it.
struct Caster {
    const lab::GpuMesh* mesh;
    glm::mat4 model;
    Box box;            // world-space bounds
    uint32_t material;  // index into Lighting::materials (its opacity)
    bool casts;         // ObjectDesc::cast_shadows
    bool convex;        // a convex mesh (primitives but the torus) shadows only its own unlit side
    // Coarser tessellations of `mesh` the map may draw (caster_detail.h), coarser and coarser, and
    // each one's distance to the true surface after errors[0], the own mesh's (the shape's units);
    // `scale` takes those to world units (the model's longest axis).
    std::vector<const lab::GpuMesh*> levels;
    std::vector<double> errors;
    double scale = 1.0;
};

class ShadowMaps {
public:
    ShadowMaps(const lab::VulkanContext& vk, std::vector<Caster> objects, const Lighting& lighting,
               const std::string& shader_dir);

    // Set 0's bindings 3..9 (after the renderer's three): the slots' data and maps.
    static std::vector<lab::DescriptorBinding> bindings();
    // Points bindings 3..9 of `set` at `uniforms` and the maps (1×1 stand-ins for unused slots).
    void write_descriptors(VkDescriptorSet set, VkBuffer uniforms) const;

    // Outside any render pass, before the camera's: renders the maps whose light or casters
    // changed since they were last rendered, and writes every slot's data to `out`. `timer` (may be
    // null) times each map's passes for the panel (pass_timer.h).
    // `camera`: the picture's world → clip and size, which the maps' texels follow (fit_to_view,
    // map_footprint.h).
    void record(VkCommandBuffer cmd, const Lighting& lighting, const glm::dmat4& camera, VkExtent2D picture,
                GpuShadows* out, lab::PassTimer* timer);
    // True when these maps still fit `lighting` (the same lights cast shadows, with the same
    // resolutions); if not, the renderer is rebuilt (new images).
    bool matches(const Lighting& lighting) const;
    int maps() const { return int(maps_.size()); }
    int renders() const { return renders_; }  // maps rendered so far (a cube counts once)
    int rendered_last() const { return rendered_last_; }  // maps the last record() rendered
    // The texels per side each map's last render drew, of its resolution: "spot 3: 448 of 1024, …".
    std::string drawn() const;
    // The opaque casters' triangles each map's last render drew (caster_detail.h), of their own
    // meshes' (a cube: all six faces' casters once): "light 0: 5.3 k of 52.9 k, …".
    std::string triangles() const;
    // The shadow-map view (UI only): slot's map (a cube: its six faces) drawn by `view`; none for no map.
    void draw_view(DepthView& view, VkCommandBuffer cmd, int slot, VkExtent2D extent) const;

private:
    struct Map {
        int light = -1;  // index into Lighting::lights
        bool cube = false;
        LayeredTarget depth;          // the map (its size: the resolution), one framebuffer per face
        uint32_t used = 0;            // the texels per side the last render drew (≤ size): the square at (0, 0)
        uint64_t triangles = 0, own_triangles = 0;  // the opaque casters' in the last render (triangles())
        bool fitted = false;          // `used` was fitted to the picture (fit_to_view)
        std::vector<bool> in_map;     // the casters it holds (casters_for) and where it looks,
        LightFrustum frustum;         // both as of the last change of its key
        TranslucentShadows::Map translucent;  // translucent scenes: the transmittance map beside it
        std::vector<float> key;  // what the map was rendered from (change tracking)
        GpuShadow gpu{};
        glm::mat4 clip_to_view{1.0f};  // the map view's (depth_view.h): its projection, inverted
    };
    Map make_map(int light, bool cube, uint32_t resolution, bool translucent) const;
    std::vector<float> key_of(const lab::LightDesc& light, const Lighting& lighting) const;
    LightFrustum fit(const lab::LightDesc& light, bool cube, const std::vector<bool>& in_map) const;
    void render(VkCommandBuffer cmd, Map& map, const lab::LightDesc& light, const Lighting& lighting,
                lab::PassTimer* timer);
    void draw_casters(VkCommandBuffer cmd, const glm::dmat4& world_to_clip, const Lighting& lighting, bool translucent,
                      const std::vector<bool>& in_map, const lab::ShadowDesc* bias, const std::vector<float>& most_bias,
                      uint32_t layer = 0, const std::vector<const lab::GpuMesh*>* meshes = nullptr) const;
    uint32_t clamp_resolution(int requested, bool cube) const;
    std::vector<bool> casters_for(const lab::LightDesc& light, const Lighting& lighting) const;
    bool shadows_itself(size_t object, const Lighting& lighting) const;

    const lab::VulkanContext& vk_;
    std::vector<Caster> objects_;
    std::vector<Box> receiver_boxes_;  // every object's
    VkFormat depth_format_ = VK_FORMAT_D32_SFLOAT;
    lab::Handle<VkRenderPass> depth_pass_;        // depth only
    lab::PipelineBuilder::Result opaque_;                    // depth only, depth bias
    std::optional<TranslucentShadows> translucent_;  // its pass; pipelines when some caster is translucent
    lab::Handle<VkSampler> nearest_sampler_, compare_sampler_;
    std::vector<Map> maps_;          // one per shadow slot, in slot order
    Map stand_in_2d_, stand_in_cube_;  // 1×1, cleared: what unused slots' descriptors point at
    std::vector<int> layout_;  // layout_of() the lighting the maps were made for
    int renders_ = 0;
    int rendered_last_ = 0;
    glm::dmat4 camera_{0.0};  // the picture the maps were last sized for (record())
    VkExtent2D picture_{0, 0};
};
