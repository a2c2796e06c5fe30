// run_lab.cpp — the entry point (run_lab.h): bad input is found before anything is drawn, and each
// kind of failure becomes one line on stderr and its exit code.
#include "run_lab.h"

#include "cli.h"
#include "vk_check.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace lab {

int run_lab(int argc, char** argv, const LabInfo& info,
            const std::function<void(LabApp& app, const Scene& scene)>& body) {
    const std::string name = info.name;
    int validation_messages = 0;
    try {
        Options options = parse_command_line(argc, argv, info.default_scene);
        if (options.help || options.help_dev) {
            std::printf("%s", options.help ? usage(name).c_str() : dev_usage(name).c_str());
            return 0;
        }
        if (!options.dev.scene_dir.empty() && options.scene == info.default_scene)  // the scene folder moved
            options.scene = options.dev.scene_dir + "/" + std::filesystem::path(info.default_scene).filename().string();
        if (!options.out.empty()) {  // fail before rendering, not after
            const std::filesystem::path folder = std::filesystem::absolute(options.out).parent_path();
            if (!std::filesystem::is_directory(folder))
                throw CliError("--out " + options.out + ": folder " + folder.string() + " does not exist");
        }
        const Scene scene = load_scene(options.scene);
        {
            LabApp app(info, options, &validation_messages);
            body(app, scene);
        }  // everything Vulkan is destroyed here, so leaks are reported before we count
        if (validation_messages > 0) {
            std::fprintf(stderr, "%s: error: %d validation message%s (see above)\n", name.c_str(), validation_messages,
                         validation_messages == 1 ? "" : "s");
            return 1;
        }
        return 0;
    } catch (const CliError& e) {
        const std::string message = e.what();
        const bool has_hint = message.find("--help") != std::string::npos || message.find("did you mean") != std::string::npos;
        std::fprintf(stderr, "%s: error: %s%s\n", name.c_str(), message.c_str(), has_hint ? "" : " (try --help)");
        return 2;
    } catch (const SceneError& e) {
        std::fprintf(stderr, "%s: error: %s\n", name.c_str(), e.what());
        return 2;
    } catch (const VulkanError& e) {
        std::fprintf(stderr, "%s: error: %s\n", name.c_str(), e.what());
        return 1;
    } catch (const std::runtime_error& e) {  // bad input found while loading (meshes, images)
        std::fprintf(stderr, "%s: error: %s\n", name.c_str(), e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", name.c_str(), e.what());
        return 1;
    }
}

}  // namespace lab
