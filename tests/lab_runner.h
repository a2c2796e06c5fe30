// lab_runner.h — run a lab binary as a subprocess from a test, as a user would.
//
// No gtest here: tests/lab4_random_scenes.cpp (a plain program) renders through it too. The render
// tests' expectations on top of it are in lab_render.h.
#pragma once

#include "probe.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

// Single-quotes a path for /bin/sh.
inline std::string quoted(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

inline std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Writes `text` byte for byte to DIR/NAME (creating the folders) and returns that path: the tests'
// scene files, OBJ and MTL files.
inline std::string write_file(const std::string& dir, const std::string& name, const std::string& text) {
    const std::string path = dir + "/" + name;
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

struct RunResult {
    int exit_code = -1;  // −1: did not exit normally (crashed / killed)
    std::string log;     // stdout + stderr
};

// A lab's log as a failure message shows it: every line, but of the validation layer's messages
// ("validation error: …", "validation warning: …", often 300 characters and more; one missing
// barrier makes twenty) the first kShownMessages, each cut to kShownChars, then how many more there
// are and where the whole log is (`log_path`). So the test's hint and the first message stay in view.
inline std::string shown_log(const std::string& log, const std::string& log_path) {
    constexpr int kShownMessages = 3;
    constexpr std::size_t kShownChars = 200;
    std::string shown;
    std::size_t more_at = std::string::npos;  // where the count of the messages left out goes
    int messages = 0;
    std::istringstream lines(log);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("validation ", 0) == 0) {
            if (++messages > kShownMessages) {
                if (more_at == std::string::npos) more_at = shown.size();
                continue;
            }
            if (line.size() > kShownChars) {
                std::size_t cut = kShownChars;
                while (cut > 0 && (static_cast<unsigned char>(line[cut]) & 0xC0) == 0x80) --cut;  // whole UTF-8 characters
                line = line.substr(0, cut) + " … (cut)";
            }
        }
        shown += line + "\n";
    }
    if (more_at != std::string::npos)
        shown.insert(more_at, "(" + std::to_string(messages - kShownMessages) + " more validation messages, " +
                                  std::to_string(messages) + " in all, whole in the log: " + log_path + ")\n");
    return shown;
}

// Where a test writes its pictures and logs: build/test_output/<sub>, or $LAB_TEST_OUTPUT/<sub>
// (the exercises' grader, scripts/exercise.sh --prove, keeps its runs apart this way).
inline std::string test_output_dir(const std::string& sub) {
    const char* dir = std::getenv("LAB_TEST_OUTPUT");
    return (dir && *dir ? std::string(dir) : std::string(LAB_BINARY_DIR) + "/test_output") + "/" + sub;
}

// The command that runs `exe`. The grader (scripts/exercise.sh --prove) cannot put a flag on the
// lab's command line, so it names the lab it graded by two variables: $LAB_SHADER_DIR, the stubbed
// shaders it compiled (…/shaders/<lab>), and $LAB_EXE_DIR, the folder of its build of that lab. That
// lab's binary then runs from there, loading those shaders (--dev-shader-dir); another lab's binary
// (lab 3's test of lab 2's scene runs lab 2 too) runs as built, with its own shaders.
inline std::string lab_command(const std::string& exe) {
    const char* exe_dir = std::getenv("LAB_EXE_DIR");
    const char* shader_dir = std::getenv("LAB_SHADER_DIR");
    if (!exe_dir || !*exe_dir || !shader_dir || !*shader_dir) return quoted(exe);
    const std::string name = std::filesystem::path(exe).filename().string();
    std::filesystem::path shaders(shader_dir);
    if (!shaders.has_filename()) shaders = shaders.parent_path();  // a trailing '/'
    if (shaders.filename().string() != name) return quoted(exe);
    return quoted(std::string(exe_dir) + "/" + name) + " --dev-shader-dir " + quoted(shader_dir);
}

// Runs `exe` (lab_command) with `args` (already quoted), stdout + stderr into `log_path`.
// The exit code and the log are what the lab computed (LAB_PROBE, probe.h: the class grader's judge
// reads them back instead of running the lab, and writes the log where the run left it).
inline RunResult run_lab(const std::string& exe, const std::string& args, const std::string& log_path) {
    std::filesystem::create_directories(std::filesystem::path(log_path).parent_path());
    const std::string command = lab_command(exe) + " " + args + " > " + quoted(log_path) + " 2>&1";
    RunResult r;
    r.exit_code = LAB_PROBE([&] {
        const int status = std::system(command.c_str());
        return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }());
    r.log = LAB_PROBE(read_text(log_path));
    if (lab_probe::replaying()) std::ofstream(log_path, std::ios::binary) << r.log;
    return r;
}

