// scene_fuzz — feeds mutated scene files to the scene loader (docs/testing.md, "Fuzzing").
//
//   scene_fuzz --seed S --cases N [--lab EXE --lab-cases K] [--work DIR] FILE_OR_FOLDER...
//   scene_fuzz --replay tests/fuzz/regressions.txt [--lab EXE] [--work DIR]
//
// Each case takes one scene file (the inputs in name order, round robin), applies one to three
// mutations — deleted, duplicated or renamed keys, wrong types, extreme and non-finite-looking
// numbers, odd strings and paths, shrunk or multiplied arrays, deep nesting, truncation, stray
// bytes — writes the result to a file and loads it with lab::load_scene. A case passes when the
// scene loads (and every mesh it names builds into a well-formed mesh) or when it is rejected
// the way a lab turns into exit code 2: a SceneError (or, from a model file, a runtime_error)
// whose message is one non-empty line starting with the file name. Anything else — another
// exception type, a multi-line message, a crash or a sanitizer report — fails.
// With --lab, K cases spread over the run also go through the real lab binary (headless, tiny
// image, --validate): exit 0 and a PNG when the loader accepted the case, otherwise exit 2, no
// PNG, and exactly one "error:" line, the last one on stderr.
//
// Everything is deterministic: case i of a run uses the 64-bit case seed mix(S, i) and the
// input file i mod (number of files). A failing case prints "FAILED <case seed> <file>": that
// line, appended to tests/fuzz/regressions.txt, replays exactly that case in every test run.
#include "mesh.h"
#include "scene.h"

#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;  // keeps the file's key order, so mutants look like scenes

namespace {

// ---------------------------------------------------------------- determinism
uint64_t splitmix64(uint64_t x) {  // a good 64-bit mix: neighbouring indices give unrelated seeds
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}
uint64_t case_seed(uint64_t run_seed, uint64_t index) { return splitmix64(splitmix64(run_seed) ^ index); }

struct Rng {
    std::mt19937_64 engine;
    explicit Rng(uint64_t seed) : engine(seed) {}
    size_t below(size_t n) { return n == 0 ? 0 : size_t(engine() % n); }
    bool chance(double p) { return std::uniform_real_distribution<double>(0.0, 1.0)(engine) < p; }
    template <class T> const T& pick(const std::vector<T>& v) { return v[below(v.size())]; }
};

// ---------------------------------------------------------------- the mutations
// Some mutations need text that a JSON tree cannot hold (a duplicate key, a bare NaN, a
// million brackets, bytes that are not UTF-8). They put a marker string into the tree and
// the marker is replaced in the serialized text.
const std::string kMarker = "\x01MUT";  // serialized as "\u0001MUT<n>"

struct Mutant {
    json tree;
    std::vector<std::pair<std::string, std::string>> raw;  // "\"\\u0001MUT<n>\"" -> raw text
    std::vector<std::string> log;                          // what was done, for failure reports

