#include "renderer.h"

#include "caster_detail.h"
#include "mesh.h"
#include "shader.h"
#include "texture_image.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace {
// Objects that share a mesh (and its tessellation) share one GPU copy.
std::string mesh_key(const lab::ObjectDesc& object) {
    return (object.mesh_path.empty() ? object.mesh : object.mesh_path) + "|" + std::to_string(object.segments) + "|" +
           std::to_string(object.rings) + "|" + std::to_string(object.crease_deg) + "|" + std::to_string(object.normalize) + "|" +
           std::to_string(object.obj_material);
}

// Normals transform with the normal matrix, which keeps them perpendicular to the surface under
// a non-uniform scale (the model's own 3×3 part does not). Computed in double; scaled so
// its largest element is ±1 (only the direction matters: the shader renormalizes), which
// keeps float magnitudes near 1 even for scales of 1e-6 or 1e6.
void normal_matrix(const glm::mat4& model, glm::vec4 columns[3]) {
    // EXERCISE normal_matrix: the matrix n that turns normals from model to world space, still perpendicular to the surface: why not model's own 3×3 part under a non-uniform scale? A tangent t goes through that part M; n' must stay perpendicular to M t whenever n is to t: solve n'ᵀ(M t) = 0 for the matrix taking n to n'. Read docs/lighting.md "The default equation" (N), GLM's matrix functions. Wrong: turned objects lit as if unturned, squashed ones on the wrong slopes. Checked by Lab2Term.TurnedAndSquashedObjects, Lab2Render.DefaultScene, Lab2Render.EveryPrimitiveAndAModelLit.
    // STUB: glm::dmat3 n(1.0);  // identity: the normals do not turn with the object
    glm::dmat3 n = glm::transpose(glm::inverse(glm::dmat3(glm::dmat4(model))));
    // END EXERCISE
    double largest = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) largest = std::max(largest, std::abs(n[c][r]));
    if (largest > 0.0) n /= largest;
    for (int c = 0; c < 3; ++c) columns[c] = glm::vec4(glm::vec3(n[c]), 0.0f);
}
}  // namespace

