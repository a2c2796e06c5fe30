// gpu_mesh.h — a mesh in device-local vertex and index buffers, and binding it for a draw.
#pragma once

#include "bounds.h"
#include "buffer.h"
#include "mesh.h"

namespace lab {

struct GpuMesh {
    Buffer vertices;  // lab::Vertex, binding 0
    Buffer indices;   // uint32_t
    uint32_t index_count = 0;
    Box bounds;  // of the vertex positions, in model space (lab 4 fits shadow maps to them)
};

GpuMesh upload_mesh(const VulkanContext& vk, const Mesh& mesh);
// Binds the vertex buffer at binding 0 and the index buffer; then vkCmdDrawIndexed(index_count).
void bind_mesh(VkCommandBuffer cmd, const GpuMesh& mesh);

}  // namespace lab
