// exercise_hints.cpp — when a test fails, it names the first unfinished exercise (scripts/exercise.sh)
// that the test needs, where it is and its hint. The library exercise_hints (tests/CMakeLists.txt),
// compiled once; two users print what hint() returns:
//   * the gtest listener (tests/exercise_hints_listener.cpp), linked into every gtest program as an
//     object file: at a test's first failure, before gtest prints that failure's details (a render's
//     log, the expected and actual values), and, when two or more tests of the program failed, once
//     more at the program's end, one summary line per failing test;
//   * the command exercise_hint TEST_NAME (tests/exercise_hint_main.cpp), for a test that is not a
//     GoogleTest test: tests/with_exercise_hint.sh runs it after that test fails, as its last lines.
//
// What it knows comes from the exercises' manifest, a JSON file that scripts/exercise.py --manifest
// writes from the labs' "// EXERCISE" markers, .exercise-stubs (a student copy) and
// tests/graded_exercises.txt: the build writes it to build/exercises.json whenever one of them
// changes (target exercise_manifest, on which every test program depends; CTest's build_is_current
// runs the build before any test). $LAB_EXERCISE_MANIFEST names another one (the grader's, for a
// variant of the lab). Its "exercises": one entry per marker (name, lab, file, line, hint, "tests":
// the "Checked by" patterns, "stub" and "code" without whitespace and // comments, "todo": a
// student copy's "// TODO EXERCISE" marker, "complete": the stub is known); "rows": the
// graded_exercises.txt rows (a test matching "pattern" needs "exercises"); "order": each lab's
// exercises in its README's order. An exercise is unfinished while its code is still its stub
// (whatever its marker line says); one whose stub is not known is unfinished while its marker says
// TODO. A manifest that is missing or not readable gives one line instead of a hint, naming its path
// and why.
//
// What a test needs is the exercises whose "Checked by" names it plus its rows. A failing test
// prints, for example:
//     [ exercise ] this test needs `texel_format`, still the stub: lab3_textures/texture.cpp:28
//                  Hint: which VkFormat does a colour map ...
//     [ exercise ] it also grades `mip_chain` (lab3_textures/texture.cpp:152): finish `texel_format` first
// or, when every exercise it needs is done:
//     [ exercise ] every exercise this test needs is done (texel_format, mip_chain), yet it fails: one
//                  of them, or another exercise of the lab, is wrong in a way its stub does not show
//     [ exercise ] the exercises' own tests name the one that is wrong; run them first:
//                  ctest --test-dir build -R '^(…)$'
//     [ exercise ] if they all pass, compare your `mip_chain` with its hint: lab3_textures/texture.cpp:152 ...
//     [ exercise ] and your `texel_format`, which it needs: lab3_textures/texture.cpp:28
// (the rows list what each exercise's stub fails: a wrong answer, such as a swapped format or a
// missing barrier, can fail tests its stub does not, so a render test cannot tell which exercise is
// wrong; the exercises' own unit tests can, and the message sends the student there first; the
// exercises to compare come the most specific first, the one the fewest tests need). One of an
// exercise's own tests that only it fails says so instead ("this test checks `X` alone"). A
// failing test of no exercise, in a student copy, prints the own tests' line alone. A test that
// wrote pictures ends with "[ exercise ] pictures (expected | actual | difference): DIR/".
#include "exercise_hints.h"

#include <nlohmann/json.hpp>

#include <fnmatch.h>

