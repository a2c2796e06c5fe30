#include "window_target.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>

namespace lab {

namespace {
Handle<VkSemaphore> make_semaphore(VkDevice device) {
    VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore;
    VK_CHECK(vkCreateSemaphore(device, &info, nullptr, &semaphore));
    return Handle<VkSemaphore>(semaphore, [device](VkSemaphore s) { vkDestroySemaphore(device, s, nullptr); });
}

VkSurfaceFormatKHR choose_surface_format(const VulkanContext& vk) {
    uint32_t count = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(vk.physical_device(), vk.surface(), &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(vk.physical_device(), vk.surface(), &count, formats.data()));
    // An *_SRGB format, so the window shows exactly what the headless PNG holds.
    for (const auto& f : formats)
        if ((f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) &&
            f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
            return f;
    // No UNORM fallback on purpose: the labs' fragment shaders write linear colour and leave the
    // encoding to the *_SRGB attachment (as the headless PNG does); encoding in every lab's shader
    // would put non-lesson code into each lab. Every desktop driver we know offers B8G8R8A8_SRGB.
    std::string offered;
    for (const auto& f : formats) offered += (offered.empty() ? "" : ", ") + std::to_string(int(f.format));
    throw VulkanError("the window surface offers no 8-bit sRGB format (B8G8R8A8_SRGB or R8G8B8A8_SRGB with "
                      "SRGB_NONLINEAR; offered VkFormat values: " + offered +
                      "); the labs need one to show linear colour correctly — render with --headless instead");
}
}  // namespace

// ---------------------------------------------------------------- Window

Window::Window(const std::string& title, uint32_t width, uint32_t height) {
    glfwSetErrorCallback([](int code, const char* text) { std::fprintf(stderr, "GLFW error %d: %s\n", code, text); });
    if (!glfwInit()) throw VulkanError("GLFW: cannot open a window (no display? use --headless)");
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        throw VulkanError("GLFW: no Vulkan loader found for windows (use --headless)");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);  // shown once the device has accepted its size
    window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw VulkanError("GLFW: cannot create a " + std::to_string(width) + "x" + std::to_string(height) + " window");
    }
    glfwSetWindowUserPointer(window_, this);
    // A key tapped between two frames is still down for one frame (glfwGetKey reports the press
    // until it is read): a quick tap of W still moves a little. (Commands such as R and C count
    // presses from the key callback instead, see take_key_press.)
    glfwSetInputMode(window_, GLFW_STICKY_KEYS, GLFW_TRUE);
    watch_input();
}

Window::~Window() {
    glfwDestroyWindow(window_);
    glfwTerminate();
}

void Window::show() { glfwShowWindow(window_); }
bool Window::should_close() const { return glfwWindowShouldClose(window_); }
bool Window::take_resized() { return std::exchange(resized_, false); }
float Window::take_scroll() { return std::exchange(scroll_, 0.0f); }
bool Window::take_key_press(int glfw_key) {
    if (glfw_key < 0 || glfw_key >= int(key_presses_.size()) || key_presses_[size_t(glfw_key)] == 0) return false;
    --key_presses_[size_t(glfw_key)];
    return true;
}

namespace {
Window& owner(GLFWwindow* w) { return *static_cast<Window*>(glfwGetWindowUserPointer(w)); }
}  // namespace

