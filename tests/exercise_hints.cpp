// exercise_hints.cpp — linked into every test binary: when a test fails, it names the first
// unfinished exercise (scripts/exercise.sh) that the test needs, where it is and its hint. Built
// alone with LAB_EXERCISE_HINT_MAIN it is the command exercise_hint TEST_NAME, which says the same
// for a test that is not a GoogleTest test (tests/with_exercise_hint.sh runs it when one fails).
//
// The labs mark an exercise's code with "// EXERCISE name: hint. Checked by Suite.Test, Suite.*."
// (a student copy has "// TODO EXERCISE ..." and the stub there) up to "// END EXERCISE". What a
// test needs is the exercises whose "Checked by" names it plus its rows in
// tests/graded_exercises.txt. A failing test prints, for example:
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
// failing test of no exercise, in a student copy, prints the own tests' line alone.
//
// "Done" does not depend on the marker line: an exercise is unfinished while its code (between
// the marker and END EXERCISE, without whitespace and // comments) is still the stub. The stub's
// text comes from the complete lab's "// STUB:" lines, or in a student copy from the
// .exercise-stubs file that scripts/exercise.sh writes there.
#include "probe.h"

#include <gtest/gtest.h>

#include <fnmatch.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct Marker {
    std::string name, file, hint;
    int line = 0;
    int lab = 0;          // N of the lab folder lab<N>_* the file is in
    std::string code;     // the code between the marker and END EXERCISE, normalized (see bare())
    std::string stub;     // the complete lab's STUB lines, normalized; empty: not a complete marker
    bool todo = false;    // the marker reads "// TODO EXERCISE"
    bool unfinished = false;
    std::vector<std::string> tests;  // "Checked by" patterns
};

// A line without its // comment and without any whitespace: what a stub is compared by.
std::string bare(std::string s) {
    const size_t comment = s.find("//");
    if (comment != std::string::npos) s.erase(comment);
    s.erase(std::remove_if(s.begin(), s.end(), [](unsigned char c) { return std::isspace(c); }), s.end());
    return s;
}

int lab_number(const std::string& folder) {  // "lab3_textures" → 3
    return std::atoi(folder.c_str() + 3);
}

// The lab folders (lab<N>_*/ and shaders/lab<N>_*/) of root: their files, relative to root.
std::vector<std::string> lab_files(const fs::path& root) {
    std::vector<std::string> files;
    std::error_code ec;
    for (const fs::path& top : {root, root / "shaders"}) {
        if (!fs::is_directory(top, ec)) continue;
        for (const auto& lab : fs::directory_iterator(top, ec)) {
            const std::string name = lab.path().filename().string();
            if (!lab.is_directory() || name.rfind("lab", 0) != 0) continue;
            for (const auto& f : fs::recursive_directory_iterator(lab.path(), ec))
                if (f.is_regular_file() && f.path().extension() != ".md")
                    files.push_back(fs::relative(f.path(), root).generic_string());
        }
    }
    return files;
}

