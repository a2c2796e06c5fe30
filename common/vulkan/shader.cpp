#include "shader.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

namespace lab {

Handle<VkShaderModule> load_shader(const VulkanContext& vk, const std::string& compiled_dir, const std::string& name) {
    const std::string path = compiled_dir + "/" + name + ".spv";
    std::ifstream file(path, std::ios::binary);
    if (!file) throw VulkanError(path + ": cannot open compiled shader (rebuild the lab)");
    std::vector<char> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (bytes.empty() || bytes.size() % 4 != 0) throw VulkanError(path + ": not a SPIR-V file (size is not a multiple of 4)");

    std::vector<uint32_t> code(bytes.size() / 4);  // aligned for pCode
    std::memcpy(code.data(), bytes.data(), bytes.size());
    return make_shader_module(vk, code.data(), bytes.size());
}

Handle<VkShaderModule> make_shader_module(const VulkanContext& vk, const uint32_t* code, size_t size_bytes) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = size_bytes;
    info.pCode = code;
    VkShaderModule module;
    VK_CHECK(vkCreateShaderModule(vk.device(), &info, nullptr, &module));
    VkDevice device = vk.device();
    return Handle<VkShaderModule>(module, [device](VkShaderModule m) { vkDestroyShaderModule(device, m, nullptr); });
}

}  // namespace lab
