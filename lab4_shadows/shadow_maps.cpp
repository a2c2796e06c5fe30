#include "shadow_maps.h"

#include "caster_detail.h"
#include "map_footprint.h"
#include "shader.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace {
// Pushed with each caster (shadow.vert, translucent_shadow.frag).
struct ShadowConstants {
    glm::mat4 light_mvp;
    glm::vec4 transmittance;  // x: 1 − opacity
};
constexpr VkShaderStageFlags kBoth = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
// No map larger than this many texels in all (a cube: six faces): 1 GiB of 32-bit depth.
constexpr double kMaxTexels = 268435456.0;

// A depth-bias clamp rounded down to eight steps per octave (a bound stays a bound). Why: lavapipe
// compiles its triangle setup (LLVM) for each distinct constant / slope / clamp triple it meets and
// keeps 64 of them; a clamp that changed with every move of a light cost one compile per caster per
// frame (the default scene's point light: 28 of its 29 ms; swlike's map ≈ 13 ms). On the grid the
// values repeat, so a moving light finds them compiled.
float on_grid(double clamp) { return clamp > 0.0 ? float(std::exp2(std::floor(std::log2(clamp) * 8.0) / 8.0)) : 0.0f; }

bool translucent_material(const Lighting& lighting, uint32_t material) { return lighting.materials[material].opacity < 1.0f; }

// What the images depend on: each shadow-casting light's index, type and resolution; whether
// the transmittance maps' layers (the last number).
std::vector<int> layout_of(const Lighting& lighting) {
    std::vector<int> layout;
    const std::vector<int> slots = lighting.shadow_slots();
    for (size_t i = 0; i < lighting.lights.size(); ++i)
        if (slots[i] >= 0)
            layout.insert(layout.end(), {int(i), int(lighting.lights[i].type), uses_cube_map(lighting.lights[i]),
                                         lighting.lights[i].shadow.resolution});
    layout.push_back(lighting.translucent_layers);
    return layout;
}
}  // namespace