    std::string marker(const std::string& raw_text) {
        const std::string m = kMarker + std::to_string(raw.size());
        raw.push_back({json(m).dump(), raw_text});
        return m;
    }
    std::string text() const {
        std::string s = tree.dump(2);
        for (const auto& [from, to] : raw) {
            // A marker may sit in a value (with its quotes) or, for duplicated keys, in a key.
            for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
                s.replace(at, from.size(), to);
        }
        return s;
    }
};

// Every node of the tree as a JSON pointer ("" is the root).
void collect(const json& node, const json::json_pointer& at, std::vector<json::json_pointer>& out) {
    out.push_back(at);
    if (node.is_object())
        for (auto it = node.begin(); it != node.end(); ++it) collect(it.value(), at / it.key(), out);
    else if (node.is_array())
        for (size_t i = 0; i < node.size(); ++i) collect(node[i], at / i, out);
}

std::vector<json::json_pointer> nodes_where(const json& tree, const std::function<bool(const json&)>& keep) {
    std::vector<json::json_pointer> all, kept;
    collect(tree, json::json_pointer(), all);
    for (const auto& p : all)
        if (keep(tree.at(p))) kept.push_back(p);
    return kept;
}

// Numbers at and beyond every limit, and a few JSON spellings of numbers that are not JSON.
const std::vector<std::string> kExtremeNumbers = {
    "0", "-0", "-0.0", "1", "-1", "0.5", "1e-6", "-1e-6", "9.99999e-7", "1e6", "-1e6", "1000000.0000001",
    "1e7", "1e19", "1e38", "3.5e38", "-3.5e38", "1e300", "1.7976931348623157e308", "-1.7976931348623157e308",
    "5e-324", "1e-400", "1e400", "-1e400", "2147483647", "2147483648", "-2147483649", "4294967296",
    "9007199254740993", "18446744073709551615", "18446744073709551616", "-9223372036854775809",
    "123456789012345678901234567890", "1024", "1025", "7", "8", "16", "17", "3", "2", "180", "180.0001",
    "90", "89.9999", "179", "1e-45", "1.5", "0.0000000000000000000001"};
const std::vector<std::string> kNotJsonNumbers = {
    "NaN", "nan", "-NaN", "Infinity", "-Infinity", "inf", "+1", ".5", "01", "1.", "0x10", "1e", "-", "1_000",
    "1,5", "- 1", "1e+", "Inf", "1/0"};
const std::vector<std::string> kStrings = {
    "", " ", "NaN", "Infinity", "-inf", "1e400", "0", "true", "null", "sphere", "Sphere", "SPHERE", "spher",
    "spot", "Spot", "spotlight", "lookat", "look_at", "transform", "phong", "blinn-phong", "cook_torrance",
    "a\nb", "tab\there", "quote\"inside", "back\\slash", "\u00e9\u00e8\u00e0 unicode \u2202\u222b",
    "models/pawn.obj", "models/pawn.mtl", "models/README.md", "models", ".", "..", "/", "/dev/null",
    "/dev/zero", "/dev/urandom", "/proc/self/status", "/etc", "nonexistent.obj", "x.OBJ", "pawn.obj#x",
    "../../../../../../../../../../etc/passwd", "C:\\\\models\\\\pawn.obj", "~/pawn.obj"};
// Raw bytes (not valid JSON strings or not valid UTF-8) for the text-level marker.
const std::vector<std::string> kRawStrings = {
    "\"\xff\xfe\"", "\"\xc3\"", "\"\xed\xa0\x80\"", "\"a\x01" "b\"", "\"\\ud800\"", "\"\\u0000\"", "\"unterminated",
    "'single'", "\"\\x41\""};

json random_value(Rng& rng, int depth = 0) {
    switch (rng.below(depth > 2 ? 5 : 8)) {
        case 0: return nullptr;
        case 1: return rng.chance(0.5);
        case 2: return json(double(rng.below(2000)) / 7.0 - 100.0);
        case 3: return json(int64_t(rng.below(5000)) - 10);
        case 4: return json(rng.pick(kStrings));
        case 5: return json::array();
        case 6: {
            json a = json::array();
            for (size_t i = 0, n = rng.below(5); i < n; ++i) a.push_back(random_value(rng, depth + 1));
            return a;
        }
        default: {
            json o = json::object();
            for (size_t i = 0, n = rng.below(4); i < n; ++i) o[rng.pick(kStrings)] = random_value(rng, depth + 1);
            return o;
        }
    }
}

// Key names the format knows (and near misses): added keys may collide or look like typos.
const std::vector<std::string> kKeys = {
    "camera", "mode", "position", "postion", "target", "up", "yaw_deg", "pitch_deg", "roll_deg", "fov_y_deg",
    "fov", "near", "far", "background", "ambient", "color", "intensity", "lighting", "model", "shading",
    "spot_falloff", "distribution", "toon_bands", "markers", "nan_check", "lights", "type", "direction",
    "attenuation", "inner_deg", "outer_deg", "materials", "albedo", "specular", "shininess", "emissive",
    "roughness", "f0", "roughness_x", "roughness_y", "minnaert_k", "objects", "mesh", "material",
    "rotation_deg", "scale", "segments", "rings", "crease_deg", "normalize", "cast_shadows", "cast_shadow",
    "shadow", "resolution", "pcf", "filter", "bias", "slope_bias", "normal_offset", "fit_to_view", "opacity", "version", "",
    "a b", "x\ny"};

// Returns true when the case should also get text-level damage (see damage_text).
bool mutate_once(Mutant& m, Rng& rng) {
    json& t = m.tree;
    const auto any = nodes_where(t, [](const json&) { return true; });
    const auto objects = nodes_where(t, [](const json& j) { return j.is_object() && !j.empty(); });
    const auto arrays = nodes_where(t, [](const json& j) { return j.is_array() && !j.empty(); });
    const auto numbers = nodes_where(t, [](const json& j) { return j.is_number(); });
    const auto strings = nodes_where(t, [](const json& j) { return j.is_string(); });
    const auto non_root = [&]() { return any.size() > 1 ? any[1 + rng.below(any.size() - 1)] : any[0]; };

    switch (rng.below(14)) {
        case 0:  // delete a key
            if (!objects.empty()) {
                json& o = t.at(rng.pick(objects));
                auto it = o.begin();
                std::advance(it, long(rng.below(o.size())));
                m.log.push_back("delete key " + it.key());
                o.erase(it);
            }
            return false;
        case 1:  // duplicate a key (same or another value): JSON parsers disagree on these
            if (!objects.empty()) {
                json& o = t.at(rng.pick(objects));
                auto it = o.begin();
                std::advance(it, long(rng.below(o.size())));
                const std::string key = it.key();
                const json value = rng.chance(0.5) ? it.value() : random_value(rng);
                const std::string mark = m.marker(json(key).dump());
                o[mark] = value;
                m.log.push_back("duplicate key " + key);
            }
            return false;
        case 2: {  // add an unknown, near-miss or known key
            if (objects.empty()) return false;
            const std::string key = rng.pick(kKeys);
            t.at(rng.pick(objects))[key] = random_value(rng);
            m.log.push_back("add key " + key);
            return false;
        }
        case 3: {  // wrong type anywhere
            const auto at = non_root();
            t.at(at) = random_value(rng);
            m.log.push_back("replace " + at.to_string() + " with " + t.at(at).dump().substr(0, 60));
            return false;
        }
        case 4:
        case 5: {  // an extreme number where a number (or anything) was
            const auto at = !numbers.empty() && rng.chance(0.8) ? rng.pick(numbers) : non_root();
            const std::string text = rng.pick(kExtremeNumbers);
            t.at(at) = m.marker(text);
            m.log.push_back("number " + at.to_string() + " = " + text);
            return false;
        }
        case 6: {  // a non-finite-looking number (not JSON: must be a syntax error)
            const auto at = !numbers.empty() ? rng.pick(numbers) : non_root();
            const std::string text = rng.pick(kNotJsonNumbers);
            t.at(at) = m.marker(text);
            m.log.push_back("raw number " + at.to_string() + " = " + text);
            return false;
        }
        case 7: {  // an odd string where a string was
            const auto at = !strings.empty() && rng.chance(0.8) ? rng.pick(strings) : non_root();
            if (rng.chance(0.15)) {
                const std::string raw = rng.pick(kRawStrings);
                t.at(at) = m.marker(raw);
                m.log.push_back("raw string " + at.to_string());
            } else {
                t.at(at) = rng.chance(0.1) ? std::string(size_t(1) << (8 + rng.below(9)), 'x') : rng.pick(kStrings);
                m.log.push_back("string " + at.to_string() + " = " + t.at(at).get<std::string>().substr(0, 40));
            }
            return false;
        }
        case 8: {  // arrays: drop, repeat, empty, reverse
            if (arrays.empty()) return false;
            json& a = t.at(rng.pick(arrays));
            switch (rng.below(4)) {
                case 0: a.erase(a.begin() + long(rng.below(a.size()))); m.log.push_back("drop element"); break;
                case 1: {
                    const json e = a[rng.below(a.size())];
                    const size_t n = std::vector<size_t>{1, 2, 9, 40, 300}[rng.below(5)];
                    for (size_t i = 0; i < n; ++i) a.push_back(e);
                    m.log.push_back("repeat element x" + std::to_string(n));
                    break;
                }
                case 2: a = json::array(); m.log.push_back("empty array"); break;
                default: std::reverse(a.begin(), a.end()); m.log.push_back("reverse array"); break;
            }
            return false;
        }
        case 9: {  // a whole section replaced by an empty or a wrong container
            if (objects.empty()) return false;
            const auto at = rng.pick(objects);
            if (at.empty()) return false;
            t.at(at) = rng.chance(0.5) ? json::object() : json::array();
            m.log.push_back("empty section " + at.to_string());
            return false;
        }
        case 10: {  // deep nesting where a value was
            const auto at = non_root();
            const size_t depth = std::vector<size_t>{2, 10, 100, 1000, 10000, 100000}[rng.below(6)];
            std::string raw;
            const bool arrays_only = rng.chance(0.5);
            for (size_t i = 0; i < depth; ++i) raw += arrays_only ? "[" : "{\"a\":";
            raw += "1";
            for (size_t i = 0; i < depth; ++i) raw += arrays_only ? "]" : "}";
            t.at(at) = m.marker(raw);
            m.log.push_back("nest " + std::to_string(depth) + " at " + at.to_string());
            return false;
        }
        case 11:  // the whole document is something else
            t = random_value(rng);
            m.log.push_back("root = " + t.dump().substr(0, 60));
            return false;
        default:  // 12, 13: text-level damage is applied after serialization (see make_case)
            return true;
    }
}

// Truncation, stray bytes, deleted characters: on the serialized text.
std::string damage_text(std::string s, Rng& rng, std::vector<std::string>& log) {
    if (s.empty()) return s;
    switch (rng.below(4)) {
        case 0: {
            const size_t at = rng.below(s.size());
            log.push_back("truncate at " + std::to_string(at));
            return s.substr(0, at);
        }
        case 1: {
            const size_t at = rng.below(s.size());
            const char byte = char(rng.below(256));
            log.push_back("insert byte " + std::to_string(int(static_cast<unsigned char>(byte))));
            return s.insert(at, 1, byte);
        }
        case 2: {
            const size_t at = rng.below(s.size());
            log.push_back("delete char " + std::to_string(at));
            return s.erase(at, 1);
        }
        default: {
            const size_t at = rng.below(s.size());
            const char structural[] = "{}[],:\"";
            s[at] = structural[rng.below(sizeof structural - 1)];
            log.push_back("structural char at " + std::to_string(at));
            return s;
        }
    }
}

// Relative model paths are made absolute first, so a mutant works from any folder.
json absolute_models(json tree, const fs::path& folder) {
    if (tree.contains("objects") && tree["objects"].is_array())
        for (json& o : tree["objects"])
            if (o.is_object() && o.contains("mesh") && o["mesh"].is_string()) {
                const std::string mesh = o["mesh"].get<std::string>();
                if (mesh.find('.') != std::string::npos && fs::path(mesh).is_relative())
                    o["mesh"] = (folder / mesh).lexically_normal().string();
            }
    return tree;
}

struct Input {
    std::string path;  // as given
    json tree;         // parsed, model paths absolute; null if the file is not JSON
    std::string text;  // the raw file (for files that are not JSON: text damage only)
};

struct Case {
    std::string text;
    std::vector<std::string> log;
};

Case make_case(const Input& input, uint64_t seed) {
    Rng rng(seed);
    Case c;
    if (input.tree.is_discarded()) {  // e.g. an invalid scene kept as a test: damage the text only
        c.text = damage_text(input.text, rng, c.log);
        return c;
    }
    Mutant m{input.tree, {}, {}};
    const size_t count = 1 + rng.below(3);
    bool text_damage = false;
    for (size_t i = 0; i < count; ++i) text_damage = mutate_once(m, rng) || text_damage;
    c.text = m.text();
    if (text_damage) c.text = damage_text(c.text, rng, m.log);
    c.log = m.log;
    return c;
}

// ---------------------------------------------------------------- the checks
bool one_line(const std::string& s) { return !s.empty() && s.find_first_of("\r\n") == std::string::npos; }

std::string well_formed(const lab::Mesh& mesh) {
    if (mesh.vertices.empty() || mesh.indices.empty()) return "empty mesh";
    if (mesh.indices.size() % 3 != 0) return "index count not a multiple of 3";
    for (uint32_t i : mesh.indices)
        if (i >= mesh.vertices.size()) return "index out of range";
    for (const lab::Vertex& v : mesh.vertices)
        for (int k = 0; k < 3; ++k)
            if (!std::isfinite(v.position[k]) || !std::isfinite(v.normal[k])) return "non-finite vertex";
    return "";
}

enum class Outcome { Loaded, Rejected, Failed };

// Loads the file as a lab does; `why` explains a failure.
Outcome load_in_process(const std::string& file, std::string& why) {
    try {
        const lab::Scene scene = lab::load_scene(file);
        lab::MeshLibrary meshes;
        for (const lab::ObjectDesc& object : scene.objects) {
            try {
                const std::string bad = well_formed(meshes.mesh(object));
                if (!bad.empty()) {
                    why = "accepted scene, but mesh '" + object.mesh + "': " + bad;
                    return Outcome::Failed;
                }
            } catch (const std::runtime_error& e) {  // a model file the loader let through
                if (!one_line(e.what())) {
                    why = "mesh error is not one line: " + std::string(e.what());
                    return Outcome::Failed;
                }
                return Outcome::Rejected;
            }
        }
        return Outcome::Loaded;
    } catch (const lab::SceneError& e) {
        const std::string message = e.what();
        if (!one_line(message)) why = "message is not one line: " + message;
        else if (message.rfind(file + ": ", 0) != 0) why = "message does not start with the file name: " + message;
        else return Outcome::Rejected;
        return Outcome::Failed;
    } catch (const std::exception& e) {
        why = std::string("unexpected exception (exit code would not be 2): ") + e.what();
        return Outcome::Failed;
    }
}

std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string shell_quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// The same file through the real lab: exit 0 + PNG if loaded, else exit 2 + one error line.
bool check_with_lab(const std::string& lab, const std::string& file, Outcome expected, const fs::path& work,
                    std::string& why) {
    const fs::path png = work / "lab.png", err = work / "lab.stderr";
    fs::remove(png);
    const std::string command = shell_quote(lab) + " --headless --validate --width 24 --height 16 --scene " +
                                shell_quote(file) + " --out " + shell_quote(png.string()) + " >/dev/null 2>" +
                                shell_quote(err.string());
    const int status = std::system(command.c_str());
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    const std::string stderr_text = read_file(err);
    std::vector<std::string> lines;
    std::istringstream stream(stderr_text);
    for (std::string line; std::getline(stream, line);) lines.push_back(line);
    const size_t errors = size_t(std::count_if(lines.begin(), lines.end(),
                                               [](const std::string& l) { return l.find(": error: ") != std::string::npos; }));
    if (expected == Outcome::Loaded) {
        if (code != 0 || !fs::exists(png)) why = "lab exit " + std::to_string(code) + " for a scene the loader accepts: " + stderr_text;
        return why.empty();
    }
    if (code != 2) why = "lab exit " + std::to_string(code) + " (expected 2): " + stderr_text;
    else if (fs::exists(png)) why = "lab wrote a PNG for a rejected scene";
    else if (errors != 1 || lines.empty() || lines.back().find(": error: ") == std::string::npos ||
             lines.back().find(file) == std::string::npos)
        why = "expected exactly one error line naming the file, last on stderr: " + stderr_text;
    return why.empty();
}

// ---------------------------------------------------------------- the run
struct Options {
    uint64_t seed = 1;
    size_t cases = 300;
    std::string lab;
    size_t lab_cases = 0;
    std::string replay;
    fs::path work;
    std::vector<std::string> inputs;
};

[[noreturn]] void usage_error(const std::string& message) {
    std::fprintf(stderr, "scene_fuzz: error: %s\nusage: scene_fuzz --seed S --cases N [--lab EXE --lab-cases K] "
                         "[--work DIR] FILE_OR_FOLDER... | scene_fuzz --replay FILE [--lab EXE] [--work DIR]\n",
                 message.c_str());
    std::exit(2);
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto next = [&]() -> std::string {
            if (i + 1 >= argc) usage_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--seed") o.seed = std::stoull(next());
        else if (a == "--cases") o.cases = std::stoull(next());
        else if (a == "--lab") o.lab = next();
        else if (a == "--lab-cases") o.lab_cases = std::stoull(next());
        else if (a == "--replay") o.replay = next();
        else if (a == "--work") o.work = next();
        else if (!a.empty() && a[0] == '-') usage_error("unknown option " + a);
        else o.inputs.push_back(a);
    }
    if (o.replay.empty() && o.inputs.empty()) usage_error("no scene files");
    return o;
}

Input read_input(const std::string& path) {
    Input in{path, json(), read_file(path)};
    in.tree = json::parse(in.text, nullptr, /*allow_exceptions=*/false);
    if (!in.tree.is_discarded()) in.tree = absolute_models(in.tree, fs::absolute(path).parent_path());
    return in;
}

}  // namespace