#include <algorithm>
#include <cerrno>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace exercise_hints {
namespace {

struct Exercise {
    std::string name, file, hint;
    int line = 0;
    int lab = 0;          // N of the lab folder lab<N>_* the file is in
    bool todo = false;    // the marker reads "// TODO EXERCISE"
    bool unfinished = false;
    std::vector<std::string> tests;  // "Checked by" patterns
};

struct Manifest {
    std::string path;
    std::string error;  // why it could not be read; empty: read
    std::vector<Exercise> exercises;  // in the labs' order (see load())
    std::vector<std::pair<std::string, std::vector<std::string>>> rows;  // pattern → exercises
};

std::string printf_string(const char* format, ...) __attribute__((format(printf, 1, 2)));
std::string printf_string(const char* format, ...) {
    va_list args, again;
    va_start(args, format);
    va_copy(again, args);
    const int size = std::vsnprintf(nullptr, 0, format, args);
    va_end(args);
    std::string text(size > 0 ? size_t(size) : 0, '\0');
    if (size > 0) std::vsnprintf(text.data(), text.size() + 1, format, again);
    va_end(again);
    return text;
}

// The manifest at `path`, its exercises in the labs' order and, within a lab, in the order of
// `exercise.sh --list` ("order", then a lab's folder before its shaders, then path and line).
Manifest load(const std::string& path) {
    Manifest m;
    m.path = path;
    std::ifstream in(path);
    if (!in) {
        m.error = std::strerror(errno);
        return m;
    }
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        m.error = std::string("not JSON: ") + e.what();
        return m;
    } catch (const std::exception& e) {  // a folder, a read error
        m.error = e.what();
        return m;
    }
    std::vector<std::string> order;  // every lab's "order", lab 1's first
    try {
        for (const auto& e : doc.at("exercises")) {
            Exercise x;
            x.name = e.at("name").get<std::string>();
            x.file = e.at("file").get<std::string>();
            x.hint = e.at("hint").get<std::string>();
            x.line = e.at("line").get<int>();
            x.lab = e.at("lab").get<int>();
            x.todo = e.at("todo").get<bool>();
            x.tests = e.at("tests").get<std::vector<std::string>>();
            const std::string stub = e.at("stub").get<std::string>(), code = e.at("code").get<std::string>();
            // A complete marker without STUB lines has no stub to be; a TODO marker whose stub is
            // unknown (a copy written before .exercise-stubs) is taken at its word.
            x.unfinished = e.at("complete").get<bool>() ? (x.todo || !stub.empty()) && code == stub : x.todo;
            m.exercises.push_back(x);
        }
        for (const auto& r : doc.at("rows"))
            m.rows.emplace_back(r.at("pattern").get<std::string>(), r.at("exercises").get<std::vector<std::string>>());
        std::vector<std::pair<int, std::vector<std::string>>> labs;  // "lab2" → 2, sorted by number
        for (const auto& [lab, names] : doc.at("order").items())
            labs.emplace_back(std::atoi(lab.c_str() + (lab.rfind("lab", 0) == 0 ? 3 : 0)), names.get<std::vector<std::string>>());
        std::sort(labs.begin(), labs.end());
        for (const auto& lab : labs) order.insert(order.end(), lab.second.begin(), lab.second.end());
    } catch (const nlohmann::json::exception& e) {
        m.error = std::string("not an exercises' manifest: ") + e.what();
        m.exercises.clear();
        m.rows.clear();
        return m;
    }
    const auto rank = [&](const Exercise& x) { return std::find(order.begin(), order.end(), x.name) - order.begin(); };
    const auto in_shaders = [](const Exercise& x) { return x.file.rfind("shaders/", 0) == 0; };
    std::stable_sort(m.exercises.begin(), m.exercises.end(), [&](const Exercise& a, const Exercise& b) {
        if (a.lab != b.lab) return a.lab < b.lab;
        if (rank(a) != rank(b)) return rank(a) < rank(b);
        if (in_shaders(a) != in_shaders(b)) return in_shaders(b);  // a lab's folder before its shaders
        return a.file != b.file ? a.file < b.file : a.line < b.line;
    });
    return m;
}

const Manifest& manifest() {
    static const Manifest m = load(manifest_path());
    return m;
}

bool matches(const std::string& pattern, const std::string& test) {
    return fnmatch(pattern.c_str(), test.c_str(), 0) == 0;
}

