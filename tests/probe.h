// probe.h — the values a graded test gets from the lab's code, recorded by one process and judged
// by another, so that no verdict comes from a process that runs a student's code.
//
// A test marks each value that the lab computes for it: LAB_PROBE(expression) for a value,
// LAB_PROBE_UPDATE(object, statement) for a call that changes an object in place. With $LAB_PROBE
// unset (the suite, a student's own ctest) both are exactly their expression or statement.
//
// The class grader (scripts/grade/) runs a graded test twice:
//   * the probe, LAB_PROBE=record, in the sandbox, linked with the student's code: each marked value
//     is appended to $LAB_PROBE_DIR/<Suite.Test>.probe; whatever this process prints is ignored;
//   * the judge, LAB_PROBE=replay, built from the handed-out copy (every exercise its stub, no
//     student code in it): a marked expression is not evaluated, its recorded value is returned,
//     and the test's own checks against the reference give the verdict.
// The judge's stubs make a missing mark visible: a value that the lab computes without one comes
// from a stub, and the solution then fails its own test in the judge (the grader refuses to start).
// A record that does not fit the test (another site, another size, cut short) throws: the test fails.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace lab_probe {

enum class Mode { Off, Record, Replay };

// A record of one test is at most this large (a few pictures); a larger one is not read.
inline constexpr std::uint64_t kMaxRecordBytes = std::uint64_t(256) << 20;

struct State {
    Mode mode = Mode::Off;
    std::string dir;     // $LAB_PROBE_DIR
    std::string test;    // Suite.Test of the test running now
    std::string data;    // replay: the test's record
    std::size_t at = 0;  // replay: where the next value starts
    bool loaded = false;
};

inline State& state() {
    static State s = [] {
        State init;
        const char* mode = std::getenv("LAB_PROBE");
        const char* dir = std::getenv("LAB_PROBE_DIR");
        if (mode && dir && *dir) {
            const std::string m = mode;
            init.mode = m == "record" ? Mode::Record : m == "replay" ? Mode::Replay : Mode::Off;
            init.dir = dir;
        }
        return init;
    }();
    return s;
}

inline bool replaying() { return state().mode == Mode::Replay; }

inline std::string record_path() {
    std::string name = state().test.empty() ? std::string("main") : state().test;
    for (char& c : name)
        if (c == '/') c = '_';  // parameterized tests: AllModels/Lab2Model.MatchesReference/phong
    return state().dir + "/" + name + ".probe";
}

// Called as each test starts (tests/exercise_hints_listener.cpp): a new record.
inline void begin_test(const std::string& name) {
    State& s = state();
    s.test = name;
    s.data.clear();
    s.at = 0;
    s.loaded = false;
    if (s.mode == Mode::Record) std::remove(record_path().c_str());
}

[[noreturn]] inline void mismatch(int line, const std::string& why) {
    throw std::runtime_error("(probe) the recorded values do not fit this test at line " + std::to_string(line) +
                             ": " + why + " — the code under test did not run this test to its end");
}

// One entry: the line of the LAB_PROBE site, the size, the bytes.
inline void append(int line, const void* bytes, std::uint64_t size) {
    std::ofstream out(record_path(), std::ios::binary | std::ios::app);
    const std::uint32_t l = static_cast<std::uint32_t>(line);
    out.write(reinterpret_cast<const char*>(&l), sizeof l);
    out.write(reinterpret_cast<const char*>(&size), sizeof size);
    out.write(static_cast<const char*>(bytes), static_cast<std::streamsize>(size));
}

// The next entry's bytes, which must come from `line`.
inline std::string take(int line) {
    State& s = state();
    if (!s.loaded) {
        std::ifstream in(record_path(), std::ios::binary | std::ios::ate);
        if (!in) mismatch(line, "there is no record");
        const std::streamoff size = in.tellg();
        if (size < 0 || std::uint64_t(size) > kMaxRecordBytes) mismatch(line, "the record is too large");
        s.data.resize(static_cast<std::size_t>(size));
        in.seekg(0);
        in.read(s.data.data(), size);
        s.loaded = true;
    }
    std::uint32_t l = 0;
    std::uint64_t size = 0;
    if (s.data.size() - s.at < sizeof l + sizeof size) mismatch(line, "the record ends here");
    std::memcpy(&l, s.data.data() + s.at, sizeof l);
    std::memcpy(&size, s.data.data() + s.at + sizeof l, sizeof size);
    s.at += sizeof l + sizeof size;
    if (l != std::uint32_t(line)) mismatch(line, "the next value was recorded at line " + std::to_string(l));
    if (size > s.data.size() - s.at) mismatch(line, "the value is cut short");
    std::string bytes = s.data.substr(s.at, static_cast<std::size_t>(size));
    s.at += static_cast<std::size_t>(size);
    return bytes;
}

// How a value becomes bytes and back: trivially copyable types (numbers, GLM vectors and matrices,
// Vulkan's plain structs, the labs' plain structs) byte for byte; strings and vectors of them with
// their length.
template <class T>
std::string encode(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>, "LAB_PROBE: a plain value, a std::string or a std::vector of plain values");
    return std::string(reinterpret_cast<const char*>(&v), sizeof v);
}
inline std::string encode(const std::string& v) { return v; }
template <class T>
std::string encode(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>, "LAB_PROBE: a vector of plain values");
    return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

template <class T>
struct Decode {
    static T from(const std::string& b, int line) {
        if (b.size() != sizeof(T)) mismatch(line, "a value of " + std::to_string(b.size()) + " bytes where " + std::to_string(sizeof(T)) + " were expected");
        T v;
        std::memcpy(static_cast<void*>(&v), b.data(), sizeof(T));
        return v;
    }
};
template <>
struct Decode<std::string> {
    static std::string from(const std::string& b, int) { return b; }
};
template <class T>
struct Decode<std::vector<T>> {
    static std::vector<T> from(const std::string& b, int line) {
        if (b.size() % sizeof(T)) mismatch(line, "a vector whose size is no whole number of elements");
        std::vector<T> v(b.size() / sizeof(T));
        if (!v.empty()) std::memcpy(static_cast<void*>(v.data()), b.data(), b.size());
        return v;
    }
};

// LAB_PROBE(e): e, recorded (record) or read back without evaluating e (replay).
template <class F>
auto value(int line, F&& compute) -> std::decay_t<decltype(compute())> {
    using T = std::decay_t<decltype(compute())>;
    switch (state().mode) {
        case Mode::Off: return compute();
        case Mode::Replay: return Decode<T>::from(take(line), line);
        case Mode::Record: break;
    }
    T v = compute();
    const std::string bytes = encode(v);
    append(line, bytes.data(), bytes.size());
    return v;
}

// LAB_PROBE_UPDATE(object, statement): the statement runs and object's new value is recorded
// (record), or object takes its recorded value and the statement does not run (replay).
template <class T, class F>
void update(int line, T& object, F&& statement) {
    if (replaying()) {
        object = Decode<T>::from(take(line), line);
        return;
    }
    statement();
    if (state().mode == Mode::Record) {
        const std::string bytes = encode(object);
        append(line, bytes.data(), bytes.size());
    }
}

}  // namespace lab_probe

#define LAB_PROBE(...) ::lab_probe::value(__LINE__, [&]() { return (__VA_ARGS__); })
#define LAB_PROBE_UPDATE(object, ...) ::lab_probe::update(__LINE__, object, [&]() { __VA_ARGS__; })
