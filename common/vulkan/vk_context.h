// vk_context.h — instance, validation, physical device, device and queue.
//
// One VulkanContext per program. It picks a device that can render (and
// present, when given a window), enables only the optional features the
// device really supports, and counts validation messages so a run with
// --validate can fail on any of them.
#pragma once

#include "memory.h"
#include "vk_check.h"
#include "vk_handle.h"

#include <vulkan/vulkan.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

struct GLFWwindow;

namespace lab {

struct ContextOptions {
    bool validate = false;          // Khronos validation layer + debug messenger
    GLFWwindow* window = nullptr;   // present to this window (nullptr: headless)
    int* message_count = nullptr;   // optional: also counts validation messages here (outlives the context)
    // Test hooks (--dev-validation-probe, --dev-no-blit: app/dev_options.h).
    bool validation_probe = false;  // with `validate`: commit one mistake per check the layer must report
    bool no_blit = false;           // format_properties() reports no format as a blit source or target
    // --dev-without-feature: these optional features (names from fakeable_features()) count as
    // unsupported, so the labs take the path a device without them takes.
    std::vector<std::string> without_features;
    // --dev-minimum-limits: the device's limits lowered to the least the specification requires
    // (minimum_limits() below), so the labs take the path a device at those minimums takes.
    bool minimum_limits = false;
};

// `limits` lowered, where they are higher, to the least the Vulkan specification requires of every
// device (its table "Required Limits"): image, framebuffer and buffer sizes, and descriptor counts.
VkPhysicalDeviceLimits minimum_limits(VkPhysicalDeviceLimits limits);

// The optional features the labs use, by their Vulkan names (VkPhysicalDeviceFeatures'), plus
// "timestamps" (the queue's timestampValidBits): what ContextOptions::without_features may name.
const std::vector<std::string>& fakeable_features();

class VulkanContext {
public:
    explicit VulkanContext(const ContextOptions& options);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physical_device() const { return physical_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queue_family() const { return queue_family_; }
    VkSurfaceKHR surface() const { return surface_; }  // VK_NULL_HANDLE when headless
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    // Optional features that are both supported and enabled (check before use).
    const VkPhysicalDeviceFeatures& enabled_features() const { return enabled_features_; }
    // The queue family's timestampValidBits: 0 when it has no timestamps.
    uint32_t timestamp_valid_bits() const { return timestamp_valid_bits_; }

    uint32_t find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags wanted) const;
    // Device memory for buffers and images: ranges of a few large blocks (memory.h).
    MemoryAllocator& allocator() const { return *allocator_; }
    VkFormat depth_format() const { return depth_format_; }
    // vkGetPhysicalDeviceFormatProperties, less the blit features under ContextOptions::no_blit.
    VkFormatProperties format_properties(VkFormat format) const;

    // Records commands into the context's upload command buffer, submits and waits.
    // For uploads and readbacks — never inside the frame loop. The one command buffer is
    // recycled (its pool reset) on every call instead of allocating and freeing one per call:
    // that is the usual pattern, and Debian 12's validation layer (1.3.239, synchronization
    // validation) keeps about 3 KB for every command buffer freed, which made a scene reload
    // (two uploads per mesh) leak memory (docs/testing.md, "Window soak").
    void run_once(const std::function<void(VkCommandBuffer)>& record) const;

    // Validation messages (warnings and errors) seen so far, less the filtered ones
    // (kFilteredMessages in vk_context.cpp: each with its reason; synchronization hazards never).
    int validation_messages() const { return validation_messages_; }

private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL on_debug_message(
        VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT type,
        const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);
    void create_instance(const ContextOptions& options);
    void pick_physical_device();
    void create_device(const std::vector<std::string>& without_features);
    void provoke_validation_messages();  // test hook ContextOptions::validation_probe

    // The message counters first: the instance reports into them until it is destroyed.
    int validation_messages_ = 0;
    int* external_count_ = nullptr;
    // Owned objects in creation order (destroyed in reverse: vk_handle.h).
    Handle<VkInstance> instance_;
    Handle<VkDebugUtilsMessengerEXT> messenger_;
    Handle<VkSurfaceKHR> surface_;
    Handle<VkDevice> device_;
    std::unique_ptr<MemoryAllocator> allocator_;  // given back before the device is destroyed
    Handle<VkCommandPool> upload_pool_;
    Handle<VkFence> upload_fence_;                 // run_once's
    VkCommandBuffer upload_cmd_ = VK_NULL_HANDLE;  // run_once's, freed with the pool
    // Chosen, not owned.
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memory_{};
    VkPhysicalDeviceFeatures enabled_features_{};
    uint32_t timestamp_valid_bits_ = 0;
    VkFormat depth_format_ = VK_FORMAT_D32_SFLOAT;
    bool presenting_ = false;
    bool no_blit_ = false;
    bool minimum_limits_ = false;
};

}  // namespace lab
