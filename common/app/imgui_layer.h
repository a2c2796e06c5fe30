// imgui_layer.h — Dear ImGui (1.86): input through its GLFW backend, drawn by ImGuiRenderer
// (a cached overlay put over the lab's picture: opaque panels copied, the rest blended).
#pragma once

#include "imgui_renderer.h"
#include "vk_context.h"

#include <array>
#include <cstdint>
#include <memory>

struct GLFWwindow;
struct GLFWcursor;

namespace lab {

class Window;

class ImGuiLayer {
public:
    // `render_pass`, `format`: the frame's; `copy_to_target`: its images accept copies (render_after_pass()).
    ImGuiLayer(const VulkanContext& vk, GLFWwindow* window, VkRenderPass render_pass, VkFormat format, bool copy_to_target);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    // Before any ImGui:: call of this frame; `dt_seconds` since the previous UI frame.
    void new_frame(Window& window, float dt_seconds);
    // After the frame's ImGui:: calls, before its render pass begins: ends the UI frame and
    // redraws the overlay if the panels changed (see imgui_renderer.h).
    void prepare(VkCommandBuffer cmd, uint32_t slot, VkExtent2D extent);
    void render(VkCommandBuffer cmd);  // at the end of the render pass: blends the panels' translucent parts
    // After the render pass: copies the opaque panels into the frame's image (TRANSFER_DST_OPTIMAL).
    void render_after_pass(VkCommandBuffer cmd, VkImage image);
    uint64_t redraw_count() const { return renderer_->redraw_count(); }
    bool wants_mouse() const;         // the pointer is over a panel: the scene should ignore it
    bool wants_keyboard() const;      // a text field has focus
    bool wants_text_input() const;    // a text field is being edited (its cursor blinks)

private:
    void platform_new_frame(Window& window, float dt_seconds);

    // The mouse cursors the UI asks for (arrow, text beam, resize arrows, hand), and the one shown.
    std::array<GLFWcursor*, 9> cursors_{};  // by ImGuiMouseCursor; null = the arrow
    int shown_cursor_ = -2;
    std::unique_ptr<ImGuiRenderer> renderer_;
};

}  // namespace lab