ShadowMaps::ShadowMaps(const lab::VulkanContext& vk, std::vector<Caster> objects, const Lighting& lighting,
                       const std::string& shader_dir)
    : vk_(vk), objects_(std::move(objects)) {
    for (const Caster& c : objects_) receiver_boxes_.push_back(c.box);
    // 32-bit float depth where the device samples it (precision for perspective maps), else 16-bit.
    // Cube maps' bilinear filter needs a depth format the device filters (lavapipe: none): else nearest.
    const VkFormatFeatureFlags depth_use = VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
    depth_format_ = format_supports(vk, VK_FORMAT_D32_SFLOAT, depth_use) ? VK_FORMAT_D32_SFLOAT : VK_FORMAT_D16_UNORM;
    const bool linear = format_supports(vk, depth_format_, depth_use | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT);

    depth_pass_ = make_offscreen_pass(vk, VK_FORMAT_UNDEFINED, depth_format_);
    // Two optional features the maps use (README "Near and far", "Bias"): without them the maps
    // are still drawn, and the lab says once what they lose.
    const std::vector<int> casting = lighting.shadow_slots();
    if (std::any_of(casting.begin(), casting.end(), [](int slot) { return slot >= 0; })) {
        if (!vk.enabled_features().depthClamp)
            std::fprintf(stderr, "warning: no depthClamp on this device: a caster nearer a light than its map's near "
                                 "plane (far / 1000) casts no shadow\n");
        if (!vk.enabled_features().depthBiasClamp)
            std::fprintf(stderr, "warning: no depthBiasClamp on this device: the shadow maps' depth bias is not "
                                 "bounded (a huge bias or an edge-on caster can lose its shadow)\n");
    }
    nearest_sampler_ = make_depth_sampler(vk, false, false);
    compare_sampler_ = make_depth_sampler(vk, linear, true);

    // Opaque casters: depth only — position-only vertex input, no fragment shader, no colour.
    const lab::Handle<VkShaderModule> vertex_shader = lab::load_shader(vk, shader_dir, "shadow.vert");
    lab::PipelineBuilder casters;  // what every shadow pipeline shares
    casters.vertex_attributes(lab::kPosition).push_constants(kBoth, sizeof(ShadowConstants));
    // Depth clamp: a caster in front of the near plane is drawn at depth 0 instead of clipped
    // away (light_frustum.cpp keeps near/far ≥ 1e-3 for precision). Without the feature such a
    // caster is lost.
    opaque_ = lab::PipelineBuilder(casters)
                  .shaders(vertex_shader, VK_NULL_HANDLE)
                  .cull(VK_CULL_MODE_NONE)  // a plane casts from either side
                  .color_attachments(0)
                  .dynamic_depth_bias()
                  .depth_clamp(vk.enabled_features().depthClamp)
                  .build(vk, depth_pass_);
    // The second lesson: transmittance maps beside the depth maps (translucent_shadows.cpp), with
    // as many layers as a ray can cross translucent faces.
    translucent_.emplace(vk, depth_format_, uint32_t(lighting.translucent_layers), casters, vertex_shader, shader_dir);

    const std::vector<int> slots = lighting.shadow_slots();
    for (size_t i = 0; i < lighting.lights.size(); ++i) {
        if (slots[i] < 0) continue;
        const bool cube = uses_cube_map(lighting.lights[i]);
        maps_.push_back(make_map(int(i), cube, clamp_resolution(lighting.lights[i].shadow.resolution, cube), translucent_->active()));
    }
    layout_ = layout_of(lighting);
    // Unused slots read 1×1 maps that say "lit"; cleared once, here, into the layouts they are read in.
    stand_in_2d_ = make_map(-1, false, 1, true);
    stand_in_cube_ = make_map(-1, true, 1, true);
    vk.run_once([&](VkCommandBuffer cmd) {
        for (const Map* m : {&stand_in_2d_, &stand_in_cube_}) {
            m->depth.clear(cmd);
            m->translucent.transmittance.clear(cmd);
        }
    });
}

uint32_t ShadowMaps::clamp_resolution(int requested, bool cube) const {
    const VkPhysicalDeviceLimits& limits = vk_.properties().limits;
    const uint32_t most = std::min({cube ? limits.maxImageDimensionCube : limits.maxImageDimension2D, limits.maxFramebufferWidth,
                                    limits.maxFramebufferHeight, uint32_t(std::sqrt(kMaxTexels / (cube ? 6.0 : 1.0)))});
    const uint32_t resolution = std::clamp(uint32_t(std::max(requested, 1)), 1u, most);
    if (resolution != uint32_t(requested))
        std::fprintf(stderr, "warning: shadow map resolution %d: at most %u here (%s), using %u\n", requested, most,
                     cube ? "cube faces, six of them" : "the device's limit or 2^28 texels", resolution);
    return resolution;
}

ShadowMaps::Map ShadowMaps::make_map(int light, bool cube, uint32_t resolution, bool translucent) const {
    Map m;
    m.light = light;
    m.cube = cube;
    const VkImageUsageFlags sampled_depth = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    m.depth = create_layered_target(vk_, depth_pass_, resolution, cube, depth_format_, sampled_depth, VK_IMAGE_ASPECT_DEPTH_BIT);
    if (translucent) m.translucent = translucent_->make_map(resolution, cube);
    return m;
}

// 3: GpuShadows; per slot: 4, 5: 2D depth (nearest, comparison), 6, 7: cube depth (nearest,
// comparison; the faces as a 2D array), 8, 9: transmittance (2D, cube faces).
std::vector<lab::DescriptorBinding> ShadowMaps::bindings() {
    std::vector<lab::DescriptorBinding> bindings = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kBoth}};
    bindings.resize(7, {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kBoth, kMaxShadowLights});
    return bindings;
}

