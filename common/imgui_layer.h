// imgui_layer.h — Dear ImGui (1.86, GLFW + Vulkan backends) drawn inside the lab's render pass.
#pragma once

#include "vk_context.h"

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
    Handle<VkDescriptorPool> pool_;
};

}  // namespace lab
