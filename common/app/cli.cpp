// cli.cpp — the command line every lab shares (see usage() for the options).
//
// Both "--width 800" and "--width=800" work. Every mistake throws CliError with
// one line that names the option, so a typo never silently runs with defaults.
#include "cli.h"

#include "text_match.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <vector>

namespace lab {
namespace {

// A bound for the command line only. What a device allows (maxImageDimension2D and
// maxFramebufferWidth/Height: Vulkan guarantees 4096, desktop GPUs offer 16384 or 32768) is
// checked once the device is known (check_image_size() in lab_app.cpp): same one-line error, exit 2.
// The bound sits above every device's limit, so a user always meets the device's own answer (an
// H100 allows 32768: with a bound of 32768 its check could never be reached).
constexpr long long kMaxImageSide = 65536;

std::string lower(const std::string& s) { return to_lower(s); }

// The students' options, then the developer ones (dev_options.h).
const std::vector<OptionSpec>& option_specs() {
    static const std::vector<OptionSpec> specs = [] {
        std::vector<OptionSpec> all = {
            {"scene", true},  {"headless", false}, {"out", true},       {"width", true},
            {"height", true}, {"frames", true},    {"validate", false}, {"benchmark", true},
            {"window", false}, {"help", false},    {"help-dev", false},
        };
        all.insert(all.end(), dev_option_specs().begin(), dev_option_specs().end());
        return all;
    }();
    return specs;
}

// "--heigth" -> " (did you mean --height?)"
std::string did_you_mean(const std::string& name) {
    std::vector<std::string> names;
    for (const auto& spec : option_specs()) names.push_back(spec.name);
    const std::string best = closest_match(name, names, 2);  // at most 2 letters off
    const char* help = name.rfind("dev-", 0) == 0 ? " (see --help-dev)" : " (see --help)";
    return best.empty() ? help : " (did you mean --" + best + "?)";
}

}  // namespace

long long parse_whole_number(const std::string& option, const std::string& text, long long lo, long long hi) {
    size_t i = (!text.empty() && (text[0] == '-' || text[0] == '+')) ? 1 : 0;
    const bool digits = i < text.size() &&
                        std::all_of(text.begin() + static_cast<long>(i), text.end(),
                                    [](unsigned char c) { return std::isdigit(c) != 0; });
    if (!digits) throw CliError(option + ": expected a whole number, got '" + text + "'");
    const std::string range = " (allowed: " + std::to_string(lo) + ".." + std::to_string(hi) + ")";
    // Compare digit strings before converting so that huge values cannot overflow.
    if (text.size() - i > 18) throw CliError(option + ": " + text + " is out of range" + range);
    const long long v = std::stoll(text);
    if (v < lo || v > hi) throw CliError(option + ": " + text + " is out of range" + range);
    return v;
}

Options parse_command_line(int argc, const char* const* argv, const std::string& default_scene) {
    Options o;
    o.scene = default_scene;
    std::vector<std::string> args(argv + std::min(argc, 1), argv + std::max(argc, 0));

    // --help wins over everything else, even over mistakes elsewhere on the line.
    for (const auto& a : args) {
        if (a == "--help" || a == "-h") o.help = true;
        if (a == "--help-dev") o.help_dev = true;
        if (o.help || o.help_dev) return o;
    }

    bool headless_asked = false;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg.size() > 1 && arg[0] == '-' && arg[1] != '-')
            throw CliError("unknown option '" + arg + "' (long options start with --; see --help)");
        if (arg.rfind("--", 0) != 0) {
            const bool looks_like_scene = lower(arg).size() > 5 &&
                                          lower(arg).compare(arg.size() - 5, 5, ".json") == 0;
            throw CliError("unexpected argument '" + arg + "'" +
                           (looks_like_scene ? " (did you mean --scene " + arg + "?)" : " (see --help)"));
        }
        // Split "--name=value" / "--name".
        const size_t eq = arg.find('=');
        const std::string name = arg.substr(2, eq == std::string::npos ? std::string::npos : eq - 2);
        const std::string option = "--" + name;
        auto spec = std::find_if(option_specs().begin(), option_specs().end(),
                                 [&](const OptionSpec& s) { return name == s.name; });
        if (spec == option_specs().end()) throw CliError("unknown option '" + option + "'" + did_you_mean(name));

        std::string value;
        if (!spec->takes_value) {
            if (eq != std::string::npos) throw CliError(option + " takes no value (got '" + arg + "')");
        } else if (eq != std::string::npos) {
            value = arg.substr(eq + 1);
            if (value.empty()) throw CliError(option + ": missing value after '='");
        } else {
            // The next argument is the value, unless there is none or it is the next option.
            if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0)
                throw CliError(option + ": missing value");
            value = args[++i];
        }

        if (name == "scene") {
            o.scene = value;
        } else if (name == "headless") {
            o.headless = true;
            headless_asked = true;
        } else if (name == "out") {
            if (lower(value).size() < 5 || lower(value).compare(value.size() - 4, 4, ".png") != 0)
                throw CliError(option + ": the file name must end in .png, got '" + value + "'");
            o.out = value;
            o.headless = true;  // a PNG comes from a headless render
        } else if (name == "width") {
            o.width = static_cast<uint32_t>(parse_whole_number(option, value, 1, kMaxImageSide));
        } else if (name == "height") {
            o.height = static_cast<uint32_t>(parse_whole_number(option, value, 1, kMaxImageSide));
        } else if (name == "frames") {
            o.frames = static_cast<int>(parse_whole_number(option, value, 1, INT_MAX));
        } else if (name == "validate") {
            o.validate = true;
        } else if (name == "benchmark") {
            o.benchmark = static_cast<int>(parse_whole_number(option, value, 1, INT_MAX));
        } else if (name == "window") {
            o.window = true;
        } else {
            set_dev_option(o.dev, name, value);
        }
    }
    // A benchmark is headless (rendering alone) unless --window asks for the whole window path.
    if (o.benchmark > 0 && !o.window) o.headless = true;
    if (o.window) {
        if (headless_asked || !o.out.empty())
            throw CliError(std::string("--window cannot be combined with ") + (headless_asked ? "--headless" : "--out") +
                           " (a window renders on screen, not offscreen)");
        o.headless = false;
    }
    return o;
}

std::string usage(const std::string& program) {
    return "usage: " + program + " [options]\n"
           "\n"
           "options (--name value or --name=value):\n"
           "  --scene FILE      scene file to render (default: the lab's own scene in scenes/)\n"
           "  --headless        render offscreen, without a window\n"
           "  --out FILE.png    write the last headless frame to FILE.png (implies --headless)\n"
           "  --width W         image width in pixels, 1..65536 and at most what the\n"
           "                    Vulkan device allows (16384 or 32768; default: 1280)\n"
           "  --height H        image height in pixels, likewise (default: 720)\n"
           "  --frames N        render N >= 1 frames, then exit\n"
           "                    (default: until the window closes; headless: 1)\n"
           "  --validate        enable the Khronos validation layer; any message fails the run\n"
           "  --benchmark N     render N >= 1 headless frames and print frame-time statistics\n"
           "                    (implies --headless, unless --window)\n"
           "  --window          with --benchmark: measure in a window (rendering + UI + present)\n"
           "  -h, --help        show this help and exit\n"
           "\n"
           "A bad command line prints one error line and exits with code 2.\n";
}

}  // namespace lab
