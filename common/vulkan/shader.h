// shader.h — load a compiled SPIR-V shader from the lab's shader folder.
//
// Shaders are compiled by CMake at build time into build/shaders/<lab>/; the
// folder is compiled into the binary (LAB_SHADER_DIR, LabApp::shader_dir()).
#pragma once

#include "vk_context.h"

#include <string>

namespace lab {

// `compiled_dir` is the lab's shader folder (LabApp::shader_dir()); `name` e.g. "unlit.vert".
Handle<VkShaderModule> load_shader(const VulkanContext& vk, const std::string& compiled_dir, const std::string& name);

// A module from SPIR-V already in memory (common's own shaders, compiled into the program).
Handle<VkShaderModule> make_shader_module(const VulkanContext& vk, const uint32_t* code, size_t size_bytes);

}  // namespace lab
