#include "gpu_mesh.h"

namespace lab {

GpuMesh upload_mesh(const VulkanContext& vk, const Mesh& mesh) {
    return GpuMesh{Buffer::device_local(vk, mesh.vertices.data(), mesh.vertices.size() * sizeof(Vertex),
                                        VK_BUFFER_USAGE_VERTEX_BUFFER_BIT),
                   Buffer::device_local(vk, mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t),
                                        VK_BUFFER_USAGE_INDEX_BUFFER_BIT),
                   static_cast<uint32_t>(mesh.indices.size()), mesh_bounds(mesh)};
}

void bind_mesh(VkCommandBuffer cmd, const GpuMesh& mesh) {
    const VkDeviceSize offset = 0;
    VkBuffer vertex_buffer = mesh.vertices.get();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
    vkCmdBindIndexBuffer(cmd, mesh.indices.get(), 0, VK_INDEX_TYPE_UINT32);
}

}  // namespace lab