Renderer::Renderer(const lab::VulkanContext& vk, const lab::RenderTarget& target, const lab::Scene& scene,
                   const Lighting& lighting, const std::string& shader_dir)
    : vk_(vk), render_pass_(target.render_pass()), samplers_(vk),
      shadow_view_(vk, target.render_pass(), 6 * kMaxShadowLights, shader_dir) {
    // Geometry: upload each distinct mesh once, remember what to draw.
    lab::MeshLibrary library;  // reads each model file once
    std::vector<Caster> casters;  // lab 4: what the shadow maps draw
    bool translucent = false;     // lab 4: does any object need the translucent layers?
    // Lab 4: per mesh, the coarser tessellations a map may draw and how far each is from the
    // true surface (caster_detail.h), made once here.
    std::map<std::string, std::pair<std::vector<const lab::GpuMesh*>, std::vector<double>>> details;
    for (const lab::ObjectDesc& object : scene.objects) {
        const std::string key = mesh_key(object);
        auto it = meshes_.find(key);
        // (a mesh may be here already as another object's coarser level, without levels of its own)
        if (it == meshes_.end() || !details.count(key)) {
            const lab::Mesh mesh = library.mesh(object);
            if (it == meshes_.end()) it = meshes_.emplace(key, lab::upload_mesh(vk, mesh)).first;
            auto& [levels, errors] = details[key];
            for (const lab::ObjectDesc& level : coarser_levels(object)) {
                if (errors.empty()) errors.push_back(surface_error(object.mesh, mesh));
                const lab::Mesh coarse = library.mesh(level);
                auto at = meshes_.find(mesh_key(level));
                if (at == meshes_.end()) at = meshes_.emplace(mesh_key(level), lab::upload_mesh(vk, coarse)).first;
                levels.push_back(&at->second);
                errors.push_back(surface_error(level.mesh, coarse));
            }
        }
        const lab::MaterialDesc& material = scene.materials.at(object.material);
        items_.push_back({&it->second, {lab::model_matrix(object), glm::vec4(material.albedo, 1.0f)}});
        items_.back().box = lab::transformed(it->second.bounds, glm::dmat4(items_.back().constants.model));  // world space
        // Lit: the normal matrix and the material's index instead of its colour.
        LitConstants& lit = items_.back().lit;
        lit.model = items_.back().constants.model;
        normal_matrix(lit.model, lit.normal_matrix);
        lit.material = uint32_t(lighting.material_index(object.material));
        translucent = translucent || lighting.materials[lit.material].opacity < 1.0f;
        const glm::mat3 axes(lit.model);  // object units → world: at most the longest axis
        const double scale = std::max({glm::length(axes[0]), glm::length(axes[1]), glm::length(axes[2])});
        const auto& [levels, errors] = details[key];
        casters.push_back({&it->second, lit.model, items_.back().box, lit.material, object.cast_shadows, Lighting::convex(object),
                           levels, errors, scale});
    }
    // Lab 4: the layers' lists are written by fragment shaders, an optional feature
    // (fragmentStoresAndAtomics). Without it translucent objects are drawn opaque, and the lab
    // says so; their shadows (transmittance maps: colour attachments only) still let light through.
    if (translucent && !vk.enabled_features().fragmentStoresAndAtomics) {
        translucent = false;
        std::fprintf(stderr, "warning: no fragmentStoresAndAtomics on this device: translucent objects are drawn "
                             "opaque (their shadows still let light through)\n");
    }
    shadow_maps_ = std::make_unique<ShadowMaps>(vk, std::move(casters), lighting, shader_dir);
    // Light markers: a cube per point light, a cone per spot and directional light.
    for (const auto& [key, mesh] : {std::pair<std::string, lab::Mesh>{"marker|cube", lab::make_cube()},
                                    std::pair<std::string, lab::Mesh>{"marker|cone", lab::make_cone(16)}})
        meshes_.emplace(key, lab::upload_mesh(vk, mesh));

    // One uniform buffer + descriptor set per frame in flight, so the CPU can
    // write frame N+1's camera while the GPU still reads frame N's. The same for
    // the lights (a storage buffer) and the materials (a uniform buffer).
    const VkShaderStageFlags both = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    std::vector<lab::DescriptorBinding> bindings = {
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, both},   // the fragment shader needs the camera position
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, both},   // lights (Gouraud reads them in the vertex shader)
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, both}};  // materials
    for (const lab::DescriptorBinding& b : ShadowMaps::bindings()) bindings.push_back(b);  // lab 4: 3..9
    if (translucent) {  // lab 4: 10..13, the translucent layers' lists (translucent_layers.glsl)
        if (bindings.size() != TranslucentLayers::kFirstBinding)
            throw std::logic_error("set 0: the translucent layers' bindings must follow the shadow maps' at " +
                                   std::to_string(TranslucentLayers::kFirstBinding));
        for (const lab::DescriptorBinding& b : TranslucentLayers::bindings()) bindings.push_back(b);
    }
    set_layout_ = lab::make_descriptor_set_layout(vk, bindings);
    pool_ = lab::make_descriptor_pool(vk, bindings, lab::RenderTarget::kFramesInFlight);
    if (translucent)
        layers_ = std::make_unique<TranslucentLayers>(vk, target.extent(), target.render_pass(), set_layout_, shader_dir);
    const VkDeviceSize material_bytes = kMaxMaterials * sizeof(GpuMaterial);
    for (uint32_t slot = 0; slot < lab::RenderTarget::kFramesInFlight; ++slot) {
        uniforms_.push_back(lab::Buffer::host_visible(vk, sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT));
        lights_.push_back(lab::Buffer::host_visible(vk, sizeof(GpuLights), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT));
        materials_.push_back(lab::Buffer::host_visible(vk, material_bytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT));
        sets_.push_back(lab::allocate_descriptor_set(vk, pool_, set_layout_));
        lab::write_buffer_descriptor(vk, sets_.back(), 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniforms_.back().get(),
                                     sizeof(FrameUniforms));
        lab::write_buffer_descriptor(vk, sets_.back(), 1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, lights_.back().get(),
                                     sizeof(GpuLights));
        lab::write_buffer_descriptor(vk, sets_.back(), 2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, materials_.back().get(),
                                     material_bytes);
        shadows_.push_back(lab::Buffer::host_visible(vk, sizeof(GpuShadows), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT));
        shadow_maps_->write_descriptors(sets_.back(), shadows_.back().get());
        if (layers_) layers_->write_descriptors(sets_.back(), slot);
    }

    vertex_shader_ = lab::load_shader(vk, shader_dir, "unlit.vert");
    fragment_shader_ = lab::load_shader(vk, shader_dir, "unlit.frag");
    pipeline_ = lab::PipelineBuilder()
                    .shaders(vertex_shader_, fragment_shader_)
                    .vertex_attributes(lab::kPosition)
                    .descriptor_set(set_layout_)
                    .push_constants(VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, sizeof(ObjectConstants))
                    .build(vk, target.render_pass());
    lit_vertex_shader_ = lab::load_shader(vk, shader_dir, "lit.vert");
    lit_fragment_shader_ = lab::load_shader(vk, shader_dir, "lit.frag");
    textured_fragment_shader_ = lab::load_shader(vk, shader_dir, "textured.frag");
    if (layers_) {  // lab 4: lit.frag and textured.frag that store layers instead of writing colour
        layer_fragment_shader_ = lab::load_shader(vk, shader_dir, "lit_layer.frag");
        textured_layer_fragment_shader_ = lab::load_shader(vk, shader_dir, "textured_layer.frag");
    }
    load_textures(lighting);
    lit_pipeline(variant_of(lighting));  // the scene's own variant, built up front
}