// Every marker of one file ("// [TODO ]EXERCISE name: hint[ Checked by A.B, C.*.]").
void scan_file(const fs::path& path, const std::string& rel, std::vector<Marker>& out) {
    const std::string folder = rel.rfind("shaders/", 0) == 0 ? rel.substr(8) : rel;
    const int lab = lab_number(folder);
    std::ifstream in(path);
    std::string text;
    Marker* open = nullptr;
    for (int line = 1; std::getline(in, text); ++line) {
        if (open) {
            const std::string trimmed = bare(text);
            if (text.find("// END EXERCISE") != std::string::npos && trimmed.empty()) {
                open = nullptr;
            } else if (const size_t s = text.find("// STUB: "); s != std::string::npos && trimmed.empty()) {
                open->stub += bare(text.substr(s + 9));
            } else {
                open->code += trimmed;
            }
            continue;
        }
        size_t at = text.find("// EXERCISE ");
        bool todo = false;
        if (at == std::string::npos) {
            at = text.find("// TODO EXERCISE ");
            if (at == std::string::npos) continue;
            todo = true;
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
        Marker mk;
        mk.name = name, mk.file = rel, mk.hint = hint, mk.line = line, mk.lab = lab, mk.todo = todo;
        std::replace(tests.begin(), tests.end(), ',', ' ');
        std::istringstream words(tests);
        for (std::string t; words >> t;) mk.tests.push_back(t);
        out.push_back(mk);
        open = &out.back();
    }
}

// The stubs a student copy was written with: .exercise-stubs, "file name stub-line" per line.
std::map<std::string, std::string> copy_stubs(const fs::path& root) {
    std::map<std::string, std::string> stubs;  // "file name" → normalized stub
    std::ifstream in(root / ".exercise-stubs");
    std::string file, name, rest;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream words(line);
        if (!(words >> file >> name)) continue;
        std::getline(words, rest);
        stubs[file + " " + name] += bare(rest);
    }
    return stubs;
}

// The exercises' order, the one the lab READMEs number them in: tests/graded_exercises.txt's
// "!order name…" rows, one per lab (exercise.sh --list and the course site follow it too).
std::vector<std::string> exercise_order() {
    std::vector<std::string> names;
    std::ifstream in(fs::path(LAB_SOURCE_DIR) / "tests" / "graded_exercises.txt");
    for (std::string line; std::getline(in, line);) {
        line.erase(std::min(line.size(), line.find('#')));
        std::istringstream words(line);
        std::string first;
        if (!(words >> first) || first != "!order") continue;
        for (std::string n; words >> n;) names.push_back(n);
    }
    return names;
}

// Every marker of the project at LAB_SOURCE_DIR, in the labs' order and, within a lab, in the
// order of `exercise.sh --list` ("!order" rows, then path and line). The prover (exercise.sh --prove) builds the
// tests from a mirror of one lab with exercises stubbed: LAB_EXERCISE_SOURCES names it, and its
// lab folders are read instead of the project's.
std::vector<Marker> scan_markers() {
    const fs::path root = LAB_SOURCE_DIR;
    std::vector<Marker> complete;
    std::vector<std::string> files = lab_files(root);
    std::sort(files.begin(), files.end());
    for (const std::string& f : files) scan_file(root / f, f, complete);

    std::vector<Marker> markers = complete;
    const char* mirror = std::getenv("LAB_EXERCISE_SOURCES");
    if (mirror && *mirror) {
        std::vector<std::string> mirrored = lab_files(mirror);
        std::vector<std::string> labs;  // the lab folders the mirror replaces
        for (const std::string& f : mirrored) {
            const std::string folder = f.rfind("shaders/", 0) == 0 ? f.substr(8) : f;
            labs.push_back(folder.substr(0, folder.find('/')));
        }
        std::vector<std::string> kept;
        for (const std::string& f : files) {
            const std::string folder = f.rfind("shaders/", 0) == 0 ? f.substr(8) : f;
            if (std::find(labs.begin(), labs.end(), folder.substr(0, folder.find('/'))) == labs.end())
                kept.push_back(f);
        }
        markers.clear();
        for (const std::string& f : kept) scan_file(root / f, f, markers);
        for (const std::string& f : mirrored) scan_file(fs::path(mirror) / f, f, markers);
    }
    const std::map<std::string, std::string> stubs = copy_stubs(root);
    for (Marker& m : markers) {
        // The stub this marker's code is compared with: its own STUB lines (the complete lab), the
        // complete project's for the same file (the prover's mirror), or the copy's manifest.
        std::string stub = m.stub;
        bool known = !m.stub.empty() || !m.todo;
        for (const Marker& c : complete)
            if (!known && c.file == m.file && c.name == m.name && !c.todo) stub = c.stub, known = true;
        if (const auto s = stubs.find(m.file + " " + m.name); !known && s != stubs.end()) stub = s->second, known = true;
        // A complete marker without STUB lines has no stub to be; a TODO marker whose stub is
        // unknown (a copy written before .exercise-stubs) is taken at its word.
        m.unfinished = known ? (m.todo || !m.stub.empty()) && m.code == stub : m.todo;
    }
    const std::vector<std::string> order = exercise_order();
    const auto rank = [&](const Marker& m) {
        return std::find(order.begin(), order.end(), m.name) - order.begin();
    };
    std::stable_sort(markers.begin(), markers.end(), [&](const Marker& a, const Marker& b) {
        if (a.lab != b.lab) return a.lab < b.lab;
        if (rank(a) != rank(b)) return rank(a) < rank(b);
        const std::string fa = a.file.rfind("shaders/", 0) == 0 ? a.file.substr(8) : a.file;
        const std::string fb = b.file.rfind("shaders/", 0) == 0 ? b.file.substr(8) : b.file;
        const bool sa = fa != a.file, sb = fb != b.file;  // a lab's folder before its shaders
        if (sa != sb) return sb;
        return a.file != b.file ? a.file < b.file : a.line < b.line;
    });
    return markers;
}

