#include "vk_context.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace lab {

const char* vk_result_name(VkResult result) {
    switch (result) {
#define LAB_RESULT(r) \
    case r:           \
        return #r;
        LAB_RESULT(VK_NOT_READY)
        LAB_RESULT(VK_TIMEOUT)
        LAB_RESULT(VK_INCOMPLETE)
        LAB_RESULT(VK_SUBOPTIMAL_KHR)
        LAB_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
        LAB_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        LAB_RESULT(VK_ERROR_INITIALIZATION_FAILED)
        LAB_RESULT(VK_ERROR_DEVICE_LOST)
        LAB_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
        LAB_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
        LAB_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
        LAB_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
        LAB_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
        LAB_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
        LAB_RESULT(VK_ERROR_SURFACE_LOST_KHR)
        LAB_RESULT(VK_ERROR_OUT_OF_DATE_KHR)
#undef LAB_RESULT
        default:
            return "VkResult error";
    }
}

void throw_vk_error(VkResult result, const char* call, const char* file, int line) {
    throw VulkanError(std::string(file) + ":" + std::to_string(line) + ": " + call + " failed with " +
                      vk_result_name(result) + " (" + std::to_string(result) + ")");
}

namespace {
constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// Validation messages that are not defects of this project, by message ID, each with its reason.
// Everything else — and synchronization hazards ("SYNC-…") always — fails a --validate run.
struct FilteredMessage {
    const char* id;
    const char* reason;
};
constexpr FilteredMessage kFilteredMessages[] = {
    {"UNASSIGNED-BestPractices-vkCreateInstance-specialuse-extension-debugging",
     "VK_EXT_debug_utils and VK_EXT_validation_features are enabled only with --validate, which is debugging"},
};

bool filtered(const char* id) {
    if (!id || std::strncmp(id, "SYNC-", 5) == 0) return false;  // hazards are never filtered
    for (const FilteredMessage& f : kFilteredMessages)
        if (std::strcmp(id, f.id) == 0) return true;
    return false;
}

bool has_layer_extension(const char* layer, const char* extension) {
    uint32_t count = 0;
    vkEnumerateInstanceExtensionProperties(layer, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data());
    for (const auto& e : extensions)
        if (std::strcmp(e.extensionName, extension) == 0) return true;
    return false;
}

bool has_layer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    for (const auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}
}  // namespace

VulkanContext::VulkanContext(const ContextOptions& options)
    : external_count_(options.message_count), no_blit_(options.no_blit), minimum_limits_(options.minimum_limits) {
    // Each object is a Handle member, declared in creation order: if a step throws, what was made
    // so far is destroyed in reverse order, as it is when the context goes.
    create_instance(options);
    if (options.window) {
        VkSurfaceKHR surface;
        VK_CHECK(glfwCreateWindowSurface(instance_, options.window, nullptr, &surface));
        surface_ = Handle<VkSurfaceKHR>(surface, [instance = instance_.get()](VkSurfaceKHR s) {
            vkDestroySurfaceKHR(instance, s, nullptr);
        });
        presenting_ = true;
    }
    pick_physical_device();
    create_device(options.without_features);
    if (options.validate && options.validation_probe) provoke_validation_messages();
}

VulkanContext::~VulkanContext() {
    if (device_) vkDeviceWaitIdle(device_);  // then the members go, the device's objects first
}

VkBool32 VulkanContext::on_debug_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                         VkDebugUtilsMessageTypeFlagsEXT,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void* self) {
    auto* context = static_cast<VulkanContext*>(self);
    if (filtered(data->pMessageIdName)) return VK_FALSE;
    context->validation_messages_++;
    if (context->external_count_) ++*context->external_count_;
    const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
    std::fprintf(stderr, "validation %s: %s\n", level, data->pMessage);
    return VK_FALSE;
}