// Each map image is loaded once, and an upload is kept for each image and format (format_of
// decides a map's), however many materials use it, with a mip chain if any of them samples mipmaps. A bad file
// becomes the checkerboard and one warning line.
void Renderer::load_textures(const Lighting& lighting) {
    const VkFormat formats[3] = {format_of(MapKind::Albedo), format_of(MapKind::Specular), format_of(MapKind::Emissive)};
    std::map<TextureKey, bool> mipmaps;  // [map, format]: does any material want its mip chain?
    uint32_t textured = 0;
    for (const lab::MaterialDesc& m : lighting.materials) {
        textured += m.has_maps();
        const std::string* maps[3] = {&m.albedo_map, &m.specular_map, &m.emissive_map};
        for (int i = 0; i < 3; ++i)
            if (!maps[i]->empty()) mipmaps[{*maps[i], formats[i]}] |= m.sampler.mipmaps != lab::SamplerDesc::Mipmaps::None;
    }
    for (const auto& [key, mips] : mipmaps) {
        const lab::TextureLoad load = lab::load_texture_image(key.first, int(vk_.properties().limits.maxImageDimension2D));
        if (!load.warning.empty()) warnings_.push_back(load.warning);
        if (!load.warning.empty()) std::fprintf(stderr, "warning: %s\n", load.warning.c_str());
        textures_.emplace(key, upload_texture(vk_, load.image, mips, MipSource::Auto, key.second));
    }
    if (textured > 0) {
        white_ = upload_texture(vk_, lab::Image8{1, 1, {255, 255, 255, 255}}, false);
        // Set 1: a material's three maps, each a combined image sampler the fragment shader reads.
        const std::vector<lab::DescriptorBinding> maps(3, {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT});
        texture_layout_ = lab::make_descriptor_set_layout(vk_, maps);
        texture_pool_ = lab::make_descriptor_pool(vk_, maps, textured);
    }
    bool any_auto = false;
    for (const lab::MaterialDesc& m : lighting.materials) {
        material_sets_.push_back(VK_NULL_HANDLE);
        // "anisotropic": "auto" becomes probes or the sampler's anisotropy for this device.
        any_auto |= m.has_maps() && m.sampler.anisotropic == lab::SamplerDesc::Anisotropic::Auto;
        const lab::SamplerDesc sampler = samplers_.resolve(m.sampler);
        // probes: the shader's own anisotropic filter, its maximum a constant (0 = off: no cost)
        material_maps_.push_back({!m.albedo_map.empty(), !m.specular_map.empty(), !m.emissive_map.empty(), m.distorted,
                                  m.has_maps() ? sampler.probes() : 0});
        if (!m.has_maps()) continue;
        material_sets_.back() = lab::allocate_descriptor_set(vk_, texture_pool_, texture_layout_);
        // A combined image sampler is three things: the sampler (how to read; identical settings
        // share one VkSampler), the image view (what to read) and the layout the image will be in
        // when the shader reads it. One write per binding, all three in one update.
        const std::string* maps[3] = {&m.albedo_map, &m.specular_map, &m.emissive_map};
        VkDescriptorImageInfo images[3];
        VkWriteDescriptorSet writes[3];
        for (uint32_t binding = 0; binding < 3; ++binding) {
            const Texture& t = maps[binding]->empty() ? white_ : textures_.at({*maps[binding], formats[binding]});
            images[binding] = {samplers_.get(sampler), t.image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            writes[binding] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            writes[binding].dstSet = material_sets_.back();
            writes[binding].dstBinding = binding;  // albedo 0, specular 1, emissive 2 (lit.frag)
            writes[binding].descriptorCount = 1;
            writes[binding].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            writes[binding].pImageInfo = &images[binding];
        }
        vkUpdateDescriptorSets(vk_.device(), 3, writes, 0, nullptr);
    }
    warnings_.insert(warnings_.end(), samplers_.warnings().begin(), samplers_.warnings().end());
    if (textured > 0)
        std::printf("textures: %zu images, %zu samplers for %u materials with maps\n", textures_.size(),
                    samplers_.size(), textured);
    if (any_auto) std::printf("%s\n", samplers_.auto_choice().c_str());
}

void Renderer::draw_shadow_maps(const lab::Frame& frame, const glm::dmat4& camera, const Lighting& lighting) {
    if (shadow_maps_->maps() == 0) return;  // no light casts shadows: no pass at all
    shadow_maps_->record(frame.cmd, lighting, camera, frame.extent, static_cast<GpuShadows*>(shadows_[frame.slot].mapped()),
                         frame.timer);
}

void Renderer::clear_translucent_layers(const lab::Frame& frame) {
    if (!layers_) return;  // no translucent object: no lists
    if (frame.extent.width != layers_->extent().width || frame.extent.height != layers_->extent().height) {
        // A resized window: one list per pixel of the new size. The frame still in flight reads
        // the old lists, and every set points at them.
        VK_CHECK(vkDeviceWaitIdle(vk_.device()));
        layers_->resize(frame.extent);
        for (uint32_t slot = 0; slot < lab::RenderTarget::kFramesInFlight; ++slot) layers_->write_descriptors(sets_[slot], slot);
    }
    layers_->clear(frame.cmd, frame.slot);
}

void Renderer::draw(const lab::Frame& frame, const glm::mat4& view, const glm::mat4& projection,
                    const glm::vec3& camera_position, const Lighting& lighting) {
    const FrameUniforms uniforms{view, projection, glm::vec4(camera_position, 1.0f), lighting.ambient_radiance()};
    std::memcpy(uniforms_[frame.slot].mapped(), &uniforms, sizeof uniforms);
    const GpuLights lights = lighting.pack_lights();
    std::memcpy(lights_[frame.slot].mapped(), &lights, sizeof lights);
    lighting.pack_materials(static_cast<GpuMaterial*>(materials_[frame.slot].mapped()));

    // Nearest objects first. The depth test keeps the nearest surface whatever the order, but a
    // fragment that a later object covers was shaded for nothing. Drawn near to far, a hidden
    // fragment fails the depth test before its shader runs (early fragment tests), so a pixel is
    // shaded about once. The key is where each object reaches farthest from the eye, so a floor
    // under everything is drawn last. (The order decides a pixel only where two surfaces tie in
    // depth: the first drawn keeps it.)
    const glm::dmat4 world_to_view(view);
    for (DrawItem& item : items_) item.far_depth = lab::far_depth(item.box, world_to_view);  // once per object
    std::stable_sort(items_.begin(), items_.end(),
                     [](const DrawItem& a, const DrawItem& b) { return a.far_depth < b.far_depth; });

    VkCommandBuffer cmd = frame.cmd;
    if (lighting.lights.empty()) {
        draw_ambient_only(cmd, frame.slot, lighting);  // objects without maps
    }
    // Lab 4: opaque objects first; then the translucent ones (opacity < 1), in any order: every
    // fragment of either face in front of the opaque picture goes into its pixel's list, and the
    // lists, each sorted by depth, are composed over the opaque picture (translucent_layers.h).
    opaque_.clear();
    translucent_.clear();
    for (const DrawItem& item : items_)
        (layers_ && lighting.materials[item.lit.material].opacity < 1.0f ? translucent_ : opaque_).push_back(&item);
    draw_lit(cmd, frame.slot, lighting, lighting.lights.empty() ? Objects::TexturedOnly : Objects::All, opaque_,
             Pass::Opaque);
    if (!translucent_.empty()) {
        draw_lit(cmd, frame.slot, lighting, Objects::All, translucent_, Pass::Layers);
        const VkRect2D area = translucent_area(view, projection, frame.extent);
        if (area.extent.width > 0 && area.extent.height > 0) layers_->resolve(cmd, sets_[frame.slot], area);
    }
    if (lighting.options.markers) draw_markers(cmd, frame.slot, lighting);
    if (lighting.shadow_view >= 0 && lighting.shadow_view < int(lighting.lights.size()))  // lab 4: the shadow-map view
        shadow_maps_->draw_view(shadow_view_, cmd, lighting.shadow_slots()[size_t(lighting.shadow_view)], frame.extent);
}

void Renderer::draw_lit(VkCommandBuffer cmd, uint32_t slot, const Lighting& lighting, Objects objects,
                        const std::vector<const DrawItem*>& items, Pass pass) {
    Variant variant = variant_of(lighting);
    VkPipeline bound_pipeline = VK_NULL_HANDLE;
    VkDescriptorSet bound_maps = VK_NULL_HANDLE;
    const lab::GpuMesh* bound = nullptr;
    for (const DrawItem* drawn : items) {
        const DrawItem& item = *drawn;
        const VkDescriptorSet maps = material_sets_[item.lit.material];
        if (objects == Objects::TexturedOnly && !maps) continue;
        // The material's maps pick the pipeline (albedo_map … probes; the mip view only with maps).
        std::copy(material_maps_[item.lit.material].begin(), material_maps_[item.lit.material].end(),
                  variant.begin() + constant::albedo_map);
        variant[constant::mip_view] = maps ? int32_t(lighting.mip_view) : 0;
        const lab::PipelineBuilder::Result& pipeline = lit_pipeline(variant, pass);
        if (pipeline.pipeline != bound_pipeline) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.pipeline);
            if (!bound_pipeline)  // set 0 stays bound across the lit layouts (they share set 0)
                vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.layout, 0, 1, &sets_[slot], 0, nullptr);
            bound_pipeline = pipeline.pipeline;
            bound_maps = VK_NULL_HANDLE;
        }
        if (maps && maps != bound_maps) {
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.layout, 1, 1, &maps, 0, nullptr);
            bound_maps = maps;
        }
        if (item.mesh != bound) {  // objects sharing a mesh skip the rebind
            lab::bind_mesh(cmd, *item.mesh);
            bound = item.mesh;
        }
        vkCmdPushConstants(cmd, pipeline.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(LitConstants), &item.lit);
        vkCmdDrawIndexed(cmd, item.mesh->index_count, 1, 0, 0, 0);
    }
}

