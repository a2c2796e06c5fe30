// imgui_layer.h — Dear ImGui (1.86, GLFW + Vulkan backends) drawn inside the lab's render pass.
#pragma once

#include "vk_context.h"

#include <array>
#include <cstdint>

struct GLFWwindow;

namespace lab {

class ImGuiLayer {
public:
    ImGuiLayer(const VulkanContext& vk, GLFWwindow* window, VkRenderPass render_pass, uint32_t image_count);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    void new_frame();                 // before any ImGui:: call of this frame
    void render(VkCommandBuffer cmd);  // at the end of the render pass
    bool wants_mouse() const;         // the pointer is over a panel: the scene should ignore it
    bool wants_keyboard() const;      // a text field has focus

private:
    const VulkanContext& vk_;
    // ImGui's colours are sRGB-encoded; the swapchain is *_SRGB and encodes again on write. Each
    // vertex colour channel goes through this table (sRGB byte -> linear byte) before drawing.
    std::array<uint8_t, 256> srgb_to_linear_{};
    Handle<VkDescriptorPool> pool_;
};

}  // namespace lab