// The CTest command that runs the own tests ("Checked by") of every exercise first taught in `labs`:
// a mistake the stubs do not show (a test's rows list what each exercise's stub fails) can fail a
// test that does not list its exercise, and that exercise's own tests name it.
std::string own_tests_command(const std::vector<Exercise>& exercises, const std::vector<int>& labs) {
    std::vector<std::string> patterns;
    for (const Exercise& x : exercises) {
        // An exercise belongs to the first lab it appears in (later labs carry its file).
        int first = x.lab;
        for (const Exercise& o : exercises)
            if (o.name == x.name) first = std::min(first, o.lab);
        if (std::find(labs.begin(), labs.end(), first) == labs.end()) continue;
        for (const std::string& t : x.tests) {
            std::string rx;  // a gtest pattern as a CTest regular expression
            for (const char c : t) rx += c == '*' ? std::string(".*") : c == '.' ? std::string("\\.") : std::string(1, c);
            if (std::find(patterns.begin(), patterns.end(), rx) == patterns.end()) patterns.push_back(rx);
        }
    }
    std::string joined;
    for (const std::string& rx : patterns) joined += (joined.empty() ? "" : "|") + rx;
    return patterns.empty() ? "" : "ctest --test-dir build -R '^(" + joined + ")$'";
}

}  // namespace

std::string manifest_path() {
    const char* path = std::getenv("LAB_EXERCISE_MANIFEST");
    return path && *path ? path : LAB_EXERCISE_MANIFEST_DEFAULT;
}

