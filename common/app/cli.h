// cli.h — the command line every lab shares.
#pragma once

#include "dev_options.h"

#include <cstdint>
#include <stdexcept>
#include <string>

namespace lab {

struct Options {
    std::string scene;         // scene file (default: the lab's scene in scenes/)
    bool headless = false;     // render offscreen, no window
    std::string out;           // PNG written after the last headless frame
    uint32_t width = 1280;
    uint32_t height = 720;
    int frames = 0;            // frames to render; 0 = until the window closes (headless: 1)
    bool validate = false;     // Khronos validation; any message makes the run fail
    int benchmark = 0;         // render N frames and print frame-time statistics (headless unless --window)
    bool window = false;       // --window: a benchmark in a window (measures the present path too)
    bool help = false;
    bool help_dev = false;     // --help-dev: the developer options (dev_options.h)
    DevOptions dev;            // --dev-…: tests and measurements
};

// Bad command lines throw CliError (the lab prints it and exits with code 2).
class CliError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A whole number in [lo, hi] for `option`; "12abc", "1.5", "" and overflow throw CliError.
long long parse_whole_number(const std::string& option, const std::string& text, long long lo, long long hi);

Options parse_command_line(int argc, const char* const* argv, const std::string& default_scene);
std::string usage(const std::string& program);

}  // namespace lab
