// exercise_hints.cpp — linked into every test binary: when a test fails, it names the exercises
// it grades (scripts/exercise.sh), where they are, and whether they are still stubs.
//
// The labs mark an exercise's code with "// EXERCISE name: hint. Checked by Suite.Test, Suite.*."
// (a student copy has "// TODO EXERCISE ..." there). A failing test whose name matches one of the
// "Checked by" patterns prints, for example:
//     [ exercise ] this test grades exercise `attenuation`: shaders/lab2_lighting/lighting.glsl:97,
//                  still the stub (TODO). Hint: what fraction of a light's radiance is left ...
#include <gtest/gtest.h>

#include <fnmatch.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct Marker {
    std::string name, file, hint;
    int line = 0;
    bool stub = false;  // "// TODO EXERCISE": the student copy, not done yet
    std::vector<std::string> tests;
};

// Every marker in the lab folders (lab<N>_*/) and their shader folders, labs in order.
std::vector<Marker> scan_markers(const fs::path& root) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (const fs::path& top : {root, root / "shaders"}) {
        if (!fs::is_directory(top, ec)) continue;
        for (const auto& lab : fs::directory_iterator(top, ec)) {
            const std::string name = lab.path().filename().string();
            if (!lab.is_directory() || name.rfind("lab", 0) != 0) continue;
            for (const auto& f : fs::recursive_directory_iterator(lab.path(), ec))
                if (f.is_regular_file() && f.path().extension() != ".md") files.push_back(f.path());
        }
    }
    std::sort(files.begin(), files.end());
    std::vector<Marker> markers;
    for (const fs::path& file : files) {
        std::ifstream in(file);
        std::string text;
        for (int line = 1; std::getline(in, text); ++line) {
            // "// [TODO ]EXERCISE name: hint[ Checked by A.B, C.*.]"
            size_t at = text.find("// EXERCISE ");
            bool stub = false;
            if (at == std::string::npos) {
                at = text.find("// TODO EXERCISE ");
                if (at == std::string::npos) continue;
                stub = true;
            }
            const size_t name_at = text.find("EXERCISE ", at) + 9;
            const size_t colon = text.find(": ", name_at);
            if (colon == std::string::npos) continue;
            const std::string name = text.substr(name_at, colon - name_at);
            if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") != std::string::npos)
                continue;
            std::string hint = text.substr(colon + 2), tests;
            const size_t checked = hint.find(" Checked by ");
            if (checked != std::string::npos) {
                tests = hint.substr(checked + 12);
                hint.erase(checked);
                if (!tests.empty() && tests.back() == '.') tests.pop_back();
            }
            Marker mk{name, fs::relative(file, root).string(), hint, line, stub, {}};
            std::replace(tests.begin(), tests.end(), ',', ' ');
            std::istringstream words(tests);
            for (std::string t; words >> t;) mk.tests.push_back(t);
            markers.push_back(mk);
        }
    }
    return markers;
}

class ExerciseHints : public ::testing::EmptyTestEventListener {
    void OnTestEnd(const ::testing::TestInfo& info) override {
        if (!info.result()->Failed()) return;
        static const std::vector<Marker> markers = scan_markers(LAB_SOURCE_DIR);
        const std::string full = std::string(info.test_suite_name()) + "." + info.name();
        // One line per exercise: a stub (TODO) wins over a finished copy of the same exercise.
        std::vector<const Marker*> hits;
        for (const Marker& m : markers) {
            const bool matches = std::any_of(m.tests.begin(), m.tests.end(), [&](const std::string& pattern) {
                return fnmatch(pattern.c_str(), full.c_str(), 0) == 0;
            });
            if (!matches) continue;
            auto same = std::find_if(hits.begin(), hits.end(), [&](const Marker* h) { return h->name == m.name; });
            if (same == hits.end()) hits.push_back(&m);
            else if (m.stub && !(*same)->stub) *same = &m;
        }
        for (const Marker* m : hits)
            std::printf("[ exercise ] this test grades exercise `%s`: %s:%d, %s. Hint: %s\n", m->name.c_str(),
                        m->file.c_str(), m->line, m->stub ? "still the stub (TODO)" : "compare with the lab's code",
                        m->hint.c_str());
        if (hits.empty()) {
            // Not named by any exercise, but a student copy may still have stubs that it depends on.
            for (const Marker& m : markers)
                if (m.stub) hits.push_back(&m);
            for (const Marker* m : hits)
                std::printf("[ exercise ] not done yet in this copy: `%s`, %s:%d\n", m->name.c_str(), m->file.c_str(),
                            m->line);
        }
        if (!hits.empty())
            std::printf("[ exercise ] pictures (actual | expected | difference): build/test_output/\n");
    }
};

// Registered before main() runs the tests.
[[maybe_unused]] const bool registered = [] {
    ::testing::UnitTest::GetInstance()->listeners().Append(new ExerciseHints);
    return true;
}();

}  // namespace