void ShadowMaps::write_descriptors(VkDescriptorSet set, VkBuffer uniforms) const {
    lab::write_buffer_descriptor(vk_, set, 3, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniforms, sizeof(GpuShadows));
    const VkImageLayout depth = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, color = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    for (uint32_t binding = 4; binding <= 9; ++binding) {
        const bool cube = binding == 6 || binding == 7 || binding == 9;
        const Map& stand_in = cube ? stand_in_cube_ : stand_in_2d_;
        std::vector<VkDescriptorImageInfo> infos;  // [slot]
        for (int slot = 0; slot < kMaxShadowLights; ++slot) {
            const Map* m = slot < int(maps_.size()) && maps_[slot].cube == cube ? &maps_[slot] : &stand_in;
            if (binding >= 8 && !translucent_->active()) m = &stand_in;
            const VkSampler sampler = binding == 5 || binding == 7 ? compare_sampler_.get() : nearest_sampler_.get();
            infos.push_back(binding >= 8 ? VkDescriptorImageInfo{sampler, m->translucent.transmittance.sampled(), color}
                                         : VkDescriptorImageInfo{sampler, m->depth.sampled(), depth});
        }
        lab::write_image_descriptors(vk_, set, binding, infos);
    }
}

std::string ShadowMaps::drawn() const {
    std::string text;
    for (const Map& m : maps_)
        text += (text.empty() ? "" : ", ") + std::string(m.cube ? "cube " : "") + "light " + std::to_string(m.light) + ": " +
                std::to_string(m.used) + " of " + std::to_string(m.depth.size);
    return text;
}

std::string ShadowMaps::triangles() const {
    const auto k = [](uint64_t n) {
        char text[32];
        std::snprintf(text, sizeof text, n < 10000 ? "%.0f" : "%.1f k", n < 10000 ? double(n) : double(n) / 1000.0);
        return std::string(text);
    };
    std::string text;
    for (const Map& m : maps_)
        text += (text.empty() ? "" : ", ") + std::string(m.cube ? "cube " : "") + "light " + std::to_string(m.light) + ": " +
                k(m.triangles) + " of " + k(m.own_triangles);
    return text;
}

bool ShadowMaps::matches(const Lighting& lighting) const { return layout_of(lighting) == layout_; }

void ShadowMaps::draw_view(DepthView& view, VkCommandBuffer cmd, int slot, VkExtent2D extent) const {
    if (slot < 0 || slot >= int(maps_.size())) return;
    view.draw(cmd, maps_[size_t(slot)].depth, maps_[size_t(slot)].clip_to_view, extent, maps_[size_t(slot)].used);
}

// Change tracking: everything a map depends on, as numbers. The light's placement and the
// shadow pass's settings, then each caster the light can reach: its transform and opacity.
// (Objects cannot move in this lab; the transform makes the rule hold when they can.)
std::vector<float> ShadowMaps::key_of(const lab::LightDesc& light, const Lighting& lighting) const {
    std::vector<float> key = {float(light.type),        light.position.x, light.position.y, light.position.z,
                              light.direction.x,        light.direction.y, light.direction.z, light.outer_deg,
                              light.shadow.bias,        light.shadow.slope_bias};
    for (const Caster& c : objects_) {
        if (!c.casts) continue;
        if (light.type == lab::LightDesc::Type::Spot &&
            !in_spot_cone(c.box, glm::dvec3(light.position), glm::dvec3(light.direction), light.outer_deg))
            continue;
        const float* m = &c.model[0][0];
        key.insert(key.end(), m, m + 16);
        key.push_back(lighting.materials[c.material].opacity);
    }
    return key;
}

