// window_target.h — a GLFW window and the swapchain that presents to it.
#pragma once

#include "render_target.h"

#include <array>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

struct GLFWwindow;

namespace lab {

// The GLFW window itself (created before Vulkan: the instance needs its extensions).
class Window {
public:
    Window(const std::string& title, uint32_t width, uint32_t height);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    GLFWwindow* handle() const { return window_; }
    void show();  // the window is created hidden (LabApp checks the size against the device first)
    bool should_close() const;
    // Set by the resize callback; cleared by whoever recreates the swapchain.
    bool take_resized();
    // Mouse-wheel steps since the last call.
    float take_scroll();
    // Whether `glfw_key` was pressed since the last call for it (each press counts once, even
    // when two presses, or a press and its release, arrive between two frames).
    bool take_key_press(int glfw_key);

    // ---- Input as the event callbacks left it, for the frame loop and the UI.
    // Every glfwGet* of window state (cursor, sizes, focus) is a round trip to the X server,
    // which first finishes everything queued before it (the last frame's whole image): the
    // loop asks these instead, kept up to date by callbacks, and never waits on the server.
    struct Input {
        glm::dvec2 cursor{0.0};      // pixels from the window's top-left corner
        bool cursor_inside = false;
        bool focused = false;
        int width = 0, height = 0;                         // window size in screen coordinates
        int framebuffer_width = 0, framebuffer_height = 0;  // in pixels
        std::array<bool, 8> mouse_down{};     // GLFW_MOUSE_BUTTON_1..8
        std::array<bool, 8> mouse_clicked{};  // went down since the last take_clicks()
        int keys_down = 0;                    // keys held right now
    };
    const Input& input() const { return input_; }
    std::array<bool, 8> take_clicks();  // a press and release between two frames still counts
    // Events (input, resize, expose, focus) seen so far: the frame loop draws when it changes.
    uint64_t event_count() const { return events_; }
    // A key or mouse button is held: the picture may change every frame (moving, dragging).
    bool input_held() const;
    // Sleeps until an event arrives or `timeout_seconds` pass (render on demand).
    void wait_events(double timeout_seconds) const;

private:
    void watch_input();  // installs the callbacks that keep input_ and events_ current

    GLFWwindow* window_ = nullptr;
    bool resized_ = false;
    float scroll_ = 0.0f;
    Input input_;
    std::array<bool, 512> key_held_{};  // by GLFW key code (GLFW_KEY_LAST = 348)
    std::array<int, 512> key_presses_{};  // presses not taken yet (take_key_press)
    uint64_t events_ = 0;
};

class WindowTarget : public RenderTarget {
public:
    WindowTarget(const VulkanContext& vk, Window& window);
    ~WindowTarget() override;

    VkRenderPass render_pass() const override { return render_pass_; }
    VkExtent2D extent() const override { return extent_; }
    VkFormat color_format() const { return surface_format_.format; }
    bool begin_frame(const glm::vec3& clear_linear, Frame& frame, const BeforePass& before_pass = {}) override;
    void end_frame(const AfterPass& after_pass = {}) override;
    // The slot the next frame will use was the previous frame's: wait for it there.
    void wait_for_previous_frame() const override { slots_.wait(slot_); }

    // Whether the swapchain images accept transfers (the surface allows TRANSFER_DST usage); if
    // not, `after_pass` is not called.
    bool accepts_copies() const { return accepts_copies_; }
    uint32_t image_count() const { return static_cast<uint32_t>(images_.size()); }

private:
    bool create_swapchain();  // false (and nothing changed) while the surface is 0×0
    void destroy_swapchain_images();
    bool recreate_swapchain();
    void mark_stale(bool suboptimal);
    void release_retired();

    const VulkanContext& vk_;
    Window& window_;
    VkSurfaceFormatKHR surface_format_{};
    bool accepts_copies_ = false;  // swapchain images made with TRANSFER_DST usage
    Handle<VkRenderPass> render_pass_;
    Handle<VkSwapchainKHR> swapchain_;
    VkExtent2D extent_{};
    // Per swapchain image: its view, framebuffer and render-finished semaphore.
    // (The semaphore must be per image, not per frame in flight: presentation
    // may still hold it when the frame slot comes round again.)
    std::vector<VkImage> images_;
    std::vector<Handle<VkImageView>> views_;
    std::vector<Handle<VkFramebuffer>> framebuffers_;
    std::vector<Handle<VkSemaphore>> render_finished_;
    Image depth_;
    // Per frame in flight.
    FrameSlots slots_;
    std::array<Handle<VkSemaphore>, kFramesInFlight> image_available_;
    uint32_t slot_ = 0;
    uint32_t image_index_ = 0;
    // Recreation: `stale_` asks for a new swapchain at the next begin_frame(); a surface that
    // stays suboptimal is recreated for once per change (`suboptimal_handled_`).
    bool stale_ = false;
    bool suboptimal_handled_ = false;
    // Old swapchains and their render-finished semaphores, kept until kFramesInFlight more presents.
    struct Retired {
        Handle<VkSwapchainKHR> swapchain;
        std::vector<Handle<VkSemaphore>> semaphores;
        uint64_t destroy_after = 0;  // value of presents_
    };
    std::deque<Retired> retired_;
    uint64_t presents_ = 0;
};

}  // namespace lab
