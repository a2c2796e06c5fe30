// exercise_hint TEST_NAME: the hint of tests/exercise_hints.cpp for a test that is not a GoogleTest
// test (a smoke run, a soak, the random scenes, a gallery): tests/with_exercise_hint.sh prints it
// when that test fails.
#include "exercise_hints.h"

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
    if (argc != 2 || argv[1][0] == '-') {
        std::fprintf(stderr, "usage: exercise_hint TEST_NAME (the CTest name): the exercises it needs, as a failing test names them\n"
                             "  reads the exercises' manifest: $LAB_EXERCISE_MANIFEST, else %s\n",
                     exercise_hints::manifest_path().c_str());
        return argc == 2 && (std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help") ? 0 : 2;
    }
    std::fputs(exercise_hints::hint(argv[1], "").text.c_str(), stdout);
    return 0;
}
