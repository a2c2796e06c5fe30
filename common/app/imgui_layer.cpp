#include "imgui_layer.h"

#include "window_target.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <imgui.h>

#include <cfloat>

namespace lab {

ImGuiLayer::ImGuiLayer(const VulkanContext& vk, GLFWwindow* window, VkRenderPass render_pass, VkFormat format,
                       bool copy_to_target) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // never write imgui.ini into the working directory
    ImGui::GetIO().BackendRendererName = "lab::ImGuiRenderer";
    ImGui::GetIO().BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;  // large meshes: VtxOffset honoured
    ImGui::StyleColorsDark();
    // Opaque panels (the dark style's are 94 % opaque): their pixels are copied onto the frame
    // instead of blended, which on a CPU driver is most of what the UI costs a frame (ui_regions.h).
    ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 1.0f;
    ImGui::GetStyle().Colors[ImGuiCol_PopupBg].w = 1.0f;
    ImGui_ImplGlfw_InitForVulkan(window, true);  // chains to the window's own callbacks
    // GLFW 3.3 has these standard cursors; ImGui's other shapes fall back to the arrow.
    cursors_[ImGuiMouseCursor_TextInput] = glfwCreateStandardCursor(GLFW_IBEAM_CURSOR);
    cursors_[ImGuiMouseCursor_ResizeNS] = glfwCreateStandardCursor(GLFW_VRESIZE_CURSOR);
    cursors_[ImGuiMouseCursor_ResizeEW] = glfwCreateStandardCursor(GLFW_HRESIZE_CURSOR);
    cursors_[ImGuiMouseCursor_Hand] = glfwCreateStandardCursor(GLFW_HAND_CURSOR);
    renderer_ = std::make_unique<ImGuiRenderer>(vk, render_pass, format, copy_to_target);  // uploads the font atlas
}

ImGuiLayer::~ImGuiLayer() {
    renderer_.reset();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    for (GLFWcursor* cursor : cursors_)
        if (cursor) glfwDestroyCursor(cursor);
}

void ImGuiLayer::new_frame(Window& window, float dt_seconds) {
    platform_new_frame(window, dt_seconds);
    ImGui::NewFrame();
}

// What ImGui_ImplGlfw_NewFrame() does, from the state the window's callbacks keep: the backend's
// own version asks GLFW for the window size (twice), the focus and the cursor every frame, four
// round trips to the X server that each wait for the last frame's image to be taken in. Keys,
// characters and the wheel still reach ImGui through the backend's callbacks.
void ImGuiLayer::platform_new_frame(Window& window, float dt_seconds) {
    const Window::Input& in = window.input();
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(in.width), float(in.height));
    if (in.width > 0 && in.height > 0)
        io.DisplayFramebufferScale = ImVec2(float(in.framebuffer_width) / float(in.width),
                                            float(in.framebuffer_height) / float(in.height));
    io.DeltaTime = dt_seconds > 0.0f ? dt_seconds : 1e-4f;  // ImGui requires a positive step

    // A click shorter than a frame still counts as held for one frame (or ImGui would miss it).
    const std::array<bool, 8> clicked = window.take_clicks();
    for (size_t i = 0; i < IM_ARRAYSIZE(io.MouseDown) && i < clicked.size(); ++i)
        io.MouseDown[i] = clicked[i] || in.mouse_down[i];
    io.MousePos = in.focused || in.cursor_inside ? ImVec2(float(in.cursor.x), float(in.cursor.y))
                                                 : ImVec2(-FLT_MAX, -FLT_MAX);

    // The cursor shape ImGui wants (text beam over a field, ...), sent only when it changes.
    const int wanted = io.MouseDrawCursor ? ImGuiMouseCursor_None : ImGui::GetMouseCursor();
    if (wanted != shown_cursor_) {
        shown_cursor_ = wanted;
        if (wanted == ImGuiMouseCursor_None) {
            glfwSetInputMode(window.handle(), GLFW_CURSOR, GLFW_CURSOR_HIDDEN);
        } else {
            glfwSetCursor(window.handle(), wanted >= 0 && size_t(wanted) < cursors_.size() ? cursors_[size_t(wanted)] : nullptr);
            glfwSetInputMode(window.handle(), GLFW_CURSOR, GLFW_CURSOR_NORMAL);
        }
    }
}

void ImGuiLayer::prepare(VkCommandBuffer cmd, uint32_t slot, VkExtent2D extent) {
    ImGui::Render();
    renderer_->prepare(cmd, slot, extent, *ImGui::GetDrawData());
}

void ImGuiLayer::render(VkCommandBuffer cmd) { renderer_->composite(cmd); }
void ImGuiLayer::render_after_pass(VkCommandBuffer cmd, VkImage image) { renderer_->copy_opaque(cmd, image); }

bool ImGuiLayer::wants_mouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool ImGuiLayer::wants_keyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }
bool ImGuiLayer::wants_text_input() const { return ImGui::GetIO().WantTextInput; }

}  // namespace lab
