// dev_options.h — the switchboard for tests and measurements: every `--dev-…` flag, parsed once
// with the rest of the command line (cli.h) and listed by `--help-dev`, not by the students'
// `--help`. A lab's picture never depends on them, except lab 3's mip view and lab 4's two (what a
// headless run cannot do with the mouse: tint by mip level, animate the lights, show a light's map).
#pragma once

#include <string>
#include <vector>

namespace lab {

struct DevOptions {
    std::string status_file;        // --dev-status-file PATH: a window's line per frame (dev/status_file.h)
    int fail_after_submit = 0;      // --dev-fail-after-submit N: throw after the Nth submit (0: off)
    bool validation_probe = false;  // --dev-validation-probe: commit one mistake per validation check
    bool no_blit = false;           // --dev-no-blit: act as a device without image blits
    std::vector<std::string> without_features;  // --dev-without-feature NAME (repeatable): act as a device without it
    bool minimum_limits = false;    // --dev-minimum-limits: act as a device at the spec's least limits
    std::string shader_dir;         // --dev-shader-dir DIR: the compiled shaders from DIR
    std::string scene_dir;          // --dev-scene-dir DIR: the default scene from DIR
    bool animate_lights = false;    // --dev-animate-lights: lab 4's lights circle the Y axis
    int shadow_view = -1;           // --dev-shadow-view N: lab 4 shows light N's shadow map (-1: none)
    bool mip_view = false;          // --dev-mip-view: labs 3 and 4 start with the mip-level view on
    int warmup_ms = 1000;           // --dev-warmup-ms N: a benchmark's warm-up lasts at least N ms (dev/benchmark.h: why)
};

// One option of the command line (cli.cpp lists the students' ones, this file the developer ones).
struct OptionSpec {
    const char* name;  // without the leading "--"
    bool takes_value;
};
const std::vector<OptionSpec>& dev_option_specs();

// Sets the option `name` (one of dev_option_specs()) from `value`; throws CliError for a bad value.
void set_dev_option(DevOptions& dev, const std::string& name, const std::string& value);

std::string dev_usage(const std::string& program);

}  // namespace lab
