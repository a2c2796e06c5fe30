// lab_runner.h — run a lab binary as a subprocess from a test, as a user would.
#pragma once

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

struct RunResult {
    int exit_code = -1;  // −1: did not exit normally (crashed / killed)
    std::string log;     // stdout + stderr
};

// Runs `exe` with `args` (already quoted), stdout + stderr into `log_path`.
inline RunResult run_lab(const std::string& exe, const std::string& args, const std::string& log_path) {
    std::filesystem::create_directories(std::filesystem::path(log_path).parent_path());
    const std::string command = quoted(exe) + " " + args + " > " + quoted(log_path) + " 2>&1";
    const int status = std::system(command.c_str());
    RunResult r;
    if (status != -1 && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
    r.log = read_text(log_path);
    return r;
}