// The lighting model, the shading and the number of lights of each type are specialization
// constants: each combination is its own pipeline, built when first needed.
const lab::PipelineBuilder::Result& Renderer::lit_pipeline(const Variant& variant, Pass pass) {
    auto it = lit_pipelines_.find({variant, pass});
    if (it != lit_pipelines_.end()) return it->second;
    // Constant i of the shaders (constant_id = i) is variant[i]; booleans are 32-bit too.
    std::vector<VkSpecializationMapEntry> entries;
    for (uint32_t i = 0; i < variant.size(); ++i)
        entries.push_back({i, uint32_t(i * sizeof(int32_t)), sizeof(int32_t)});
    const VkSpecializationInfo specialization{uint32_t(entries.size()), entries.data(), sizeof(variant), variant.data()};
    const bool maps = variant[constant::albedo_map] || variant[constant::specular_map] || variant[constant::emissive_map];
    lab::PipelineBuilder builder;
    builder.shaders(lit_vertex_shader_, maps ? textured_fragment_shader_ : lit_fragment_shader_)
        .vertex_attributes(lab::kPosition | lab::kNormal | lab::kUv | lab::kTangent)
        .descriptor_set(set_layout_)
        .push_constants(VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, sizeof(LitConstants))
        .specialization(&specialization);
    if (maps) builder.descriptor_set(texture_layout_);  // set 1: the maps
    if (pass == Pass::Layers) {  // lab 4: both faces into the lists; depth tested, nothing written to the attachments
        builder.shaders(lit_vertex_shader_, maps ? textured_layer_fragment_shader_ : layer_fragment_shader_)
            .cull(VK_CULL_MODE_NONE)
            .depth(true, false)
            .color_blend(VkPipelineColorBlendAttachmentState{});  // colour write mask 0: the layers are stored, not drawn
    }
    return lit_pipelines_[{variant, pass}] = builder.build(vk_, render_pass_);
}