int main(int argc, char** argv) {
    const Options options = parse(argc, argv);
    const fs::path work = options.work.empty() ? fs::temp_directory_path() / ("scene_fuzz_" + std::to_string(::getpid()))
                                               : options.work;
    fs::create_directories(work);

    // The cases: (input file, case seed), from the command line or a regressions file.
    std::vector<std::pair<std::string, uint64_t>> cases;
    std::vector<std::string> files;
    if (!options.replay.empty()) {
        std::ifstream list(options.replay);
        if (!list) usage_error("cannot read " + options.replay);
        const fs::path root = fs::absolute(options.replay).parent_path().parent_path().parent_path();  // tests/fuzz/x -> repo
        for (std::string line; std::getline(list, line);) {
            std::istringstream s(line);
            std::string tag, seed_text, file;
            if (!(s >> tag) || tag[0] == '#') continue;
            if (tag != "FAILED" || !(s >> seed_text >> file)) usage_error(options.replay + ": bad line: " + line);
            cases.push_back({(root / file).string(), std::stoull(seed_text, nullptr, 16)});
        }
    } else {
        for (const std::string& in : options.inputs) {
            if (fs::is_directory(in)) {
                std::vector<std::string> found;
                for (const auto& e : fs::directory_iterator(in))
                    if (e.path().extension() == ".json") found.push_back(e.path().string());
                std::sort(found.begin(), found.end());
                files.insert(files.end(), found.begin(), found.end());
            } else {
                files.push_back(in);
            }
        }
        if (files.empty()) usage_error("no .json files in the inputs");
        for (size_t i = 0; i < options.cases; ++i) cases.push_back({files[i % files.size()], case_seed(options.seed, i)});
    }

    std::map<std::string, Input> inputs;
    size_t loaded = 0, rejected = 0, failed = 0, lab_runs = 0;
    const size_t lab_every = options.lab.empty() ? 0
                             : options.replay.empty() ? std::max<size_t>(1, cases.size() / std::max<size_t>(1, options.lab_cases))
                                                      : 1;
    const fs::path last_case = work / "last_case.txt";  // survives a crash: which case it was
    for (size_t i = 0; i < cases.size(); ++i) {
        const auto& [path, seed] = cases[i];
        if (!inputs.count(path)) inputs.emplace(path, read_input(path));
        const Case c = make_case(inputs.at(path), seed);
        char seed_hex[17];
        std::snprintf(seed_hex, sizeof seed_hex, "%016" PRIx64, seed);
        const std::string id = std::string("FAILED ") + seed_hex + " " + path;
        std::ofstream(last_case) << id << "\n";

        const std::string file = (work / (std::string("case_") + seed_hex + ".json")).string();
        std::ofstream(file, std::ios::binary) << c.text;
        std::string why;
        const Outcome outcome = load_in_process(file, why);
        if (outcome != Outcome::Failed && lab_every && i % lab_every == 0) {
            ++lab_runs;
            if (!check_with_lab(options.lab, file, outcome, work, why)) {
                std::fprintf(stderr, "%s\n  mutations: ", id.c_str());
                for (const auto& l : c.log) std::fprintf(stderr, "%s; ", l.c_str());
                std::fprintf(stderr, "\n  %s\n  (kept %s)\n", why.c_str(), file.c_str());
                ++failed;
                continue;
            }
        }
        if (outcome == Outcome::Failed) {
            std::fprintf(stderr, "%s\n  mutations: ", id.c_str());
            for (const auto& l : c.log) std::fprintf(stderr, "%s; ", l.c_str());
            std::fprintf(stderr, "\n  %s\n  (kept %s)\n", why.c_str(), file.c_str());
            ++failed;
            continue;
        }
        (outcome == Outcome::Loaded ? loaded : rejected)++;
        fs::remove(file);
    }
    fs::remove(last_case);
    if (failed == 0 && options.work.empty()) fs::remove_all(work);
    std::printf("scene_fuzz: %zu cases from %zu files (%zu loaded, %zu rejected with one line), %zu through the lab; "
                "%zu failed\n",
                cases.size(), options.replay.empty() ? files.size() : inputs.size(), loaded, rejected, lab_runs, failed);
    return failed == 0 ? 0 : 1;
}
