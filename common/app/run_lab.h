// run_lab.h — a lab's entry point: the command line, the scene, the LabApp, and an exit code.
//
// A lab's main() is:
//     return lab::run_lab(argc, argv, info, [](lab::LabApp& app, const lab::Scene& scene) {
//         ... create the lab's renderer ...
//         lab::LabApp::Callbacks frame;
//         frame.update = [&](float dt) { ... };
//         frame.record = [&](const lab::Frame& f) { ... };
//         ...
//         app.run(frame);
//     });
// run_lab() turns every failure into one line on stderr and an exit code:
// 0 success, 1 Vulkan/system failure or validation messages, 2 bad input.
#pragma once

#include "lab_app.h"
#include "scene.h"

#include <functional>

namespace lab {

int run_lab(int argc, char** argv, const LabInfo& info,
            const std::function<void(LabApp& app, const Scene& scene)>& body);

}  // namespace lab
