#include "imgui_layer.h"

#include "window_target.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace lab {

namespace {
// The backend reports every VkResult here; an error must stop the run like any failed Vulkan
// call (continuing would draw with null handles).
void check_imgui_vk(VkResult result) {
    if (result < 0) throw_vk_error(result, "ImGui Vulkan backend call", __FILE__, __LINE__);
}
// sRGB transfer function (IEC 61966-2-1), value in [0, 1].
double encode_srgb(double linear) {
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// For each sRGB byte s, the linear byte l whose encoding (what the *_SRGB target writes) comes
// closest to s: the panel shows ImGui's designed colours as exactly as 8-bit vertex colours allow
// (dark tones, where linear bytes are coarse, within 2/255 for the default dark style).
std::array<uint8_t, 256> make_srgb_to_linear_table() {
    std::array<uint8_t, 256> table{};
    int l = 0;
    for (int s = 0; s < 256; ++s) {
        // encode() is increasing: move l up while the next byte encodes closer to s.
        while (l < 255 && std::abs(encode_srgb((l + 1) / 255.0) * 255.0 - s) <=
                              std::abs(encode_srgb(l / 255.0) * 255.0 - s))
            ++l;
        table[size_t(s)] = uint8_t(l);
    }
    return table;
}
}  // namespace

ImGuiLayer::ImGuiLayer(const VulkanContext& vk, GLFWwindow* window, VkRenderPass render_pass, uint32_t image_count)
    : vk_(vk), srgb_to_linear_(make_srgb_to_linear_table()) {
    // The backend allocates (and frees) a descriptor set for its font texture.
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    pool_info.maxSets = 16;
    pool_info.poolSizeCount = 1;
    pool_info.pPoolSizes = &size;
    VkDescriptorPool pool;
    VK_CHECK(vkCreateDescriptorPool(vk.device(), &pool_info, nullptr, &pool));
    VkDevice device = vk.device();
    pool_ = Handle<VkDescriptorPool>(pool, [device](VkDescriptorPool p) { vkDestroyDescriptorPool(device, p, nullptr); });

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // never write imgui.ini into the working directory
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(window, true);  // chains to the window's own callbacks
    // GLFW 3.3 has these standard cursors; ImGui's other shapes fall back to the arrow.
    cursors_[ImGuiMouseCursor_TextInput] = glfwCreateStandardCursor(GLFW_IBEAM_CURSOR);
    cursors_[ImGuiMouseCursor_ResizeNS] = glfwCreateStandardCursor(GLFW_VRESIZE_CURSOR);
    cursors_[ImGuiMouseCursor_ResizeEW] = glfwCreateStandardCursor(GLFW_HRESIZE_CURSOR);
    cursors_[ImGuiMouseCursor_Hand] = glfwCreateStandardCursor(GLFW_HAND_CURSOR);

    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = vk.instance();
    info.PhysicalDevice = vk.physical_device();
    info.Device = vk.device();
    info.QueueFamily = vk.queue_family();
    info.Queue = vk.queue();
    info.DescriptorPool = pool;
    info.Subpass = 0;
    info.MinImageCount = 2;
    info.ImageCount = image_count < 2 ? 2 : image_count;
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = check_imgui_vk;
    // The backend allocates its own memory (font image, vertex and index buffers), one allocation
    // each: see VulkanContext::LibraryScope.
    const VulkanContext::LibraryScope backend(vk);
    ImGui_ImplVulkan_Init(&info, render_pass);

    vk.run_once([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

ImGuiLayer::~ImGuiLayer() {
    const VulkanContext::LibraryScope backend(vk_);
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    for (GLFWcursor* cursor : cursors_)
        if (cursor) glfwDestroyCursor(cursor);
}

void ImGuiLayer::new_frame(Window& window, float dt_seconds) {
    ImGui_ImplVulkan_NewFrame();
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

void ImGuiLayer::render(VkCommandBuffer cmd) {
    ImGui::Render();
    // ImGui 1.86 designs its colours (style, widgets, the labs' own) in sRGB and has no option for
    // an sRGB target: without this the swapchain would encode them a second time (washed-out
    // panels). Alpha is coverage, not colour: left alone. (Blending now happens in linear space,
    // so translucent panels differ slightly from ImGui's gamma-space design.)
    const ImDrawData* draw_data = ImGui::GetDrawData();
    for (int i = 0; i < draw_data->CmdListsCount; ++i)
        for (ImDrawVert& v : draw_data->CmdLists[i]->VtxBuffer) {
            const ImU32 c = v.col;
            v.col = ImU32(srgb_to_linear_[(c >> IM_COL32_R_SHIFT) & 0xFF]) << IM_COL32_R_SHIFT |
                    ImU32(srgb_to_linear_[(c >> IM_COL32_G_SHIFT) & 0xFF]) << IM_COL32_G_SHIFT |
                    ImU32(srgb_to_linear_[(c >> IM_COL32_B_SHIFT) & 0xFF]) << IM_COL32_B_SHIFT |
                    (c & IM_COL32_A_MASK);
        }
    const VulkanContext::LibraryScope backend(vk_);  // may grow its vertex/index buffers
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
}

bool ImGuiLayer::wants_mouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool ImGuiLayer::wants_keyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }
bool ImGuiLayer::wants_text_input() const { return ImGui::GetIO().WantTextInput; }

}  // namespace lab