void Window::watch_input() {
    // One round trip each, once: from here on the callbacks keep these current.
    glfwGetWindowSize(window_, &input_.width, &input_.height);
    glfwGetFramebufferSize(window_, &input_.framebuffer_width, &input_.framebuffer_height);
    glfwGetCursorPos(window_, &input_.cursor.x, &input_.cursor.y);
    input_.focused = glfwGetWindowAttrib(window_, GLFW_FOCUSED) != 0;
    input_.cursor_inside = glfwGetWindowAttrib(window_, GLFW_HOVERED) != 0;

    // GLFW calls back with the window; the Window is its user pointer. (ImGui's backend, set up
    // later, installs its own callbacks for keys, buttons, wheel, focus and cursor enter, and
    // calls these from them.)
    glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int width, int height) {
        Window& me = owner(w);
        me.resized_ = true;
        me.input_.framebuffer_width = width;
        me.input_.framebuffer_height = height;
        ++me.events_;
    });
    glfwSetWindowSizeCallback(window_, [](GLFWwindow* w, int width, int height) {
        Window& me = owner(w);
        me.input_.width = width;
        me.input_.height = height;
        ++me.events_;
    });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
        Window& me = owner(w);
        me.input_.cursor = {x, y};
        ++me.events_;
    });
    glfwSetCursorEnterCallback(window_, [](GLFWwindow* w, int entered) {
        Window& me = owner(w);
        me.input_.cursor_inside = entered != 0;
        ++me.events_;
    });
    glfwSetWindowFocusCallback(window_, [](GLFWwindow* w, int focused) {
        Window& me = owner(w);
        me.input_.focused = focused != 0;
        ++me.events_;
    });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
        Window& me = owner(w);
        if (button >= 0 && button < int(me.input_.mouse_down.size())) {
            me.input_.mouse_down[size_t(button)] = action == GLFW_PRESS;
            if (action == GLFW_PRESS) me.input_.mouse_clicked[size_t(button)] = true;
        }
        ++me.events_;
    });
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
        Window& me = owner(w);
        if (key >= 0 && key < int(me.key_held_.size()) && action != GLFW_REPEAT) {
            bool& held = me.key_held_[size_t(key)];
            if (held != (action == GLFW_PRESS)) me.input_.keys_down += held ? -1 : 1;
            held = action == GLFW_PRESS;
            if (action == GLFW_PRESS) ++me.key_presses_[size_t(key)];
        }
        ++me.events_;
    });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
        Window& me = owner(w);
        me.scroll_ += float(dy);
        ++me.events_;  // a wheel step zooms: it needs a frame (the window soak found it drew none)
    });
    glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned int) {
        ++owner(w).events_;
    });
    // Uncovered, restored or maximized: the window needs its picture again.
    glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) { ++owner(w).events_; });
    glfwSetWindowIconifyCallback(window_, [](GLFWwindow* w, int) { ++owner(w).events_; });
}

std::array<bool, 8> Window::take_clicks() { return std::exchange(input_.mouse_clicked, {}); }

bool Window::input_held() const {
    if (input_.keys_down > 0) return true;
    for (bool down : input_.mouse_down)
        if (down) return true;
    return false;
}

void Window::wait_events(double timeout_seconds) const { glfwWaitEventsTimeout(timeout_seconds); }

// ---------------------------------------------------------------- WindowTarget

namespace {
// Whether swapchain images may be made with TRANSFER_DST usage (the UI copies panels into them).
bool surface_accepts_copies(const VulkanContext& vk) {
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(vk.physical_device(), vk.surface(), &caps));
    return (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT) != 0;
}
}  // namespace

// With copies, the render pass leaves the image ready for them and end_frame() hands it to
// presentation afterwards; without, the pass leaves it ready for presentation.
WindowTarget::WindowTarget(const VulkanContext& vk, Window& window)
    : vk_(vk), window_(window), surface_format_(choose_surface_format(vk)), accepts_copies_(surface_accepts_copies(vk)),
      render_pass_(make_render_pass(vk, surface_format_.format,
                                    accepts_copies_ ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_PRESENT_SRC_KHR)),
      slots_(vk) {
    for (auto& s : image_available_) s = make_semaphore(vk.device());
    stale_ = !create_swapchain();  // a window that starts minimized gets its swapchain later
}

WindowTarget::~WindowTarget() {
    // Then the members go in reverse order of declaration: the retired swapchains, the frame
    // slots, the depth image, framebuffers and views, the swapchain, the render pass.
    vkDeviceWaitIdle(vk_.device());  // nothing to report from a destructor; the run is over
}

