#include "renderer.h"

#include "mesh.h"
#include "shader.h"

#include <algorithm>
#include <cstring>

namespace {
// Objects that share a mesh (and its tessellation) share one GPU copy.
std::string mesh_key(const lab::ObjectDesc& object) {
    return (object.mesh_path.empty() ? object.mesh : object.mesh_path) + "|" + std::to_string(object.segments) + "|" +
           std::to_string(object.rings) + "|" + std::to_string(object.crease_deg) + "|" + std::to_string(object.normalize) + "|" +
           std::to_string(object.obj_material);
}
}  // namespace

Renderer::Renderer(const lab::VulkanContext& vk, const lab::RenderTarget& target, const lab::Scene& scene,
                   const std::string& shader_dir)
    : vk_(vk) {
    // Geometry: upload each distinct mesh once, remember what to draw.
    lab::MeshLibrary library;  // reads each model file once
    for (const lab::ObjectDesc& object : scene.objects) {
        const std::string key = mesh_key(object);
        auto it = meshes_.find(key);
        if (it == meshes_.end()) {
            it = meshes_.emplace(key, lab::upload_mesh(vk, library.mesh(object))).first;
        }
        const lab::MaterialDesc& material = scene.materials.at(object.material);
        items_.push_back({&it->second, {lab::model_matrix(object), glm::vec4(material.albedo, 1.0f)}});
        items_.back().box = lab::transformed(it->second.bounds, glm::dmat4(items_.back().constants.model));  // world space
    }

    // One uniform buffer + descriptor set per frame in flight, so the CPU can
    // write frame N+1's camera while the GPU still reads frame N's.
    const std::vector<lab::DescriptorBinding> bindings = {
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_VERTEX_BIT}};
    set_layout_ = lab::make_descriptor_set_layout(vk, bindings);
    pool_ = lab::make_descriptor_pool(vk, bindings, lab::RenderTarget::kFramesInFlight);
    for (uint32_t slot = 0; slot < lab::RenderTarget::kFramesInFlight; ++slot) {
        uniforms_.push_back(lab::Buffer::host_visible(vk, sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT));
        sets_.push_back(lab::allocate_descriptor_set(vk, pool_, set_layout_));
        lab::write_buffer_descriptor(vk, sets_.back(), 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniforms_.back().get(),
                                     sizeof(FrameUniforms));
    }

    vertex_shader_ = lab::load_shader(vk, shader_dir, "unlit.vert");
    fragment_shader_ = lab::load_shader(vk, shader_dir, "unlit.frag");
    pipeline_ = lab::PipelineBuilder()
                    .shaders(vertex_shader_, fragment_shader_)
                    .vertex_attributes(lab::kPosition)
                    .descriptor_set(set_layout_)
                    .push_constants(VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, sizeof(ObjectConstants))
                    .build(vk, target.render_pass());
}

void Renderer::draw(const lab::Frame& frame, const glm::mat4& view, const glm::mat4& projection) {
    const FrameUniforms uniforms{view, projection};
    std::memcpy(uniforms_[frame.slot].mapped(), &uniforms, sizeof uniforms);

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
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.layout, 0, 1, &sets_[frame.slot], 0, nullptr);
    const lab::GpuMesh* bound = nullptr;
    for (const DrawItem& item : items_) {
        if (item.mesh != bound) {  // objects sharing a mesh skip the rebind
            lab::bind_mesh(cmd, *item.mesh);
            bound = item.mesh;
        }
        vkCmdPushConstants(cmd, pipeline_.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(ObjectConstants), &item.constants);
        vkCmdDrawIndexed(cmd, item.mesh->index_count, 1, 0, 0, 0);
    }
}
