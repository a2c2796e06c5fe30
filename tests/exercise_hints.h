// exercise_hints.h — what a failing test says about the exercises it needs (tests/exercise_hints.cpp
// describes the messages and the manifest they come from). The library exercise_hints; its users
// are the gtest listener (tests/exercise_hints_listener.cpp, in every gtest program) and the
// command exercise_hint (tests/exercise_hint_main.cpp).
#pragma once

#include <string>

namespace exercise_hints {

// The manifest read: $LAB_EXERCISE_MANIFEST when set, else the build's exercises.json.
std::string manifest_path();

struct Hint {
    std::string text;     // the "[ exercise ]" lines, each ending in '\n'
    std::string summary;  // one line for a program's summary of failing tests, no '\n'
};

// The hint for failing test `test` (Suite.Test, or a CTest name such as lab4_smoke_animated);
// `pictures`: the folder it wrote its pictures to, "" for none. Reads the manifest once per process;
// when it cannot, the hint is one line saying why.
Hint hint(const std::string& test, const std::string& pictures);

}  // namespace exercise_hints