// tests/graded_exercises.txt: "pattern exercise…" rows; a test needs every row it matches.
std::vector<std::pair<std::string, std::vector<std::string>>> needs_table() {
    std::vector<std::pair<std::string, std::vector<std::string>>> rows;
    std::ifstream in(fs::path(LAB_SOURCE_DIR) / "tests" / "graded_exercises.txt");
    for (std::string line; std::getline(in, line);) {
        line.erase(std::min(line.size(), line.find('#')));
        std::istringstream words(line);
        std::string pattern;
        // "@e x…": what e's own code needs, "!order …": the exercises' order; neither is a test
        if (!(words >> pattern) || pattern[0] == '@' || pattern[0] == '!') continue;
        std::vector<std::string> names;
        for (std::string n; words >> n;) names.push_back(n);
        rows.emplace_back(pattern, names);
    }
    return rows;
}

bool matches(const std::string& pattern, const std::string& test) {
    return fnmatch(pattern.c_str(), test.c_str(), 0) == 0;
}

// The CTest command that runs the own tests ("Checked by") of every exercise first taught in `labs`:
// a mistake the stubs do not show (a test's rows list what each exercise's stub fails) can fail a
// test that does not list its exercise, and that exercise's own tests name it.
std::string own_tests_command(const std::vector<Marker>& markers, const std::vector<int>& labs) {
    std::vector<std::string> patterns;
    for (const Marker& m : markers) {
        // An exercise belongs to the first lab it appears in (later labs carry its file).
        int first = m.lab;
        for (const Marker& o : markers)
            if (o.name == m.name) first = std::min(first, o.lab);
        if (std::find(labs.begin(), labs.end(), first) == labs.end()) continue;
        for (const std::string& t : m.tests) {
            std::string rx;  // a gtest pattern as a CTest regular expression
            for (const char c : t) rx += c == '*' ? std::string(".*") : c == '.' ? std::string("\\.") : std::string(1, c);
            if (std::find(patterns.begin(), patterns.end(), rx) == patterns.end()) patterns.push_back(rx);
        }
    }
    std::string joined;
    for (const std::string& rx : patterns) joined += (joined.empty() ? "" : "|") + rx;
    return patterns.empty() ? "" : "ctest --test-dir build -R '^(" + joined + ")$'";
}

