// vk_handle.h — RAII ownership for any Vulkan handle.
//
// A Handle<VkFoo> owns one VkFoo and a function that destroys it; it is
// movable, not copyable, and destroys its object exactly once. Objects are
// destroyed in reverse order of declaration, so declare them in creation order.
#pragma once

#include <functional>
#include <utility>

namespace lab {

template <typename T>
class Handle {
public:
    Handle() = default;
    Handle(T handle, std::function<void(T)> destroy) : handle_(handle), destroy_(std::move(destroy)) {}
    ~Handle() { reset(); }

    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    Handle(Handle&& other) noexcept { *this = std::move(other); }
    Handle& operator=(Handle&& other) noexcept {
        if (this != &other) {
            reset();
            handle_ = std::exchange(other.handle_, T{});
            destroy_ = std::move(other.destroy_);
        }
        return *this;
    }

    T get() const { return handle_; }
    operator T() const { return handle_; }  // so a Handle passes straight to vk* calls
    const T* ptr() const { return &handle_; }
    explicit operator bool() const { return handle_ != T{}; }

    void reset() {
        if (handle_ != T{} && destroy_) destroy_(handle_);
        handle_ = T{};
    }

private:
    T handle_{};
    std::function<void(T)> destroy_;
};

}  // namespace lab
