#include "scene_reloader.h"

#include <cstdio>
#include <system_error>

namespace lab {

SceneReloader::SceneReloader(std::string file, Scene initial)
    : file_(std::move(file)), scene_(std::move(initial)), last_time_(modified_time()) {}

std::filesystem::file_time_type SceneReloader::modified_time() const {
    std::error_code ec;  // a file that is being rewritten may briefly not exist
    const auto t = std::filesystem::last_write_time(file_, ec);
    return ec ? last_time_ : t;
}

bool SceneReloader::poll(bool force, const std::function<void(const Scene&)>& apply) {
    // Looking at the file system costs a system call: twice a second is plenty.
    const auto now = std::chrono::steady_clock::now();
    if (!force && now - last_check_ < std::chrono::milliseconds(500)) return false;
    last_check_ = now;
    const auto t = modified_time();
    if (!force && t == last_time_) return false;
    last_time_ = t;

    try {
        Scene fresh = load_scene(file_);
        apply(fresh);
        scene_ = std::move(fresh);
        error_.clear();
        std::printf("reloaded %s\n", file_.c_str());
        std::fflush(stdout);  // seen at once when stdout is a file or a pipe (bench/soak.py reads it)
        return true;
    } catch (const std::exception& e) {
        error_ = e.what();
        std::fprintf(stderr, "reload failed, keeping the last good scene: %s\n", e.what());
        return true;  // the panel shows the error
    }
}

}  // namespace lab
