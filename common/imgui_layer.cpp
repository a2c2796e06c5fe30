#include "imgui_layer.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <cstdio>

namespace lab {

namespace {
// The backend reports every VkResult here; an error must stop the run like any failed Vulkan
// call (continuing would draw with null handles).
void check_imgui_vk(VkResult result) {
    if (result < 0) throw_vk_error(result, "ImGui Vulkan backend call", __FILE__, __LINE__);
}
}  // namespace

ImGuiLayer::ImGuiLayer(const VulkanContext& vk, GLFWwindow* window, VkRenderPass render_pass, uint32_t image_count) {
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
    ImGui_ImplVulkan_Init(&info, render_pass);

    vk.run_once([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

ImGuiLayer::~ImGuiLayer() {
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void ImGuiLayer::new_frame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void ImGuiLayer::render(VkCommandBuffer cmd) {
    ImGui::Render();
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
}

bool ImGuiLayer::wants_mouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool ImGuiLayer::wants_keyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

}  // namespace lab