void VulkanContext::create_instance(const ContextOptions& options) {
    std::vector<const char*> extensions;
    if (options.window) {
        uint32_t count = 0;
        const char** glfw_extensions = glfwGetRequiredInstanceExtensions(&count);
        if (!glfw_extensions) throw VulkanError("GLFW: this system cannot present Vulkan to a window");
        extensions.assign(glfw_extensions, glfw_extensions + count);
    }
    std::vector<const char*> layers;
    if (options.validate) {
        if (!has_layer(kValidationLayer))
            throw VulkanError(std::string("--validate: ") + kValidationLayer +
                              " is not installed (scripts/setup.sh installs vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        if (!has_layer_extension(kValidationLayer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME))
            throw VulkanError(std::string("--validate: ") + kValidationLayer + " lacks " +
                              VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME +
                              " (needed for synchronization validation and best practices; install a newer "
                              "vulkan-validationlayers)");
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    }

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "vulkan-labs";
    app.apiVersion = VK_API_VERSION_1_1;

    // Warnings and errors only: info/verbose messages are loader chatter.
    VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger.pfnUserCallback = &VulkanContext::on_debug_message;
    messenger.pUserData = this;

    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    // Besides the core checks: synchronization validation (read/write hazards between commands,
    // render passes and submissions) and the best-practices checks (destruction order, command
    // pool use, allocation sizes, ...). Any message of either fails the run like any other.
    const VkValidationFeatureEnableEXT enabled_checks[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT,
                                                           VK_VALIDATION_FEATURE_ENABLE_BEST_PRACTICES_EXT};
    VkValidationFeaturesEXT checks{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    checks.enabledValidationFeatureCount = 2;
    checks.pEnabledValidationFeatures = enabled_checks;
    checks.pNext = &messenger;  // the messenger also catches messages from vkCreate/DestroyInstance
    if (options.validate) info.pNext = &checks;
    VkInstance instance;
    VK_CHECK(vkCreateInstance(&info, nullptr, &instance));
    instance_ = Handle<VkInstance>(instance, [](VkInstance i) { vkDestroyInstance(i, nullptr); });

    if (options.validate) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (!create || !destroy) throw VulkanError("--validate: VK_EXT_debug_utils is not available");
        VkDebugUtilsMessengerEXT handle;
        VK_CHECK(create(instance, &messenger, nullptr, &handle));
        messenger_ = Handle<VkDebugUtilsMessengerEXT>(
            handle, [instance, destroy](VkDebugUtilsMessengerEXT m) { destroy(instance, m, nullptr); });
    }
}

void VulkanContext::pick_physical_device() {
    uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance_, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance_, &count, devices.data()));

    // Prefer a discrete GPU, then an integrated one, then anything (lavapipe is a CPU device).
    int best_score = -1;
    std::string skipped;  // why devices were passed over, for the error below
    for (VkPhysicalDevice candidate : devices) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(candidate, &props);
        // The shaders are SPIR-V 1.3, which needs Vulkan 1.1.
        if (props.apiVersion < VK_API_VERSION_1_1) {
            const std::string why = std::string("skipping Vulkan device '") + props.deviceName + "': it supports Vulkan " +
                                    std::to_string(VK_API_VERSION_MAJOR(props.apiVersion)) + "." +
                                    std::to_string(VK_API_VERSION_MINOR(props.apiVersion)) +
                                    ", the labs' shaders need 1.1";
            std::fprintf(stderr, "%s\n", why.c_str());
            skipped += "; " + why;
            continue;
        }
        uint32_t family_count = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &family_count, nullptr);
        std::vector<VkQueueFamilyProperties> families(family_count);
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &family_count, families.data());
        for (uint32_t f = 0; f < family_count; ++f) {
            if (!(families[f].queueFlags & VK_QUEUE_GRAPHICS_BIT)) continue;
            if (presenting_) {
                VkBool32 can_present = VK_FALSE;
                vkGetPhysicalDeviceSurfaceSupportKHR(candidate, f, surface_, &can_present);
                if (!can_present) continue;
            }
            const int score = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU     ? 3
                              : props.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ? 2
                                                                                            : 1;
            if (score > best_score) {
                best_score = score;
                physical_ = candidate;
                queue_family_ = f;
                // 0 when the queue has no timestamps (GPU time per pass: common/dev/gpu_timer.h).
                timestamp_valid_bits_ = props.limits.timestampPeriod > 0.0f ? families[f].timestampValidBits : 0;
            }
            break;
        }
    }
    if (!physical_) throw VulkanError("no Vulkan device can render" + std::string(presenting_ ? " and present" : "") +
                                      " (is mesa-vulkan-drivers installed?)" + skipped);
    vkGetPhysicalDeviceProperties(physical_, &properties_);
    if (minimum_limits_) properties_.limits = minimum_limits(properties_.limits);
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);

    // The first depth format the device can use as a depth attachment.
    for (VkFormat format : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_X8_D24_UNORM_PACK32, VK_FORMAT_D24_UNORM_S8_UINT,
                            VK_FORMAT_D16_UNORM}) {
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(physical_, format, &fp);
        if (fp.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) {
            depth_format_ = format;
            return;
        }
    }
    throw VulkanError("no supported depth format");
}

