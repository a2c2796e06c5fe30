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

// Where a test writes its pictures and logs: build/test_output/<sub>, or $LAB_TEST_OUTPUT/<sub>
// (the exercises' grader, scripts/exercise.sh --prove, keeps its runs apart this way).
inline std::string test_output_dir(const std::string& sub) {
    const char* dir = std::getenv("LAB_TEST_OUTPUT");
    return (dir && *dir ? std::string(dir) : std::string(LAB_BINARY_DIR) + "/test_output") + "/" + sub;
}

// Runs `exe` with `args` (already quoted), stdout + stderr into `log_path`. With $LAB_EXE_DIR set
// the lab binary of the same name in that folder runs instead (the grader's build of a stubbed lab),
// and with $LAB_SHADER_DIR set too, it loads its shaders from there (--dev-shader-dir): the grader
// runs these tests and cannot put a flag on the lab's command line itself.
inline RunResult run_lab(const std::string& exe, const std::string& args, const std::string& log_path) {
    std::filesystem::create_directories(std::filesystem::path(log_path).parent_path());
    const char* exe_dir = std::getenv("LAB_EXE_DIR");
    const char* shader_dir = std::getenv("LAB_SHADER_DIR");
    const bool graded = exe_dir && *exe_dir;
    const std::string program = graded ? std::string(exe_dir) + "/" + std::filesystem::path(exe).filename().string() : exe;
    const std::string dev_args = graded && shader_dir && *shader_dir ? " --dev-shader-dir " + quoted(shader_dir) : "";
    const std::string command = quoted(program) + dev_args + " " + args + " > " + quoted(log_path) + " 2>&1";
    const int status = std::system(command.c_str());
    RunResult r;
    if (status != -1 && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
    r.log = read_text(log_path);
    return r;
}