Hint hint(const std::string& full, const std::string& pictures) {
    const Manifest& manifest = exercise_hints::manifest();
    if (!manifest.error.empty()) {
        const bool from_env = std::getenv("LAB_EXERCISE_MANIFEST") && *std::getenv("LAB_EXERCISE_MANIFEST");
        Hint h;
        h.summary = "no hint: the exercises' manifest " + manifest.path + (from_env ? " ($LAB_EXERCISE_MANIFEST)" : "") +
                    " cannot be read (" + manifest.error + ")" +
                    (from_env ? std::string() : "; `cmake --build build --target exercise_manifest` writes it");
        h.text = "[ exercise ] " + h.summary + "\n";
        return h;
    }
    const std::vector<Exercise>& exercises = manifest.exercises;
    const auto& table = manifest.rows;
    Hint h;
    std::string& out = h.text;

    std::vector<std::string> graded, needed;
    for (const Exercise& x : exercises)
        if (std::any_of(x.tests.begin(), x.tests.end(), [&](const std::string& p) { return matches(p, full); }))
            graded.push_back(x.name);
    needed = graded;
    for (const auto& [pattern, names] : table)
        if (matches(pattern, full)) needed.insert(needed.end(), names.begin(), names.end());
    if (needed.empty()) {
        // A test of no exercise. In a student copy, a mistake in one (an invalid sampler, a missing
        // barrier: the validation layer) can still fail it: say how to find which.
        h.summary = "grades no exercise";
        std::vector<int> todo_labs;
        for (const Exercise& x : exercises)
            if (x.todo && std::find(todo_labs.begin(), todo_labs.end(), x.lab) == todo_labs.end()) todo_labs.push_back(x.lab);
        const std::string command = own_tests_command(exercises, todo_labs);
        if (!command.empty())
            out += printf_string("[ exercise ] this test grades no exercise; if it fails after you changed one, the exercises'\n"
                                 "             own tests name the one that is wrong: %s\n", command.c_str());
        return h;
    }

    // The exercises it needs in the labs' order, each once: an unfinished copy of an exercise
    // (a lab carries an earlier lab's files) stands for it, else its first lab's; the order is
    // that of the exercise's own (first) lab.
    std::vector<const Exercise*> order;
    for (const Exercise& x : exercises) {
        if (std::find(needed.begin(), needed.end(), x.name) == needed.end()) continue;
        auto same = std::find_if(order.begin(), order.end(), [&](const Exercise* o) { return o->name == x.name; });
        if (same == order.end()) order.push_back(&x);
        else if (x.unfinished && !(*same)->unfinished) *same = &x;
    }
    const auto is_graded = [&](const Exercise* x) {
        return std::find(graded.begin(), graded.end(), x->name) != graded.end();
    };
    const auto first = std::find_if(order.begin(), order.end(), [](const Exercise* x) { return x->unfinished; });
    if (first != order.end()) {
        const Exercise& x = **first;
        h.summary = printf_string("needs `%s`, still the stub: %s:%d", x.name.c_str(), x.file.c_str(), x.line);
        out += printf_string("[ exercise ] this test needs `%s`, still the stub: %s:%d\n             Hint: %s\n",
                             x.name.c_str(), x.file.c_str(), x.line, x.hint.c_str());
        for (const Exercise* g : order)
            if (is_graded(g) && g != &x)
                out += printf_string("[ exercise ] it also grades `%s` (%s:%d): finish `%s` first\n", g->name.c_str(),
                                     g->file.c_str(), g->line, x.name.c_str());
    } else if (order.size() == 1 && is_graded(order.front())) {
        // One of the exercise's own tests (its "Checked by", and no other exercise's stub fails
        // it): the test's own failure is about that exercise alone.
        const Exercise& x = *order.front();
        h.summary = printf_string("checks `%s` alone: %s:%d", x.name.c_str(), x.file.c_str(), x.line);
        out += printf_string("[ exercise ] this test checks `%s` alone, and `%s` is no longer the stub: what the test\n"
                             "             prints is what is wrong with it: %s:%d\n             Hint: %s\n",
                             x.name.c_str(), x.name.c_str(), x.file.c_str(), x.line, x.hint.c_str());
    } else {
        // Done is not right, and the test cannot tell which exercise is wrong: a wrong answer can fail
        // tests its stub does not (a swapped format, a missing barrier). The exercises' own tests
        // can: the message sends the student there first, then names the ones this test needs.
        std::string names;
        for (const Exercise* x : order) names += (names.empty() ? "" : ", ") + x->name;
        h.summary = "every exercise it needs is done (" + names + ")";
        out += printf_string("[ exercise ] %s (%s), yet it fails: %s, or another exercise of the lab, is wrong in a way its\n"
                             "             stub does not show\n",
                             order.size() == 1 ? "the exercise this test needs is done" : "every exercise this test needs is done",
                             names.c_str(), order.size() == 1 ? "it" : "one of them");
        std::vector<int> labs;
        for (const Exercise* x : order)
            if (std::find(labs.begin(), labs.end(), x->lab) == labs.end()) labs.push_back(x->lab);
        const std::string command = own_tests_command(exercises, labs);
        if (!command.empty())
            out += printf_string("[ exercise ] the exercises' own tests name the one that is wrong; run them first:\n"
                                 "             %s\n", command.c_str());
        // Then the exercises to compare, the most specific to this test first: the one the fewest
        // tests need (its rows and its "Checked by" patterns). An exercise every render needs (lab
        // 4's pass_dependencies, whose mistakes the validation layer reports by name anyway) says
        // least about a wrong picture, so it comes last.
        std::map<std::string, std::set<std::string>> tests_needing;  // exercise → the test patterns
        for (const auto& [pattern, names] : table)
            for (const std::string& n : names) tests_needing[n].insert(pattern);
        for (const Exercise& x : exercises) tests_needing[x.name].insert(x.tests.begin(), x.tests.end());
        std::vector<const Exercise*> compare = order;
        std::stable_sort(compare.begin(), compare.end(), [&](const Exercise* a, const Exercise* b) {
            return tests_needing[a->name].size() < tests_needing[b->name].size();
        });
        bool compared = false;  // the first line says "if they all pass, compare", the rest "and"
        for (const Exercise* g : compare) {
            if (is_graded(g))
                out += printf_string("[ exercise ] %s `%s` with its hint: %s:%d\n             Hint: %s\n",
                                     compared ? "and compare your" : "if they all pass, compare your", g->name.c_str(),
                                     g->file.c_str(), g->line, g->hint.c_str());
            else
                out += printf_string("[ exercise ] %s `%s`, which it needs: %s:%d\n",
                                     compared ? "and your" : "if they all pass, compare your", g->name.c_str(),
                                     g->file.c_str(), g->line);
            compared = true;
        }
    }
    // tests/reference/image_compare.h writes them left to right in this order.
    if (!pictures.empty()) out += "[ exercise ] pictures (expected | actual | difference): " + pictures + "/\n";
    return h;
}

}  // namespace exercise_hints