namespace {
// OPAQUE when the surface supports it (the labs draw opaque pixels), else what it does support.
VkCompositeAlphaFlagBitsKHR choose_composite_alpha(VkCompositeAlphaFlagsKHR supported) {
    for (VkCompositeAlphaFlagBitsKHR mode : {VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR,
                                             VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR,
                                             VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR})
        if (supported & mode) return mode;
    throw VulkanError("the window surface supports no composite alpha mode");
}
}  // namespace

bool WindowTarget::create_swapchain() {
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(vk_.physical_device(), vk_.surface(), &caps));
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == UINT32_MAX) {  // the surface takes the size of the swapchain: use the window's
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_.handle(), &w, &h);
        extent = {std::clamp(uint32_t(w), caps.minImageExtent.width, caps.maxImageExtent.width),
                  std::clamp(uint32_t(h), caps.minImageExtent.height, caps.maxImageExtent.height)};
    }
    // Minimized (or mid-resize to nothing): a 0×0 swapchain or depth image is invalid. Keep the
    // old swapchain (if any) and try again on a later frame.
    if (extent.width == 0 || extent.height == 0) return false;

    uint32_t image_count = caps.minImageCount + 1;
    if (caps.maxImageCount > 0) image_count = std::min(image_count, caps.maxImageCount);

    const VkSwapchainKHR old = swapchain_;
    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = vk_.surface();
    info.minImageCount = image_count;
    info.imageFormat = surface_format_.format;
    info.imageColorSpace = surface_format_.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (accepts_copies_ ? VK_IMAGE_USAGE_TRANSFER_DST_BIT : 0);
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = choose_composite_alpha(caps.supportedCompositeAlpha);
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // vsync; the only mode every driver must offer
    info.clipped = VK_TRUE;
    info.oldSwapchain = old;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSwapchainKHR(vk_.device(), &info, nullptr, &created));

    // The old swapchain and its render-finished semaphores may still be held by a presentation
    // that vkDeviceWaitIdle does not cover (VK_EXT_swapchain_maintenance1, which could tell, is not
    // offered by Debian 12's drivers): destroy them only after kFramesInFlight more presents.
    VkDevice device = vk_.device();
    if (old) {
        Retired retired;
        retired.swapchain = std::move(swapchain_);
        retired.semaphores = std::move(render_finished_);
        retired.destroy_after = presents_ + kFramesInFlight;
        retired_.push_back(std::move(retired));
    }
    render_finished_.clear();
    destroy_swapchain_images();
    swapchain_ = Handle<VkSwapchainKHR>(created, [device](VkSwapchainKHR s) { vkDestroySwapchainKHR(device, s, nullptr); });
    extent_ = extent;

    uint32_t count = 0;
    VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain_, &count, nullptr));
    images_.resize(count);
    VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain_, &count, images_.data()));

    depth_ = create_target_image(vk_, extent_, vk_.depth_format(), VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                 VK_IMAGE_ASPECT_DEPTH_BIT);
    for (VkImage image : images_) {
        views_.push_back(create_target_view(vk_, image, surface_format_.format, VK_IMAGE_ASPECT_COLOR_BIT));
        framebuffers_.push_back(make_framebuffer(vk_, render_pass_, {views_.back(), depth_.view}, extent_));
        render_finished_.push_back(make_semaphore(device));
    }
    return true;
}

void WindowTarget::destroy_swapchain_images() {
    framebuffers_.clear();
    views_.clear();
    render_finished_.clear();
    depth_ = Image{};
}

bool WindowTarget::recreate_swapchain() {
    // Every path that makes a swapchain goes through create_swapchain(), which refuses 0×0.
    VK_CHECK(vkDeviceWaitIdle(vk_.device()));  // framebuffers and depth are in use by in-flight frames
    if (!create_swapchain()) return false;
    stale_ = false;
    return true;
}

void WindowTarget::mark_stale(bool suboptimal) {
    // A surface can stay suboptimal (e.g. a rotated display we do not pre-rotate for): recreate once
    // per change, not every frame. A resize or an out-of-date swapchain is a new change.
    if (suboptimal && suboptimal_handled_) return;
    suboptimal_handled_ = suboptimal;
    stale_ = true;
}

