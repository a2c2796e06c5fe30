// exercise_hints_listener.cpp — the gtest listener of every gtest program (tests/CMakeLists.txt links
// it as an object file, so its registration below always runs): at a test's first failure it prints
// the test's hint (tests/exercise_hints.cpp) before gtest prints the failure, and at the program's
// end, when two or more tests failed, one line per failing test. It also starts the probe's record
// of each test (tests/probe.h).
#include "exercise_hints.h"
#include "probe.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace {

std::string full_name(const ::testing::TestInfo& info) {
    return std::string(info.test_suite_name()) + "." + info.name();
}

// Where a failing test left its pictures: the folder a render recorded as the test's "pictures"
// property (tests/lab_render.h), relative to the source folder as the README writes it; empty for
// a test that rendered nothing (a unit test). Not the newest picture on disk: with -j2 another
// test's render lands there while a unit test runs.
std::string pictures_of(const ::testing::TestResult& result) {
    for (int i = 0; i < result.test_property_count(); ++i) {
        const ::testing::TestProperty& property = result.GetTestProperty(i);
        if (std::string(property.key()) != "pictures") continue;
        const std::filesystem::path dir = property.value();
        const std::filesystem::path relative = dir.lexically_relative(LAB_SOURCE_DIR);
        return (relative.empty() || *relative.begin() == ".." ? dir : relative).string();
    }
    return "";
}

class ExerciseHints : public ::testing::EmptyTestEventListener {
    // The class grader's probe and judge (probe.h) keep one record per test.
    void OnTestStart(const ::testing::TestInfo& info) override {
        lab_probe::begin_test(full_name(info));
        running_ = &info;
        hinted_ = false;
    }
    void OnTestEnd(const ::testing::TestInfo&) override { running_ = nullptr; }
    // Registered ahead of gtest's printer, so this runs before the failure is printed. (Not
    // UnitTest::current_test_info() here: gtest holds the lock that it takes.)
    void OnTestPartResult(const ::testing::TestPartResult& part) override {
        if (!part.failed() || hinted_ || !running_) return;  // !running_: a failure outside a test
        hinted_ = true;
        const exercise_hints::Hint h = exercise_hints::hint(full_name(*running_), pictures_of(*running_->result()));
        std::fputs(h.text.c_str(), stdout);
        std::fflush(stdout);
        failed_.emplace_back(full_name(*running_), h.summary);
    }
    // After gtest's own summary (the end events run in reverse order): the last lines.
    void OnTestProgramEnd(const ::testing::UnitTest&) override {
        if (failed_.size() < 2) return;
        std::printf("[ exercise ] %zu tests failed; what each needs (its hint is above, at its first failure):\n",
                    failed_.size());
        for (const auto& [test, summary] : failed_) std::printf("[ exercise ]   %s: %s\n", test.c_str(), summary.c_str());
        std::fflush(stdout);
    }

    const ::testing::TestInfo* running_ = nullptr;
    bool hinted_ = false;
    std::vector<std::pair<std::string, std::string>> failed_;  // test → its hint's summary line
};

// Registered before main() runs the tests, ahead of gtest's printer (released and appended again
// after it: listeners run in the order of the list, the end events in reverse).
[[maybe_unused]] const bool registered = [] {
    ::testing::TestEventListeners& listeners = ::testing::UnitTest::GetInstance()->listeners();
    ::testing::TestEventListener* printer = listeners.Release(listeners.default_result_printer());
    listeners.Append(new ExerciseHints);
    if (printer) listeners.Append(printer);
    return true;
}();

}  // namespace