void ShadowMaps::record(VkCommandBuffer cmd, const Lighting& lighting, const glm::dmat4& camera, VkExtent2D picture,
                        GpuShadows* out, lab::PassTimer* timer) {
    *out = GpuShadows{};
    rendered_last_ = 0;
    // Where the picture shows receivers, and how wide its pixels are there (maps that follow the
    // view), worked out again only when the camera or the picture's size moved, or a map changed.
    const bool moved = camera != camera_ || picture.width != picture_.width || picture.height != picture_.height;
    camera_ = camera;
    picture_ = picture;
    std::vector<ViewSample> view;
    bool sampled = false;
    for (size_t slot = 0; slot < maps_.size(); ++slot) {
        Map& map = maps_[slot];
        const lab::LightDesc& light = lighting.lights[size_t(map.light)];
        std::vector<float> key = key_of(light, lighting);
        const bool changed = key != map.key;  // the light or a caster in its volume changed (or never rendered)
        if (changed) {
            map.in_map = casters_for(light, lighting);
            map.frustum = fit(light, map.cube, map.in_map);
        }
        // The texels the picture needs (README "Maps sized to the picture"), or all of them.
        uint32_t used = map.depth.size;
        if (light.shadow.fit_to_view && map.fitted && !moved && !changed) {
            used = map.used;
        } else if (light.shadow.fit_to_view) {
            if (!sampled) view = sample_view(camera, picture.width, picture.height, receiver_boxes_);
            sampled = true;
            std::vector<FootprintCaster> casters;
            for (size_t i = 0; i < objects_.size(); ++i)
                if (map.in_map[i])
                    casters.push_back({objects_[i].box, int(i), shadows_itself(i, lighting)});
            const bool directional = light.type == lab::LightDesc::Type::Directional;
            const double texels = texels_needed(map.frustum, view, casters, glm::dvec3(directional ? light.direction : light.position),
                                                directional);
            used = footprint_resolution(texels, map.depth.size, map.used);
        }
        map.fitted = light.shadow.fit_to_view;
        if (changed || used != map.used) {
            map.used = used;
            render(cmd, map, light, lighting, timer);
            map.key = std::move(key);
            ++renders_;
            ++rendered_last_;
        }
        // Only the lookup's numbers: the map still holds what they describe.
        (*out)[slot] = map.gpu;
        (*out)[slot].params.x *= light.shadow.normal_offset / float(map.used);
    }
}

// Draws the map's casters (`in_map`, casters_for) into the current pass: opaque ones with the
// bound depth-only pipeline and the light's depth bias, at most `most_bias[i]` for caster i, or
// (translucent, no `most_bias`) the translucent ones into transmittance layer `layer`.
// `meshes` (optional): the tessellation to draw of each caster (caster_detail.h), else its own.
void ShadowMaps::draw_casters(VkCommandBuffer cmd, const glm::dmat4& world_to_clip, const Lighting& lighting,
                              bool translucent, const std::vector<bool>& in_map, const lab::ShadowDesc* bias,
                              const std::vector<float>& most_bias, uint32_t layer,
                              const std::vector<const lab::GpuMesh*>* meshes) const {
    const lab::GpuMesh* bound = nullptr;
    for (size_t i = 0; i < objects_.size(); ++i) {
        const Caster& c = objects_[i];
        if (!in_map[i] || translucent_material(lighting, c.material) != translucent) continue;
        const ShadowConstants constants{glm::mat4(world_to_clip * glm::dmat4(c.model)),
                                        glm::vec4(1.0f - lighting.materials[c.material].opacity, float(layer),
                                                  translucent_->peel_slack(), 0.0f)};
        const lab::GpuMesh* mesh = meshes ? (*meshes)[i] : c.mesh;
        if (mesh != bound) {
            lab::bind_mesh(cmd, *mesh);
            bound = mesh;
        }
        vkCmdPushConstants(cmd, opaque_.layout, kBoth, 0, sizeof constants, &constants);
        if (bias) vkCmdSetDepthBias(cmd, bias->bias, most_bias[i], bias->slope_bias);
        vkCmdDrawIndexed(cmd, mesh->index_count, 1, 0, 0, 0);
    }
}

// Can object i shadow itself? Not when it is convex and opaque: it shadows only its own unlit side.
bool ShadowMaps::shadows_itself(size_t i, const Lighting& lighting) const {
    return !objects_[i].convex || translucent_material(lighting, objects_[i].material);
}