void WindowTarget::release_retired() {
    while (!retired_.empty() && retired_.front().destroy_after <= presents_) retired_.pop_front();
}

namespace {
// A failed acquire or present other than out-of-date/suboptimal ends the run, saying what happened.
[[noreturn]] void throw_surface_error(const char* what, VkResult result) {
    std::string message = std::string(what) + " failed with " + vk_result_name(result);
    if (result == VK_ERROR_SURFACE_LOST_KHR) message += ": the window's surface is gone (window closed or display lost)";
    if (result == VK_ERROR_DEVICE_LOST) message += ": the GPU was lost (driver reset or hang)";
    throw VulkanError(message);
}
}  // namespace

bool WindowTarget::begin_frame(const glm::vec3& clear_linear, Frame& frame, const BeforePass& before_pass) {
    if (window_.take_resized()) mark_stale(false);
    // A minimized window has a 0×0 framebuffer: draw nothing, wait for events.
    const int w = window_.input().framebuffer_width, h = window_.input().framebuffer_height;  // no round trip
    if (w == 0 || h == 0 || (stale_ && !recreate_swapchain())) {
        glfwWaitEventsTimeout(0.1);
        return false;
    }

    slots_.wait(slot_);
    release_retired();
    const VkResult acquired = vkAcquireNextImageKHR(vk_.device(), swapchain_, UINT64_MAX, image_available_[slot_],
                                                    VK_NULL_HANDLE, &image_index_);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {  // no image, nothing signalled: recreate and try again
        mark_stale(false);
        return false;
    }
    if (acquired == VK_SUBOPTIMAL_KHR)
        mark_stale(true);  // the image is ours and its semaphore will signal: draw it, recreate next frame
    else if (acquired != VK_SUCCESS)
        throw_surface_error("vkAcquireNextImageKHR", acquired);
    slots_.reset_fence(slot_);  // only once we know we will submit, or the next wait would hang
    slots_.reset_commands(slot_);

    frame.cmd = slots_.command_buffer(slot_);
    frame.slot = slot_;
    frame.extent = extent_;
    begin_render_pass(frame, render_pass_, framebuffers_[image_index_], clear_linear, before_pass);
    return true;
}

void WindowTarget::end_frame(const AfterPass& after_pass) {
    VkCommandBuffer cmd = slots_.command_buffer(slot_);
    vkCmdEndRenderPass(cmd);
    if (accepts_copies_) {
        const VkImage image = images_[image_index_];
        if (after_pass) after_pass(cmd, image);
        // Copies done (the pass's own dependency ordered them after its colour writes): from
        // TRANSFER_DST_OPTIMAL to the layout presentation needs (it waits on the render-finished
        // semaphore, so no access to make visible).
        target_barrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                       VK_ACCESS_TRANSFER_WRITE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
    }
    VK_CHECK(vkEndCommandBuffer(cmd));

    VkSemaphore wait = image_available_[slot_];
    VkSemaphore signal = render_finished_[image_index_];
    const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &wait;
    submit.pWaitDstStageMask = &wait_stage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &signal;
    VK_CHECK(vkQueueSubmit(vk_.queue(), 1, &submit, slots_.fence(slot_)));

    VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &signal;
    present.swapchainCount = 1;
    present.pSwapchains = swapchain_.ptr();
    present.pImageIndices = &image_index_;
    const VkResult presented = vkQueuePresentKHR(vk_.queue(), &present);
    ++presents_;
    slot_ = (slot_ + 1) % kFramesInFlight;
    // Errors first, so that a pending resize never hides a lost surface; the swapchain itself is
    // recreated at the start of the next frame.
    if (presented == VK_ERROR_OUT_OF_DATE_KHR)
        mark_stale(false);
    else if (presented == VK_SUBOPTIMAL_KHR)
        mark_stale(true);
    else if (presented != VK_SUCCESS)
        throw_surface_error("vkQueuePresentKHR", presented);
    if (window_.take_resized()) mark_stale(false);
}

}  // namespace lab