// Light markers, drawn unlit in the light's colour: a cube at a point light, a cone along a
// spot light's axis and along a directional light's direction.
void Renderer::draw_markers(VkCommandBuffer cmd, uint32_t slot, const Lighting& lighting) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.layout, 0, 1, &sets_[slot], 0, nullptr);
    for (const lab::LightDesc& light : lighting.lights) {
        const bool point = light.type == lab::LightDesc::Type::Point;
        const lab::GpuMesh& mesh = meshes_.at(point ? "marker|cube" : "marker|cone");
        // The cone's apex (+Y) points the way the light travels; a directional light's
        // arrow floats 3 units up-light of the origin.
        const glm::vec3 d = glm::length(light.direction) > 0.0f ? glm::normalize(light.direction) : glm::vec3(0, -1, 0);
        const glm::vec3 side = glm::normalize(glm::cross(std::abs(d.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0), d));
        const glm::vec3 position = light.type == lab::LightDesc::Type::Directional ? -3.0f * d : light.position;
        glm::mat4 model(glm::vec4(side, 0.0f), glm::vec4(d, 0.0f), glm::vec4(glm::cross(side, d), 0.0f),
                        glm::vec4(position, 1.0f));
        model = model * glm::mat4(glm::mat3(point ? 0.12f : 0.2f));
        const float brightest = std::max({light.color.r, light.color.g, light.color.b, 1e-6f});
        const ObjectConstants constants{model, glm::vec4(light.color / brightest, 1.0f)};
        lab::bind_mesh(cmd, mesh);
        vkCmdPushConstants(cmd, pipeline_.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(ObjectConstants), &constants);
        vkCmdDrawIndexed(cmd, mesh.index_count, 1, 0, 0, 0);
    }
}