// Which objects a light's map holds (per object): those with cast_shadows, inside a spot's cone,
// that can shadow a receiver — another object, or themselves when their mesh is not convex or
// they are translucent (an opaque convex object shadows only its own unlit side; through a
// translucent one the camera sees its inner far faces, which its near faces shadow). The map is
// fitted to them and draws only them: a floor under everything would only spread the texels and
// cost a draw.
std::vector<bool> ShadowMaps::casters_for(const lab::LightDesc& light, const Lighting& lighting) const {
    const glm::dvec3 position(light.position), direction(light.direction);
    const bool directional = light.type == lab::LightDesc::Type::Directional, spot = light.type == lab::LightDesc::Type::Spot;
    std::vector<bool> in_map(objects_.size(), false);
    for (size_t i = 0; i < objects_.size(); ++i) {
        const Box& c = objects_[i].box;
        if (!objects_[i].casts || (spot && !in_spot_cone(c, position, direction, light.outer_deg))) continue;
        for (size_t j = 0; j < objects_.size() && !in_map[i]; ++j)
            if (i != j || shadows_itself(i, lighting))
                in_map[i] = directional ? can_shadow(c, objects_[j].box, direction) : can_shadow_from(c, objects_[j].box, position);
    }
    return in_map;
}

LightFrustum ShadowMaps::fit(const lab::LightDesc& light, bool cube, const std::vector<bool>& in_map) const {
    const glm::dvec3 position(light.position), direction(light.direction);
    std::vector<Box> casters;
    for (size_t i = 0; i < objects_.size(); ++i)
        if (in_map[i]) casters.push_back(objects_[i].box);
    if (light.type == lab::LightDesc::Type::Directional) return fit_directional(direction, casters, receiver_boxes_);
    if (!cube) return fit_spot(position, direction, light.outer_deg, casters);
    return fit_point(position, casters);  // a point light, or a spot too wide for one map
}