// What test `full` (Suite.Test, or a CTest name such as lab4_smoke_stress) needs, printed as the
// grader's hint: the first unfinished exercise it needs, or that every one is done. `pictures`:
// the folder the failing test wrote its pictures to (empty: it wrote none), said on the last line.
void print_hint(const std::string& full, const std::string& pictures) {
    static const std::vector<Marker> markers = scan_markers();
    static const auto table = needs_table();

    std::vector<std::string> graded, needed;
    for (const Marker& m : markers)
        if (std::any_of(m.tests.begin(), m.tests.end(), [&](const std::string& p) { return matches(p, full); }))
            graded.push_back(m.name);
    needed = graded;
    for (const auto& [pattern, names] : table)
        if (matches(pattern, full)) needed.insert(needed.end(), names.begin(), names.end());
    if (needed.empty()) {
        // A test of no exercise. In a student copy, a mistake in one (an invalid sampler, a missing
        // barrier: the validation layer) can still fail it: say how to find which.
        std::vector<int> todo_labs;
        for (const Marker& m : markers)
            if (m.todo && std::find(todo_labs.begin(), todo_labs.end(), m.lab) == todo_labs.end()) todo_labs.push_back(m.lab);
        const std::string command = own_tests_command(markers, todo_labs);
        if (!command.empty())
            std::printf("[ exercise ] this test grades no exercise; if it fails after you changed one, the exercises'\n"
                        "             own tests name the one that is wrong: %s\n", command.c_str());
        return;
    }

    // The exercises it needs in the labs' order, each once: an unfinished copy of an exercise
    // (a lab carries an earlier lab's files) stands for it, else its first lab's; the order is
    // that of the exercise's own (first) lab.
    std::vector<const Marker*> order;
    for (const Marker& m : markers) {
        if (std::find(needed.begin(), needed.end(), m.name) == needed.end()) continue;
        auto same = std::find_if(order.begin(), order.end(), [&](const Marker* o) { return o->name == m.name; });
        if (same == order.end()) order.push_back(&m);
        else if (m.unfinished && !(*same)->unfinished) *same = &m;
    }
    const auto is_graded = [&](const Marker* m) {
        return std::find(graded.begin(), graded.end(), m->name) != graded.end();
    };
    const auto first = std::find_if(order.begin(), order.end(), [](const Marker* m) { return m->unfinished; });
    if (first != order.end()) {
        const Marker& m = **first;
        std::printf("[ exercise ] this test needs `%s`, still the stub: %s:%d\n             Hint: %s\n",
                    m.name.c_str(), m.file.c_str(), m.line, m.hint.c_str());
        for (const Marker* g : order)
            if (is_graded(g) && g != &m)
                std::printf("[ exercise ] it also grades `%s` (%s:%d): finish `%s` first\n", g->name.c_str(),
                            g->file.c_str(), g->line, m.name.c_str());
    } else if (order.size() == 1 && is_graded(order.front())) {
        // One of the exercise's own tests (its "Checked by", and no other exercise's stub fails
        // it): the test's own failure above is about that exercise alone.
        const Marker& m = *order.front();
        std::printf("[ exercise ] this test checks `%s` alone, and `%s` is no longer the stub: what the test\n"
                    "             printed above is what is wrong with it: %s:%d\n             Hint: %s\n",
                    m.name.c_str(), m.name.c_str(), m.file.c_str(), m.line, m.hint.c_str());
    } else {
        // Done is not right, and the test cannot tell which exercise is wrong: a wrong answer can fail
        // tests its stub does not (a swapped format, a missing barrier). The exercises' own tests
        // can: the message sends the student there first, then names the ones this test needs.
        std::string names;
        for (const Marker* m : order) names += (names.empty() ? "" : ", ") + m->name;
        std::printf("[ exercise ] %s (%s), yet it fails: %s, or another exercise of the lab, is wrong in a way its\n"
                    "             stub does not show\n",
                    order.size() == 1 ? "the exercise this test needs is done" : "every exercise this test needs is done",
                    names.c_str(), order.size() == 1 ? "it" : "one of them");
        std::vector<int> labs;
        for (const Marker* m : order)
            if (std::find(labs.begin(), labs.end(), m->lab) == labs.end()) labs.push_back(m->lab);
        const std::string command = own_tests_command(markers, labs);
        if (!command.empty())
            std::printf("[ exercise ] the exercises' own tests name the one that is wrong; run them first:\n"
                        "             %s\n", command.c_str());
        // Then the exercises to compare, the most specific to this test first: the one the fewest
        // tests need (its rows in graded_exercises.txt and its "Checked by" patterns). An exercise
        // every render needs (lab 4's pass_dependencies, whose mistakes the validation layer
        // reports by name anyway) says least about a wrong picture, so it comes last.
        std::map<std::string, std::set<std::string>> tests_needing;  // exercise → the test patterns
        for (const auto& [pattern, names] : table)
            for (const std::string& n : names) tests_needing[n].insert(pattern);
        for (const Marker& m : markers) tests_needing[m.name].insert(m.tests.begin(), m.tests.end());
        std::vector<const Marker*> compare = order;
        std::stable_sort(compare.begin(), compare.end(), [&](const Marker* x, const Marker* y) {
            return tests_needing[x->name].size() < tests_needing[y->name].size();
        });
        bool compared = false;  // the first line says "if they all pass, compare", the rest "and"
        for (const Marker* g : compare) {
            if (is_graded(g))
                std::printf("[ exercise ] %s `%s` with its hint: %s:%d\n             Hint: %s\n",
                            compared ? "and compare your" : "if they all pass, compare your", g->name.c_str(),
                            g->file.c_str(), g->line, g->hint.c_str());
            else
                std::printf("[ exercise ] %s `%s`, which it needs: %s:%d\n",
                            compared ? "and your" : "if they all pass, compare your", g->name.c_str(), g->file.c_str(),
                            g->line);
            compared = true;
        }
    }
    // tests/reference/image_compare.h writes them left to right in this order.
    if (!pictures.empty()) std::printf("[ exercise ] pictures (expected | actual | difference): %s/\n", pictures.c_str());
}