VkPhysicalDeviceLimits minimum_limits(VkPhysicalDeviceLimits limits) {
    const auto at_most = [](uint32_t& value, uint32_t minimum) { value = std::min(value, minimum); };
    at_most(limits.maxImageDimension2D, 4096);
    at_most(limits.maxImageDimensionCube, 4096);
    at_most(limits.maxFramebufferWidth, 4096);
    at_most(limits.maxFramebufferHeight, 4096);
    at_most(limits.maxUniformBufferRange, 16384);
    at_most(limits.maxStorageBufferRange, 1u << 27);
    at_most(limits.maxPushConstantsSize, 128);
    at_most(limits.maxBoundDescriptorSets, 4);
    at_most(limits.maxPerStageDescriptorSamplers, 16);
    at_most(limits.maxPerStageDescriptorUniformBuffers, 12);
    at_most(limits.maxPerStageDescriptorStorageBuffers, 4);
    at_most(limits.maxPerStageDescriptorSampledImages, 16);
    at_most(limits.maxPerStageResources, 128);
    at_most(limits.maxDescriptorSetSamplers, 96);
    at_most(limits.maxDescriptorSetUniformBuffers, 72);
    at_most(limits.maxDescriptorSetStorageBuffers, 24);
    at_most(limits.maxDescriptorSetSampledImages, 96);
    at_most(limits.maxColorAttachments, 4);
    limits.maxSamplerAnisotropy = std::min(limits.maxSamplerAnisotropy, 16.0f);
    return limits;
}

const std::vector<std::string>& fakeable_features() {
    static const std::vector<std::string> names = {"fragmentStoresAndAtomics", "samplerAnisotropy", "depthClamp",
                                                   "depthBiasClamp", "timestamps"};
    return names;
}

