// vk_check.h — turn a failed Vulkan call into an exception with file:line.
#pragma once

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace lab {

// Thrown for Vulkan and windowing failures (the lab exits with code 1).
class VulkanError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

const char* vk_result_name(VkResult result);

[[noreturn]] void throw_vk_error(VkResult result, const char* call, const char* file, int line);

}  // namespace lab

#define VK_CHECK(call)                                                          \
    do {                                                                        \
        VkResult vk_check_result_ = (call);                                     \
        if (vk_check_result_ != VK_SUCCESS)                                     \
            ::lab::throw_vk_error(vk_check_result_, #call, __FILE__, __LINE__); \
    } while (0)