#ifndef LAB_EXERCISE_HINT_MAIN
// Where a failing test left its pictures: the folder a render recorded as the test's "pictures"
// property (tests/lab_render.h), relative to the source folder as the README writes it; empty for
// a test that rendered nothing (a unit test). Not the newest picture on disk: with -j2 another
// test's render lands there while a unit test runs.
std::string pictures_of(const ::testing::TestResult& result) {
    for (int i = 0; i < result.test_property_count(); ++i) {
        const ::testing::TestProperty& property = result.GetTestProperty(i);
        if (std::string(property.key()) != "pictures") continue;
        const fs::path dir = property.value();
        const fs::path relative = dir.lexically_relative(LAB_SOURCE_DIR);
        return (relative.empty() || *relative.begin() == ".." ? dir : relative).string();
    }
    return "";
}

class ExerciseHints : public ::testing::EmptyTestEventListener {
    // The class grader's probe and judge (probe.h) keep one record per test.
    void OnTestStart(const ::testing::TestInfo& info) override {
        lab_probe::begin_test(std::string(info.test_suite_name()) + "." + info.name());
    }
    void OnTestEnd(const ::testing::TestInfo& info) override {
        if (!info.result()->Failed()) return;
        print_hint(std::string(info.test_suite_name()) + "." + info.name(), pictures_of(*info.result()));
    }
};

// Registered before main() runs the tests.
[[maybe_unused]] const bool registered = [] {
    ::testing::UnitTest::GetInstance()->listeners().Append(new ExerciseHints);
    return true;
}();
#endif

}  // namespace

#ifdef LAB_EXERCISE_HINT_MAIN
// exercise_hint TEST_NAME: the same hint for a test that is not a GoogleTest test (a smoke run, a
// soak, the random scenes): tests/with_exercise_hint.sh prints it when that test fails.
int main(int argc, char** argv) {
    if (argc != 2 || argv[1][0] == '-') {
        std::fprintf(stderr, "usage: exercise_hint TEST_NAME (the CTest name): the exercises it needs, as a failing test names them\n");
        return argc == 2 && (std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help") ? 0 : 2;
    }
    print_hint(argv[1], "");
    return 0;
}
#endif
