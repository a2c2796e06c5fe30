// scene_reloader.h — reload the scene file while a lab runs.
//
// poll() reloads when asked (a key) or when the file's modification time
// changed. A reload that fails — bad JSON, a broken model, anything `apply`
// throws — keeps the last good scene and remembers the one-line error for the UI.
#pragma once

#include "scene.h"

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>

namespace lab {

class SceneReloader {
public:
    SceneReloader(std::string file, Scene initial);

    // `apply` builds whatever depends on the scene (the renderer); when it
    // throws, the new scene is dropped. Returns true when something to show changed:
    // a new scene was applied, or a reload failed (error() has the new message).
    bool poll(bool force, const std::function<void(const Scene&)>& apply);

    const Scene& scene() const { return scene_; }
    const std::string& error() const { return error_; }  // "" after a good (re)load
    const std::string& file() const { return file_; }

private:
    std::filesystem::file_time_type modified_time() const;

    std::string file_;
    Scene scene_;
    std::string error_;
    std::filesystem::file_time_type last_time_{};
    std::chrono::steady_clock::time_point last_check_{};
};

}  // namespace lab