// Speed: with no lights the equation is e + ambient·a, one constant colour per object, so lab
// 1's unlit pipeline draws it at lab 1's cost (no normals to interpolate, nothing per pixel).
void Renderer::draw_ambient_only(VkCommandBuffer cmd, uint32_t slot, const Lighting& lighting) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.layout, 0, 1, &sets_[slot], 0, nullptr);
    const glm::vec3 ambient = glm::vec3(lighting.ambient_radiance());
    const lab::GpuMesh* bound = nullptr;
    for (const DrawItem& item : items_) {
        if (material_sets_[item.lit.material]) continue;  // lab 3: textured objects are drawn lit
        if (layers_ && lighting.materials[item.lit.material].opacity < 1.0f) continue;  // lab 4: into the layers
        if (item.mesh != bound) {
            lab::bind_mesh(cmd, *item.mesh);
            bound = item.mesh;
        }
        const lab::MaterialDesc& m = lighting.materials[item.lit.material];
        const ObjectConstants constants{item.constants.model, glm::vec4(m.emissive + ambient * m.albedo, 1.0f)};
        vkCmdPushConstants(cmd, pipeline_.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(ObjectConstants), &constants);
        vkCmdDrawIndexed(cmd, item.mesh->index_count, 1, 0, 0, 0);
    }
}

// The rectangle of pixels the translucent objects' world boxes can cover (covered_texels() in
// offscreen.h, the same question the transmittance maps ask): where the resolve must run.
VkRect2D Renderer::translucent_area(const glm::mat4& view, const glm::mat4& projection, VkExtent2D extent) const {
    std::vector<Box> boxes;
    for (const DrawItem* item : translucent_) boxes.push_back(item->box);
    return covered_texels(glm::dmat4(projection) * glm::dmat4(view), boxes, extent);
}