void VulkanContext::create_device(const std::vector<std::string>& without_features) {
    // Optional features: enable only what the device supports and the labs use; each use checks
    // enabled_features() and has a path for a device without it (what it does: docs/architecture.md,
    // "Optional features"). --dev-without-feature takes features away here, before anything is enabled.
    VkPhysicalDeviceFeatures supported;
    vkGetPhysicalDeviceFeatures(physical_, &supported);
    const auto without = [&](const char* name) {
        return std::find(without_features.begin(), without_features.end(), name) != without_features.end();
    };
    if (without("fragmentStoresAndAtomics")) supported.fragmentStoresAndAtomics = VK_FALSE;
    if (without("samplerAnisotropy")) supported.samplerAnisotropy = VK_FALSE;
    if (without("depthClamp")) supported.depthClamp = VK_FALSE;
    if (without("depthBiasClamp")) supported.depthBiasClamp = VK_FALSE;
    if (without("timestamps")) timestamp_valid_bits_ = 0;
    enabled_features_.samplerAnisotropy = supported.samplerAnisotropy;  // labs 3, 4: else probes, or no anisotropy
    enabled_features_.depthClamp = supported.depthClamp;  // lab 4: casters in front of a shadow map's near plane
    enabled_features_.depthBiasClamp = supported.depthBiasClamp;  // lab 4: a shadow map's depth bias bounded
    enabled_features_.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;  // lab 4: translucent layers' lists

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;

    std::vector<const char*> extensions;
    if (presenting_) extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);

    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue_info;
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    info.pEnabledFeatures = &enabled_features_;
    VkDevice device;
    VK_CHECK(vkCreateDevice(physical_, &info, nullptr, &device));
    device_ = Handle<VkDevice>(device, [](VkDevice d) { vkDestroyDevice(d, nullptr); });
    vkGetDeviceQueue(device, queue_family_, 0, &queue_);
    allocator_ = std::make_unique<MemoryAllocator>(device, memory_);

    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pool.queueFamilyIndex = queue_family_;
    VkCommandPool upload_pool;
    VK_CHECK(vkCreateCommandPool(device, &pool, nullptr, &upload_pool));
    // Destroying the pool frees upload_cmd_.
    upload_pool_ = Handle<VkCommandPool>(upload_pool, [device](VkCommandPool p) { vkDestroyCommandPool(device, p, nullptr); });
    // run_once's command buffer and fence, made once and reused by every upload.
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = upload_pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(device_, &alloc, &upload_cmd_));
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence upload_fence;
    VK_CHECK(vkCreateFence(device, &fence_info, nullptr, &upload_fence));
    upload_fence_ = Handle<VkFence>(upload_fence, [device](VkFence f) { vkDestroyFence(device, f, nullptr); });
}

// Test-only (--dev-validation-probe): one mistake each check of --validate must report, so a
// test can see that synchronization validation and best practices are really on.
void VulkanContext::provoke_validation_messages() {
    // Best practices: a command pool whose buffers are reset one by one.
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = queue_family_;
    VkCommandPool pool;
    VK_CHECK(vkCreateCommandPool(device_, &pool_info, nullptr, &pool));
    vkDestroyCommandPool(device_, pool, nullptr);

    // Synchronization: two transfers write the same buffer with no barrier between them.
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = 256;
    info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    Allocation memory;  // declared first: freed after the buffer
    VkBuffer buffer;
    VK_CHECK(vkCreateBuffer(device_, &info, nullptr, &buffer));
    Handle<VkBuffer> owner(buffer, [this](VkBuffer b) { vkDestroyBuffer(device_, b, nullptr); });
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, buffer, &req);
    memory = allocator_->allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, false);
    VK_CHECK(vkBindBufferMemory(device_, buffer, memory.memory(), memory.offset()));
    run_once([&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, buffer, 0, 256, 0u);
        vkCmdFillBuffer(cmd, buffer, 0, 256, 1u);  // write-after-write hazard
    });
}

VkFormatProperties VulkanContext::format_properties(VkFormat format) const {
    VkFormatProperties properties;
    vkGetPhysicalDeviceFormatProperties(physical_, format, &properties);
    if (no_blit_) {  // a device without blits: the fallback paths run
        const VkFormatFeatureFlags blit = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT;
        properties.linearTilingFeatures &= ~blit;
        properties.optimalTilingFeatures &= ~blit;
    }
    return properties;
}

uint32_t VulkanContext::find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags wanted) const {
    for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    throw VulkanError("no Vulkan memory type with the requested properties");
}

void VulkanContext::run_once(const std::function<void(VkCommandBuffer)>& record) const {
    // The previous upload has finished (we waited for it): resetting the pool makes its one
    // command buffer ready to record again (cheaper than resetting buffers one by one).
    VK_CHECK(vkResetCommandPool(device_, upload_pool_, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(upload_cmd_, &begin));
    record(upload_cmd_);
    VK_CHECK(vkEndCommandBuffer(upload_cmd_));

    VK_CHECK(vkResetFences(device_, 1, upload_fence_.ptr()));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &upload_cmd_;
    VK_CHECK(vkQueueSubmit(queue_, 1, &submit, upload_fence_));
    VK_CHECK(vkWaitForFences(device_, 1, upload_fence_.ptr(), VK_TRUE, UINT64_MAX));
}

}  // namespace lab
