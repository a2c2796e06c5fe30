// imgui_layer.h — Dear ImGui (1.86, GLFW + Vulkan backends) drawn inside the lab's render pass.
#pragma once

#include "vk_context.h"

#include <array>
#include <cstdint>

struct GLFWwindow;
struct GLFWcursor;

namespace lab {

class Window;

class ImGuiLayer {
public:
    ImGuiLayer(const VulkanContext& vk, GLFWwindow* window, VkRenderPass render_pass, uint32_t image_count);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    // Before any ImGui:: call of this frame; `dt_seconds` since the previous UI frame.
    void new_frame(Window& window, float dt_seconds);
    void render(VkCommandBuffer cmd);  // at the end of the render pass
    bool wants_mouse() const;         // the pointer is over a panel: the scene should ignore it
    bool wants_keyboard() const;      // a text field has focus
    bool wants_text_input() const;    // a text field is being edited (its cursor blinks)

private:
    void platform_new_frame(Window& window, float dt_seconds);

    const VulkanContext& vk_;
    // The mouse cursors the UI asks for (arrow, text beam, resize arrows, hand), and the one shown.
    std::array<GLFWcursor*, 9> cursors_{};  // by ImGuiMouseCursor; null = the arrow
    int shown_cursor_ = -2;
    // ImGui's colours are sRGB-encoded; the swapchain is *_SRGB and encodes again on write. Each
    // vertex colour channel goes through this table (sRGB byte -> linear byte) before drawing.
    std::array<uint8_t, 256> srgb_to_linear_{};
    Handle<VkDescriptorPool> pool_;
};

}  // namespace lab