// run_lab() in a window, under a virtual X server (xvfb-run). The lab's own exit code is written to
// LOG.exit and read back, since xvfb-run's exit code and messages about its own clean-up (in
// LOG.xvfb) are not the lab's.
inline RunResult run_lab_in_window(const std::string& exe, const std::string& args, const std::string& log_path) {
    std::filesystem::create_directories(std::filesystem::path(log_path).parent_path());
    const std::string code_file = log_path + ".exit";
    std::error_code ec;
    std::filesystem::remove(code_file, ec);
    const std::string lab = lab_command(exe) + " " + args + " > " + quoted(log_path) + " 2>&1; echo $? > " + quoted(code_file);
    const std::string command =
        "xvfb-run -a -s '-screen 0 1280x800x24' sh -c " + quoted(lab) + " > " + quoted(log_path + ".xvfb") + " 2>&1";
    std::system(command.c_str());
    RunResult r;
    const std::string code = read_text(code_file);
    if (!code.empty()) r.exit_code = std::stoi(code);
    r.log = read_text(log_path);
    return r;
}

// ---------------------------------------------------------------- headless renders

// The command line of a headless render with validation on (any message fails the run):
//     --scene SCENE --headless --validate --out PNG --width W --height H [EXTRA]
inline std::string render_args(const std::string& scene, const std::string& png, int width, int height,
                               const std::string& extra = "") {
    return "--scene " + quoted(scene) + " --headless --validate --out " + quoted(png) + " --width " +
           std::to_string(width) + " --height " + std::to_string(height) + (extra.empty() ? "" : " " + extra);
}

struct RenderResult : RunResult {
    std::string exe, args;  // the command line run (`exe args` reproduces it)
    std::string scene;
    std::string png;        // where the picture was asked for: DIR/NAME.png
    std::string log_path;   // DIR/NAME.log
    bool wrote_png = false; // this run left a PNG there (an older one is removed before the run)

    bool ok() const { return exit_code == 0 && wrote_png; }
    std::string command() const { return exe + " " + args; }
    // How the run ended, one line: "lab4_shadows exited 1", "... wrote no PNG", "... crashed".
    std::string outcome() const {
        const std::string lab = std::filesystem::path(exe).filename().string();
        if (exit_code < 0) return lab + " did not exit normally (crashed or killed)";
        if (exit_code == 0 && !wrote_png) return lab + " exited 0 but wrote no PNG (" + png + ")";
        return lab + " exited " + std::to_string(exit_code);
    }
    // Why the run is not ok(), for a failure message: the outcome, the command, the log (shown_log()).
    std::string failure() const {
        return outcome() + " on " + scene + "\n  command: " + command() + "\n  log (" + log_path + "):\n" +
               shown_log(log, log_path);
    }
};

// Renders `scene` with the lab binary `exe`, headless with validation on, at width × height into
// OUT_DIR/NAME.png, the log in OUT_DIR/NAME.log; `extra_args` (already quoted: --dev-… flags) go
// last. Expects nothing: the caller judges exit code, log and picture.
inline RenderResult render_lab(const std::string& exe, const std::string& scene, const std::string& out_dir,
                               const std::string& name, int width, int height, const std::string& extra_args = "") {
    RenderResult r;
    r.exe = exe;
    r.scene = scene;
    r.png = out_dir + "/" + name + ".png";
    r.log_path = out_dir + "/" + name + ".log";
    r.args = render_args(scene, r.png, width, height, extra_args);
    std::error_code ec;
    std::filesystem::remove(r.png, ec);
    static_cast<RunResult&>(r) = run_lab(exe, r.args, r.log_path);
    // The picture, as the lab wrote it (the judge writes the recorded one back).
    r.wrote_png = LAB_PROBE(std::filesystem::exists(r.png));
    if (r.wrote_png) {
        const std::string png = LAB_PROBE(read_text(r.png));
        if (lab_probe::replaying()) std::ofstream(r.png, std::ios::binary) << png;
    }
    return r;
}