// Draws the map's used² texels (record() has fitted it: map.in_map, map.frustum, map.used).
void ShadowMaps::render(VkCommandBuffer cmd, Map& map, const lab::LightDesc& light, const Lighting& lighting,
                        lab::PassTimer* timer) {
    const std::vector<bool>& in_map = map.in_map;
    const LightFrustum& f = map.frustum;
    const uint32_t used = map.used;
    const bool perspective = light.type != lab::LightDesc::Type::Directional;
    map.gpu.view_projection = glm::mat4(f.view_projection);
    map.gpu.origin = glm::vec4(glm::vec3(f.origin), 1.0f);
    // x: one texel's world size (at distance 1 for perspective maps); record() scales it by
    // normal_offset / used. y, z: a perspective map's two depth constants, with which the cube
    // lookup turns P's distance along a face's axis into the depth that face stored
    // (LightFrustum::depth_a(), depth_b()). w: the texels per side drawn, a square at the image's corner.
    map.gpu.params = glm::vec4(float(f.texel), perspective ? float(f.depth_a()) : 0.0f, perspective ? float(f.depth_b()) : 0.0f,
                               float(used));
    // The map view's way back from depth to distance: a 90° projection with the map's planes,
    // inverted (the field of view does not change the depth on the axis: a spot's map uses it too).
    map.clip_to_view = perspective ? glm::mat4(glm::inverse(glm::perspectiveRH_ZO(glm::radians(90.0), 1.0, f.near_plane, f.far_plane)))
                                   : glm::mat4(1.0f);
    // Depth bias: constant (in units of the depth format's smallest step) + slope-scaled (grows
    // with how steeply the triangle's depth changes across a texel), both as the device computes
    // them, so bounded in world units (depthBiasClamp, README "Bias"): at most max(1, slope_bias)
    // texels along the light at each caster, what the slope bias gives a face at 45°. Unbounded, a
    // device's bias can push a whole caster to the far end of the map (depth clamp: 1, no caster):
    // a thin caster seen edge-on (huge slope), a triangle crossing the light's plane (a float
    // map's unit is 2^(e − 23), e from the triangle's depth range: unbounded there).
    std::vector<float> most_bias(objects_.size(), 0.0f);
    const double most_texels = std::max(1.0, double(light.shadow.slope_bias));
    if (vk_.enabled_features().depthBiasClamp)
        for (size_t i = 0; i < objects_.size(); ++i)
            if (in_map[i]) most_bias[i] = on_grid(f.depth_of_texels(objects_[i].box, most_texels / used));
    // Opaque casters at the detail the map resolves (caster_detail.h): the coarsest tessellation
    // within half a texel of the true surface at the caster, as the camera's mesh is. Translucent
    // casters keep their own: a receiver on one is told from the faces in front of it by depth
    // (translucent_shadows.cpp's tolerance), and a coarser face would sit deeper.
    std::vector<const lab::GpuMesh*> detail(objects_.size(), nullptr);
    map.triangles = map.own_triangles = 0;
    for (size_t i = 0; i < objects_.size(); ++i) {
        const Caster& c = objects_[i];
        detail[i] = c.mesh;
        if (!in_map[i] || translucent_material(lighting, c.material)) continue;
        if (!c.levels.empty()) {
            const size_t k = pick_level(c.errors, c.scale, half_texel(f, used, c.box));
            if (k > 0) detail[i] = c.levels[k - 1];
        }
        map.triangles += detail[i]->index_count / 3;
        map.own_triangles += c.mesh->index_count / 3;
    }
    // Translucent casters: how far behind the nearest one a receiver must be (translucent_shadows.cpp),
    // and their boxes, whose covered_texels() on each face are all its transmittance pass draws.
    map.gpu.translucent = glm::vec4(TranslucentShadows::tolerance(f, used), 0.0f, 0.0f, 0.0f);
    std::vector<Box> translucent;
    for (size_t i = 0; i < objects_.size(); ++i)
        if (in_map[i] && translucent_material(lighting, objects_[i].material)) translucent.push_back(objects_[i].box);

    // The panel's GPU time per map: "map: spot 1" (light 1), its transmittance map's beside it.
    const std::string pass = std::string("map: ") + lab::light_type_name(light.type) + " " + std::to_string(map.light);
    const std::string translucent_pass = "translucent " + pass;
    for (uint32_t face = 0; face < map.depth.layers(); ++face) {
        const glm::dmat4 world_to_clip = f.world_to_clip(map.cube ? f.faces[face] : f.view_projection);
        // Only the casters whose box reaches this face: a cube face sees a quarter of the scene or
        // less, and lavapipe pays for every triangle sent, on screen or not (2D maps are fitted to
        // their casters: all reach them, nothing to cull).
        std::vector<bool> in_face = in_map;
        for (size_t i = 0; map.cube && i < objects_.size(); ++i)
            if (in_face[i] && covered_texels(world_to_clip, {objects_[i].box}, used).extent.width == 0)
                in_face[i] = false;
        {
            const lab::TimedPass timed(timer, cmd, pass);
            // The used² square, and beside it, cleared to "nothing there", as many texels as a
            // PCF footprint reaches past the edge (15 × 15 bilinear: 8): what the sampler's border
            // gives where the image ends.
            const uint32_t cleared = std::min(map.depth.size, used + 8);
            map.depth.begin(cmd, face, 1.0f, VkRect2D{{0, 0}, {cleared, cleared}}, used);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, opaque_.pipeline);
            draw_casters(cmd, world_to_clip, lighting, false, in_face, &light.shadow, most_bias, 0, &detail);
            vkCmdEndRenderPass(cmd);
        }
        if (translucent_->active()) {
            const lab::TimedPass timed(timer, cmd, translucent_pass);
            translucent_->render(cmd, map.translucent, face, map.cube,
                                 covered_texels(world_to_clip, translucent, used), used,
                                 [&](uint32_t layer) { draw_casters(cmd, world_to_clip, lighting, true, in_face, nullptr, {}, layer); });
        }
    }
}
