#include "dev_options.h"

#include "cli.h"
#include "vk_context.h"

#include <algorithm>

namespace lab {

const std::vector<OptionSpec>& dev_option_specs() {
    static const std::vector<OptionSpec> specs = {
        {"dev-status-file", true}, {"dev-fail-after-submit", true}, {"dev-validation-probe", false},
        {"dev-no-blit", false},    {"dev-shader-dir", true},        {"dev-scene-dir", true},
        {"dev-animate-lights", false}, {"dev-shadow-view", true},   {"dev-mip-view", false},
        {"dev-warmup-ms", true}, {"dev-without-feature", true}, {"dev-minimum-limits", false},
    };
    return specs;
}

void set_dev_option(DevOptions& dev, const std::string& name, const std::string& value) {
    const std::string option = "--" + name;
    if (name == "dev-status-file") {
        dev.status_file = value;
    } else if (name == "dev-fail-after-submit") {
        dev.fail_after_submit = int(parse_whole_number(option, value, 1, 1000000));
    } else if (name == "dev-validation-probe") {
        dev.validation_probe = true;
    } else if (name == "dev-no-blit") {
        dev.no_blit = true;
    } else if (name == "dev-shader-dir") {
        dev.shader_dir = value;
    } else if (name == "dev-scene-dir") {
        dev.scene_dir = value;
    } else if (name == "dev-animate-lights") {
        dev.animate_lights = true;
    } else if (name == "dev-shadow-view") {
        dev.shadow_view = int(parse_whole_number(option, value, 0, 1000));
    } else if (name == "dev-mip-view") {
        dev.mip_view = true;
    } else if (name == "dev-warmup-ms") {
        dev.warmup_ms = int(parse_whole_number(option, value, 0, 600000));
    } else if (name == "dev-minimum-limits") {
        dev.minimum_limits = true;
    } else if (name == "dev-without-feature") {
        const std::vector<std::string>& known = fakeable_features();
        if (std::find(known.begin(), known.end(), value) == known.end()) {
            std::string list;
            for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
            throw CliError(option + ": unknown feature '" + value + "' (one of " + list + ")");
        }
        dev.without_features.push_back(value);
    }
}

std::string dev_usage(const std::string& program) {
    return "usage: " + program + " [options] [developer options]\n"
           "\n"
           "developer options, for tests and measurements (--help lists the others):\n"
           "  --dev-status-file PATH     in a window, rewrite PATH after every frame with\n"
           "                             \"frame=N width=W height=H\" (\" idle\" appended once idle)\n"
           "  --dev-fail-after-submit N  throw right after the Nth frame is submitted, as a lost\n"
           "                             device would (the run must still end validation-clean)\n"
           "  --dev-validation-probe     with --validate: commit one mistake for each validation\n"
           "                             check, to prove the checks are on\n"
           "  --dev-no-blit              act as a device without image blits: mip chains come\n"
           "                             from the CPU fallback\n"
           "  --dev-shader-dir DIR       load the compiled shaders from DIR (the exercises' grader)\n"
           "  --dev-scene-dir DIR        look for the lab's default scene in DIR\n"
           "  --dev-animate-lights       lab 4: the lights circle the Y axis (every shadow map is\n"
           "                             re-rendered every frame: what --benchmark times)\n"
           "  --dev-shadow-view N        lab 4: show light N's shadow map (headless pictures)\n"
           "  --dev-mip-view             labs 3 and 4: start with the mip-level view on (each\n"
           "                             textured pixel tinted by the mip level it reads)\n"
           "  --dev-warmup-ms N          --benchmark: warm up for at least N ms (default 1000)\n"
           "                             before timing: an idle GPU's clock may need time to rise\n"
           "  --dev-without-feature NAME act as a device without the optional feature NAME\n"
           "                             (repeatable): fragmentStoresAndAtomics, samplerAnisotropy,\n"
           "                             depthClamp, depthBiasClamp or timestamps; the lab takes\n"
           "                             the path it takes on such a device\n"
           "  --dev-minimum-limits       act as a device whose limits are the least the Vulkan\n"
           "                             specification allows (image, buffer and descriptor counts)\n"
           "  --help-dev                 show this help and exit\n";
}

}  // namespace lab
