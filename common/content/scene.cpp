// scene.cpp — reads and validates scene files (format v1, docs/scene-format.md).
//
// Design: every JSON object of the format ("section") is read by one small
// function that calls a read helper per known key. The helpers check the type
// and range of the value and remember the key as known; Section::finish() then
// rejects any key nobody asked for, so a typo ("postion") is an error instead
// of a silently ignored setting. Adding a key to the format is one line.
//
// Every problem throws SceneError with one line "FILE: JSON.PATH: reason".
#include "scene.h"

#include "mesh.h"
#include "text_match.h"

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <set>
#include <sstream>
#include <system_error>

namespace lab {

namespace {
const char* const kLightTypeNames[] = {"directional", "point", "spot"};  // LightDesc::Type's order
}  // namespace

const char* light_type_name(LightDesc::Type type) { return kLightTypeNames[int(type)]; }

const std::vector<std::string>& primitive_mesh_names() {
    static const std::vector<std::string> names = {
        "plane", "cube", "sphere", "icosphere", "icosahedron", "cylinder", "cone", "torus"};
    return names;
}

const std::vector<std::string>& procedural_texture_names() {
    static const std::vector<std::string> names = {"checker", "metal", "grid"};
    return names;
}

bool known_procedural_or_path(const std::string& map) {
    const std::string prefix = "procedural:";
    if (map.rfind(prefix, 0) != 0) return true;
    const auto& names = procedural_texture_names();
    return std::find(names.begin(), names.end(), map.substr(prefix.size())) != names.end();
}

namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

// Limits that are not physics but protect the renderer from absurd input
// (documented in docs/scene-format.md, "Numbers").
constexpr double kMaxMagnitude = 1e6;  // every number: |v| <= 1e6 (also keeps floats finite)
constexpr double kMinLength = 1e-6;    // directions: length >= 1e-6; scale: |component| >= 1e-6
constexpr int kMaxTessellation = 1024;
constexpr std::uintmax_t kMaxSceneBytes = 16u << 20;  // a scene file is a few KiB; 16 MiB is absurd already

// --- small string helpers ---------------------------------------------------

std::string lower(const std::string& s) { return to_lower(s); }

bool ends_with_ci(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           lower(s.substr(s.size() - suffix.size())) == lower(suffix);
}

std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
    return out;
}

std::string number_text(double v) {
    std::ostringstream s;
    s << v;  // 6 significant digits, e.g. "0.5", "1e+07"
    return s.str();
}

// The candidate that `word` is probably a typo of, or "" if none is close:
// a few letters off ("postion" -> "position") or a prefix of each other.
std::string closest(const std::string& word, const std::vector<std::string>& candidates) {
    std::string best;
    size_t best_distance = std::max<size_t>(1, std::min<size_t>(3, word.size() / 3)) + 1;
    for (const auto& c : candidates) {
        size_t d = edit_distance(word, c);
        // One is the start of the other: "fov" -> "fov_y_deg", "spotlight" -> "spot".
        const std::string w = lower(word), lc = lower(c);
        if (std::min(w.size(), lc.size()) >= 3 && (lc.rfind(w, 0) == 0 || w.rfind(lc, 0) == 0))
            d = std::min<size_t>(d, 1);
        if (d < best_distance) {
            best_distance = d;
            best = c;
        }
    }
    return best;
}

// "; did you mean 'x'?" or "; expected one of: a, b, c"
std::string suggestion(const std::string& word, const std::vector<std::string>& candidates) {
    const std::string guess = closest(word, candidates);
    if (!guess.empty()) return "; did you mean '" + guess + "'?";
    return "; expected one of: " + join(candidates);
}

// JSON paths as in the messages: camera.near, objects[3].scale, materials.red.albedo
std::string key_path(const std::string& parent, const std::string& key) {
    bool plain = !key.empty();
    for (char c : key) plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-');
    if (!plain) return parent + "[\"" + key + "\"]";  // e.g. materials["my red"]
    return parent.empty() ? key : parent + "." + key;
}

std::string index_path(const std::string& parent, size_t index) {
    return parent + "[" + std::to_string(index) + "]";
}

// --- errors -----------------------------------------------------------------

// What every message needs: the file label, and the folder relative mesh paths start from.
struct Context {
    std::string label;
    fs::path base_dir;
};

// Builds the one-line message. Keys may contain escaped newlines, so control
// characters are replaced to keep the promise of one line.
[[noreturn]] void fail(const Context& ctx, const std::string& path, const std::string& reason) {
    std::string message = ctx.label + ": " + (path.empty() ? "(top level)" : path) + ": " + reason;
    for (char& c : message)
        if (static_cast<unsigned char>(c) < 0x20) c = ' ';
    throw SceneError(message);
}

// --- reading numbers and vectors --------------------------------------------

// The interval a number must lie in (on top of the |v| <= 1e6 rule).
struct Range {
    double lo = -kMaxMagnitude;
    double hi = kMaxMagnitude;
    bool lo_open = false;  // true: v > lo instead of v >= lo
    bool hi_open = false;

    bool contains(double v) const {
        return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
    }
    std::string describe() const {
        const bool has_lo = lo > -kMaxMagnitude, has_hi = hi < kMaxMagnitude;
        if (has_lo && has_hi)
            return std::string("in ") + (lo_open ? "(" : "[") + number_text(lo) + ", " +
                   number_text(hi) + (hi_open ? ")" : "]");
        if (has_lo || lo_open) return std::string(lo_open ? "> " : ">= ") + number_text(lo);
        if (has_hi || hi_open) return std::string(hi_open ? "< " : "<= ") + number_text(hi);
        return "in [-1e6, 1e6]";
    }
};

const Range kAnyNumber{};
const Range kNonNegative{0.0, kMaxMagnitude};
const Range kPositive{0.0, kMaxMagnitude, true, false};

Range closed_range(double lo, double hi) { return Range{lo, hi, false, false}; }
Range open_range(double lo, double hi) { return Range{lo, hi, true, true}; }

// Reads a JSON number as double: a type error for anything else, and no
// NaN / infinity / absurd magnitudes. (JSON text cannot spell NaN, and the parser
// already rejects overflow such as 1e400, but the check costs nothing.)
double read_number(const Context& ctx, const json& value, const std::string& path) {
    if (!value.is_number())
        fail(ctx, path, std::string("expected a number, got ") + value.type_name());
    const double v = value.get<double>();
    if (!std::isfinite(v)) fail(ctx, path, "must be a finite number");
    if (std::fabs(v) > kMaxMagnitude)
        fail(ctx, path, "number out of range: magnitude must be <= 1e6, got " + number_text(v));
    return v;
}

double read_number(const Context& ctx, const json& value, const std::string& path, const Range& range) {
    const double v = read_number(ctx, value, path);
    if (!range.contains(v)) fail(ctx, path, "must be " + range.describe() + ", got " + number_text(v));
    return v;
}

// What a vec3 means decides which values are valid.
enum class Vec {
    Coordinate,   // any finite numbers
    Direction,    // not (nearly) zero length
    Color,        // components >= 0 (linear RGB, may exceed 1)
    Scale,        // components non-zero
    Attenuation,  // components >= 0
};

glm::vec3 read_vec3(const Context& ctx, const json& value, const std::string& path, Vec kind) {
    if (!value.is_array() || value.size() != 3) {
        const std::string got = value.is_array()
                                    ? "an array of " + std::to_string(value.size()) + " elements"
                                    : std::string(value.type_name());
        fail(ctx, path, "expected an array of 3 numbers [x, y, z], got " + got);
    }
    glm::dvec3 v;
    for (int i = 0; i < 3; ++i) {
        const std::string element = index_path(path, static_cast<size_t>(i));
        const json& e = value[static_cast<size_t>(i)];
        switch (kind) {
            case Vec::Color:
            case Vec::Attenuation:
                v[i] = read_number(ctx, e, element, kNonNegative);
                break;
            case Vec::Scale:
                v[i] = read_number(ctx, e, element);
                // A zero scale flattens the object and makes the normal matrix singular.
                if (std::fabs(v[i]) < kMinLength)
                    fail(ctx, element, "scale must be non-zero (|s| >= 1e-6), got " + number_text(v[i]));
                break;
            default:
                v[i] = read_number(ctx, e, element);
        }
    }
    // A direction gets normalized; a zero vector has no direction.
    if (kind == Vec::Direction && glm::length(v) < kMinLength)
        fail(ctx, path, "direction must not be zero-length (length >= 1e-6)");
    return glm::vec3(v);
}

// --- Section: one JSON object of the format ---------------------------------

class Section {
public:
    Section(const Context& ctx, const json& value, std::string path)
        : ctx_(ctx), value_(value), path_(std::move(path)) {
        if (!value_.is_object())
            fail(ctx_, path_, std::string("expected an object { ... }, got ") + value_.type_name());
    }

    const Context& ctx() const { return ctx_; }
    const std::string& path() const { return path_; }
    std::string path_of(const std::string& key) const { return key_path(path_, key); }

    // Marks `key` as known and returns its value, or nullptr if absent.
    const json* find(const std::string& key) {
        known_.push_back(key);
        auto it = value_.find(key);
        return it == value_.end() ? nullptr : &*it;
    }

    // Like find, but the key must be present.
    const json& required(const std::string& key) {
        const json* v = find(key);
        if (!v) {
            // A required key is missing: maybe it is there under a misspelled name.
            std::vector<std::string> present;
            for (const auto& item : value_.items()) present.push_back(item.key());
            const std::string typo = closest(key, present);
            fail(ctx_, path_of(key),
                 "missing required key" + (typo.empty() ? "" : " (found '" + typo + "': a typo?)"));
        }
        return *v;
    }

    void number(const std::string& key, float& out, const Range& range = kAnyNumber) {
        if (const json* v = find(key)) out = static_cast<float>(read_number(ctx_, *v, path_of(key), range));
    }

    void vec3(const std::string& key, glm::vec3& out, Vec kind) {
        if (const json* v = find(key)) out = read_vec3(ctx_, *v, path_of(key), kind);
    }

    void integer(const std::string& key, int& out, int lo, int hi) {
        const json* v = find(key);
        if (!v) return;
        const std::string p = path_of(key);
        const double d = read_number(ctx_, *v, p);
        // 3.0 is accepted (JSON does not distinguish it from 3); 1.5 is not.
        if (d != std::floor(d)) fail(ctx_, p, "expected an integer, got " + number_text(d));
        if (d < lo || d > hi)
            fail(ctx_, p, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                              number_text(d));
        out = static_cast<int>(d);
    }

    void boolean(const std::string& key, bool& out) {
        const json* v = find(key);
        if (!v) return;
        if (!v->is_boolean())
            fail(ctx_, path_of(key), std::string("expected true or false, got ") + v->type_name());
        out = v->get<bool>();
    }

    static std::string text_of(const Context& ctx, const json& v, const std::string& path) {
        if (!v.is_string()) fail(ctx, path, std::string("expected a string, got ") + v.type_name());
        return v.get<std::string>();
    }

    // A string that must be one of `choices`; returns its index.
    size_t choice(const json& v, const std::string& key, const std::string& what,
                  const std::vector<std::string>& choices) {
        const std::string s = text_of(ctx_, v, path_of(key));
        for (size_t i = 0; i < choices.size(); ++i)
            if (s == choices[i]) return i;
        fail(ctx_, path_of(key), "unknown " + what + " '" + s + "'" + suggestion(s, choices));
    }

    // Rejects every key no read call asked for. `what` names the section in the
    // message when the valid keys depend on it (e.g. "point light").
    void finish(const std::string& what = "") {
        for (const auto& item : value_.items()) {
            if (std::find(known_.begin(), known_.end(), item.key()) != known_.end()) continue;
            fail(ctx_, path_of(item.key()),
                 "unknown key" + (what.empty() ? "" : " for a " + what) + suggestion(item.key(), known_));
        }
    }

private:
    const Context& ctx_;
    const json& value_;
    std::string path_;
    std::vector<std::string> known_;
};

// --- the sections -------------------------------------------------------------

CameraDesc read_camera(const Context& ctx, const json& value) {
    CameraDesc c;
    Section s(ctx, value, "camera");
    if (const json* mode = s.find("mode"))
        c.mode = s.choice(*mode, "mode", "camera mode", {"lookat", "transform"}) == 0
                     ? CameraDesc::Mode::LookAt
                     : CameraDesc::Mode::Transform;
    // Both modes accept all keys, so switching "mode" is a one-word edit.
    // position == target is allowed (the camera then looks down -Z, docs/conventions.md).
    s.vec3("position", c.position, Vec::Coordinate);
    s.vec3("target", c.target, Vec::Coordinate);
    s.vec3("up", c.up, Vec::Direction);
    s.number("yaw_deg", c.yaw_deg);
    s.number("pitch_deg", c.pitch_deg);
    s.number("roll_deg", c.roll_deg);
    s.number("fov_y_deg", c.fov_y_deg, open_range(0.0, 180.0));
    s.number("near", c.near_plane, kPositive);
    s.number("far", c.far_plane, kPositive);
    s.finish();
    if (!(c.near_plane < c.far_plane))
        fail(ctx, s.path_of("far"), "must be greater than near (near = " + number_text(c.near_plane) +
                                        ", far = " + number_text(c.far_plane) + ")");
    return c;
}

AmbientDesc read_ambient(const Context& ctx, const json& value) {
    AmbientDesc a;
    Section s(ctx, value, "ambient");
    s.vec3("color", a.color, Vec::Color);
    s.number("intensity", a.intensity, kNonNegative);
    s.finish();
    return a;
}

// Lab 4: "shadow": { "resolution", "pcf", "filter", "bias", "slope_bias", "normal_offset", "fit_to_view" }.
ShadowDesc read_shadow(const Context& ctx, const json& value, const std::string& path) {
    ShadowDesc d;
    Section s(ctx, value, path);
    s.integer("resolution", d.resolution, 1, 16384);  // texels per side (per cube face)
    s.integer("pcf", d.pcf, 1, 15);                     // an N×N kernel centred on the lookup
    // An even kernel has no centre tap, so it would shift the shadow by half a texel.
    if (d.pcf % 2 == 0)
        fail(ctx, s.path_of("pcf"), "must be odd (an N×N kernel centred on the texel), got " + std::to_string(d.pcf));
    if (const json* v = s.find("filter"))
        d.filter = ShadowDesc::Filter(s.choice(*v, "filter", "shadow filter", {"nearest", "bilinear"}));
    s.number("bias", d.bias, kNonNegative);
    s.number("slope_bias", d.slope_bias, kNonNegative);
    s.number("normal_offset", d.normal_offset, kNonNegative);
    s.boolean("fit_to_view", d.fit_to_view);
    s.finish();
    return d;
}

LightDesc read_light(const Context& ctx, const json& value, const std::string& path) {
    LightDesc l;
    Section s(ctx, value, path);
    static const std::vector<std::string> types(std::begin(kLightTypeNames), std::end(kLightTypeNames));
    const size_t type = s.choice(s.required("type"), "type", "light type", types);
    l.type = static_cast<LightDesc::Type>(type);
    // Each type reads only its own keys, so e.g. "inner_deg" on a point light
    // is reported as unknown rather than silently ignored.
    const bool directional = l.type == LightDesc::Type::Directional;
    const bool spot = l.type == LightDesc::Type::Spot;
    if (!directional) s.vec3("position", l.position, Vec::Coordinate);
    if (directional || spot) s.vec3("direction", l.direction, Vec::Direction);
    s.vec3("color", l.color, Vec::Color);
    s.number("intensity", l.intensity, kNonNegative);
    if (!directional) s.vec3("attenuation", l.attenuation, Vec::Attenuation);
    if (spot) {
        s.number("inner_deg", l.inner_deg, closed_range(0.0, 90.0));
        s.number("outer_deg", l.outer_deg, closed_range(0.0, 90.0));
    }
    s.boolean("cast_shadows", l.cast_shadows);  // lab 4
    if (const json* v = s.find("shadow")) l.shadow = read_shadow(ctx, *v, s.path_of("shadow"));
    s.finish(types[type] + " light");
    if (spot && l.inner_deg > l.outer_deg)
        fail(ctx, s.path_of("inner_deg"), "must be <= outer_deg (inner = " + number_text(l.inner_deg) +
                                              ", outer = " + number_text(l.outer_deg) + ")");
    return l;
}

// [a, b]: two numbers in `range`.
glm::vec2 read_vec2(const Context& ctx, const json& value, const std::string& path, const Range& range) {
    if (!value.is_array() || value.size() != 2) {
        const std::string got = value.is_array() ? "an array of " + std::to_string(value.size()) + " elements"
                                                 : std::string(value.type_name());
        fail(ctx, path, "expected an array of 2 numbers [u, v], got " + got);
    }
    return {float(read_number(ctx, value[0], index_path(path, 0), range)),
            float(read_number(ctx, value[1], index_path(path, 1), range))};
}

// Lab 3: a texture map is "procedural:NAME" or an image path relative to the scene file. A
// missing or broken image is not a scene error (the lab warns and shows a checkerboard); an
// unknown procedural name is.
std::string read_map(const Context& ctx, const json& value, const std::string& path) {
    const std::string text = Section::text_of(ctx, value, path);
    if (text.empty()) fail(ctx, path, "must not be empty (leave the key out for no map)");
    const std::string prefix = "procedural:";
    if (text.rfind(prefix, 0) == 0) {
        const std::string name = text.substr(prefix.size());
        if (!known_procedural_or_path(text))
            fail(ctx, path, "unknown procedural texture '" + name + "'" + suggestion(name, procedural_texture_names()));
        return text;
    }
    fs::path file(text);
    if (file.is_relative()) file = ctx.base_dir / file;
    std::error_code ec;
    return fs::absolute(file, ec).lexically_normal().string();
}

SamplerDesc read_sampler(const Context& ctx, const json& value, const std::string& path) {
    SamplerDesc d;
    Section s(ctx, value, path);
    if (const json* v = s.find("filter"))
        d.filter = SamplerDesc::Filter(s.choice(*v, "filter", "filter", {"nearest", "linear"}));
    if (const json* v = s.find("mipmaps"))
        d.mipmaps = SamplerDesc::Mipmaps(s.choice(*v, "mipmaps", "mipmap mode", {"none", "nearest", "linear"}));
    s.integer("anisotropy", d.anisotropy, 1, 16);
    if (const json* v = s.find("wrap"))
        d.wrap = SamplerDesc::Wrap(s.choice(*v, "wrap", "wrap mode", {"repeat", "clamp", "mirror"}));
    if (const json* v = s.find("anisotropic"))
        d.anisotropic = SamplerDesc::Anisotropic(s.choice(*v, "anisotropic", "anisotropic filter", {"sampler", "probes", "auto"}));
    s.finish();
    // Each probe reads the level of its share of the footprint: without mipmaps there is only level 0
    // ("auto" picks the probes on a CPU device, so it needs them too).
    if (d.anisotropic == SamplerDesc::Anisotropic::Probes && d.mipmaps == SamplerDesc::Mipmaps::None)
        fail(ctx, s.path_of("anisotropic"), "\"probes\" needs mipmaps (\"mipmaps\": \"linear\" or \"nearest\"): each probe reads a coarser level");
    if (d.anisotropic == SamplerDesc::Anisotropic::Auto && d.mipmaps == SamplerDesc::Mipmaps::None)
        fail(ctx, s.path_of("anisotropic"), "\"auto\" needs mipmaps (\"mipmaps\": \"linear\" or \"nearest\"): on a CPU device it means probes, which read coarser levels");
    return d;
}

DistortionDesc read_distortion(const Context& ctx, const json& value, const std::string& path) {
    DistortionDesc d;
    Section s(ctx, value, path);
    const auto vec2 = [&](const std::string& key, glm::vec2& out, const Range& range) {
        if (const json* v = s.find(key)) out = read_vec2(ctx, *v, s.path_of(key), range);
    };
    vec2("amplitude", d.amplitude, closed_range(-1.0, 1.0));
    vec2("frequency", d.frequency, closed_range(-1000.0, 1000.0));
    vec2("position_frequency", d.position_frequency, closed_range(-1000.0, 1000.0));
    vec2("scales", d.scales, closed_range(-1000.0, 1000.0));
    vec2("weights", d.weights, closed_range(0.0, 1.0));
    s.finish();
    return d;
}

MaterialDesc read_material(const Context& ctx, const json& value, const std::string& path) {
    MaterialDesc m;
    Section s(ctx, value, path);
    s.vec3("albedo", m.albedo, Vec::Color);
    s.vec3("specular", m.specular, Vec::Color);
    s.number("shininess", m.shininess, kNonNegative);
    s.vec3("emissive", m.emissive, Vec::Color);
    s.number("roughness", m.roughness, closed_range(0.0, 1.0));
    s.vec3("f0", m.f0, Vec::Color);
    s.number("roughness_x", m.roughness_x, closed_range(0.01, 1.0));
    s.number("roughness_y", m.roughness_y, closed_range(0.01, 1.0));
    s.number("minnaert_k", m.minnaert_k, closed_range(0.0, 4.0));
    // Lab 3: texture maps and how they are read.
    if (const json* v = s.find("albedo_map")) m.albedo_map = read_map(ctx, *v, s.path_of("albedo_map"));
    if (const json* v = s.find("specular_map")) m.specular_map = read_map(ctx, *v, s.path_of("specular_map"));
    if (const json* v = s.find("emissive_map")) m.emissive_map = read_map(ctx, *v, s.path_of("emissive_map"));
    s.number("emissive_strength", m.emissive_strength, kNonNegative);
    s.number("opacity", m.opacity, closed_range(0.0, 1.0));  // lab 4: < 1 is translucent
    if (const json* v = s.find("uv_scale")) m.uv_scale = read_vec2(ctx, *v, s.path_of("uv_scale"), kAnyNumber);
    if (const json* v = s.find("uv_offset")) m.uv_offset = read_vec2(ctx, *v, s.path_of("uv_offset"), kAnyNumber);
    if (const json* v = s.find("sampler")) m.sampler = read_sampler(ctx, *v, s.path_of("sampler"));
    if (const json* v = s.find("sampling"))
        m.distorted = s.choice(*v, "sampling", "sampling mode", {"single", "distorted"}) == 1;
    if (const json* v = s.find("distortion")) m.distortion = read_distortion(ctx, *v, s.path_of("distortion"));
    s.finish();
    if (m.f0.x > 1.0f || m.f0.y > 1.0f || m.f0.z > 1.0f)
        fail(ctx, s.path_of("f0"), "each component must be <= 1 (a reflectance)");
    return m;
}

// Lab 2: "lighting": { "model": ..., "shading": ..., ... } (docs/lighting.md).
LightingDesc read_lighting(const Context& ctx, const json& value) {
    using L = LightingDesc;
    L l;
    Section s(ctx, value, "lighting");
    if (const json* v = s.find("model"))
        l.model = L::Model(s.choice(*v, "model", "lighting model",
                                    {"lambert", "phong", "blinn_phong", "toon", "oren_nayar", "minnaert",
                                     "cook_torrance", "ward"}));
    if (const json* v = s.find("shading"))
        l.shading = L::Shading(s.choice(*v, "shading", "shading model", {"flat", "gouraud", "phong"}));
    if (const json* v = s.find("spot_falloff"))
        l.spot_falloff = L::SpotFalloff(s.choice(*v, "spot_falloff", "spot falloff", {"smooth", "edge"}));
    if (const json* v = s.find("distribution"))
        l.distribution = L::Distribution(s.choice(*v, "distribution", "distribution", {"ggx", "beckmann"}));
    s.integer("toon_bands", l.toon_bands, 1, 16);
    s.boolean("markers", l.markers);
    if (const json* v = s.find("nan_check"))
        l.nan_check = L::NanCheck(s.choice(*v, "nan_check", "nan_check mode", {"off", "on", "self_test"}));
    s.finish();
    return l;
}

// "plane", "cube", ... or a .obj path (relative to the scene file's folder).
void read_mesh(const Context& ctx, const json& value, const std::string& path, ObjectDesc& o) {
    o.mesh = Section::text_of(ctx, value, path);
    const auto& names = primitive_mesh_names();
    if (std::find(names.begin(), names.end(), o.mesh) != names.end()) return;
    if (!ends_with_ci(o.mesh, ".obj"))
        fail(ctx, path, "unknown mesh '" + o.mesh + "'" + suggestion(o.mesh, names) +
                            " (or a file path ending in .obj)");
    fs::path file(o.mesh);
    if (file.is_relative()) file = ctx.base_dir / file;
    std::error_code ec;
    file = fs::absolute(file, ec).lexically_normal();
    o.mesh_path = file.string();
    if (!fs::exists(file, ec)) fail(ctx, path, "mesh file not found: " + o.mesh_path);
    if (!fs::is_regular_file(file, ec)) fail(ctx, path, "mesh path is not a file: " + o.mesh_path);
}

// segments / rings: 0 = the primitive's default, otherwise 3..1024.
void read_tessellation(Section& s, const std::string& key, int& out) {
    s.integer(key, out, 0, kMaxTessellation);
    if (out == 1 || out == 2)
        fail(s.ctx(), s.path_of(key), "must be 0 (default) or in [3, 1024], got " + std::to_string(out));
}

ObjectDesc read_object(const Context& ctx, const json& value, const std::string& path,
                       const std::map<std::string, MaterialDesc>& materials) {
    ObjectDesc o;
    Section s(ctx, value, path);
    read_mesh(ctx, s.required("mesh"), s.path_of("mesh"), o);
    // A model may leave "material" out: its own .mtl materials are used (see expand_model_materials).
    const json* material = o.mesh_path.empty() ? &s.required("material") : s.find("material");
    if (material) o.material = Section::text_of(ctx, *material, s.path_of("material"));
    if (material && materials.count(o.material) == 0) {
        std::vector<std::string> names;
        for (const auto& m : materials) names.push_back(m.first);
        fail(ctx, s.path_of("material"), "unknown material '" + o.material + "'" + suggestion(o.material, names));
    }
    s.vec3("position", o.position, Vec::Coordinate);
    s.vec3("rotation_deg", o.rotation_deg, Vec::Coordinate);
    s.vec3("scale", o.scale, Vec::Scale);
    if (o.mesh == "icosphere")
        s.integer("segments", o.segments, 0, 7);  // the subdivision level (0 = default 2)
    else
        read_tessellation(s, "segments", o.segments);
    read_tessellation(s, "rings", o.rings);
    s.number("crease_deg", o.crease_deg, closed_range(0.0, 180.0));
    s.boolean("normalize", o.normalize);
    s.boolean("cast_shadows", o.cast_shadows);  // lab 4
    s.finish();
    return o;
}

const json& expect_array(const Context& ctx, const json& value, const std::string& path) {
    if (!value.is_array()) fail(ctx, path, std::string("expected an array [ ... ], got ") + value.type_name());
    return value;
}

// Models without a "material" key use the materials of their .mtl file: the
// object is split into one object per material (ObjectDesc::obj_material picks
// its triangles) and each .mtl material becomes a scene material named
// "MODEL.obj#NAME" (Kd → albedo, Ks → specular, Ns → shininess, Ke → emissive; map_Kd,
// map_Ks, map_Ke → albedo_map, specular_map, emissive_map).
// Triangles with no material — or a model with no .mtl — use "MODEL.obj#default"
// (the format's default material). Renderers and the CPU reference then see
// ordinary objects and need no special case.
void expand_model_materials(const Context& ctx, Scene& scene) {
    std::vector<ObjectDesc> expanded;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const ObjectDesc& object = scene.objects[i];
        if (object.mesh_path.empty() || !object.material.empty()) {
            expanded.push_back(object);
            continue;
        }
        LoadedModel model;
        try {
            model = load_obj(object.mesh_path, object.crease_deg, object.normalize);
        } catch (const std::exception& e) {
            fail(ctx, index_path("objects", i) + ".mesh", e.what());
        }
        std::vector<bool> used(model.materials.size() + 1, false);  // [0] = "no material"
        for (int m : model.triangle_material) used[size_t(m + 1)] = true;
        for (int m = -1; m < int(model.materials.size()); ++m) {
            if (!used[size_t(m + 1)]) continue;
            ObjectDesc part = object;
            part.obj_material = m;
            part.material = object.mesh + "#" + (m < 0 ? "default" : model.materials[size_t(m)].name);
            MaterialDesc desc;  // "#default": the format's default material
            if (m >= 0) {
                const ObjMaterial& mtl = model.materials[size_t(m)];
                desc.albedo = mtl.albedo;
                desc.specular = mtl.specular;
                desc.shininess = mtl.shininess;
                desc.emissive = mtl.emissive;
                desc.albedo_map = mtl.albedo_texture;  // map_Kd, map_Ks, map_Ke (lab 3)
                desc.specular_map = mtl.specular_texture;
                desc.emissive_map = mtl.emissive_texture;
            }
            scene.materials[part.material] = desc;
            expanded.push_back(part);
        }
    }
    scene.objects = std::move(expanded);
}

Scene read_scene(const Context& ctx, const json& root) {
    Scene scene;
    Section s(ctx, root, "");
    if (const json* v = s.find("camera")) scene.camera = read_camera(ctx, *v);
    s.vec3("background", scene.background, Vec::Color);
    if (const json* v = s.find("ambient")) scene.ambient = read_ambient(ctx, *v);
    if (const json* v = s.find("lighting")) scene.lighting = read_lighting(ctx, *v);
    if (const json* v = s.find("lights")) {
        for (const json& light : expect_array(ctx, *v, "lights"))
            scene.lights.push_back(read_light(ctx, light, index_path("lights", scene.lights.size())));
    }
    // "objects" is required (it may be empty); "materials" only when there are objects.
    const json& objects = expect_array(ctx, s.required("objects"), "objects");
    const json* materials = s.find("materials");
    if (!materials && !objects.empty())
        fail(ctx, "materials", "missing required key (objects refer to materials by name)");
    if (materials) {
        if (!materials->is_object())
            fail(ctx, "materials", std::string("expected an object { \"name\": {...} }, got ") +
                                       materials->type_name());
        for (const auto& item : materials->items()) {
            const std::string path = key_path("materials", item.key());
            if (item.key().empty()) fail(ctx, path, "material name must not be empty");
            scene.materials[item.key()] = read_material(ctx, item.value(), path);
        }
    }
    for (const json& object : objects)
        scene.objects.push_back(
            read_object(ctx, object, index_path("objects", scene.objects.size()), scene.materials));
    s.finish();
    expand_model_materials(ctx, scene);
    return scene;
}

// --- JSON syntax ---------------------------------------------------------------

// A first pass over the text with nlohmann's SAX interface. It finds
//  - the byte position of a syntax error (json::parse reports the position of
//    most errors, but not of number overflow such as 1e400), and
//  - duplicate keys, which json::parse would silently resolve to the last one.
class SyntaxCheck : public json::json_sax_t {
public:
    size_t error_offset = 0;     // 0-based byte offset of a syntax error
    std::string error_message;   // set on a syntax error
    std::string duplicate_path;  // set on a duplicate key

    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override { return open(true); }
    bool start_array(std::size_t) override { return open(false); }
    bool end_object() override { return close(); }
    bool end_array() override { return close(); }

    bool key(string_t& k) override {
        Level& level = stack_.back();
        if (!level.keys.insert(k).second) {
            stack_.pop_back();  // the path of the enclosing object, plus the key
            duplicate_path = key_path(path(), k);
            return false;
        }
        level.key = k;
        return true;
    }

    bool parse_error(std::size_t position, const std::string& last_token, const json::exception& ex) override {
        // nlohmann counts the offending character as read: it is at position - 1.
        error_offset = position > 0 ? position - 1 : 0;
        // A number that overflows (id 406) is reported at its last digit; point at its first.
        if (ex.id == 406 && last_token.size() <= error_offset) error_offset -= last_token.size() - 1;
        error_message = ex.what();
        return false;
    }

private:
    struct Level {
        bool is_object;
        std::set<std::string> keys;  // objects: keys seen so far
        std::string key;             // objects: the current key
        size_t index = 0;            // arrays: the current element
    };
    std::vector<Level> stack_;

    std::string path() const {
        std::string p;
        for (const Level& level : stack_)
            p = level.is_object ? key_path(p, level.key) : index_path(p, level.index);
        return p;
    }
    // A value finished: the enclosing array moves on to its next element.
    bool value() {
        if (!stack_.empty() && !stack_.back().is_object) ++stack_.back().index;
        return true;
    }
    bool open(bool is_object) {
        stack_.push_back(Level{is_object, {}, {}, 0});
        return true;
    }
    bool close() {
        stack_.pop_back();
        return value();
    }
};

// "line L, column C" of the character at 0-based byte `offset`.
std::string line_column(const std::string& text, size_t offset) {
    offset = std::min(offset, text.size());
    size_t line = 1, line_start = 0;
    for (size_t i = 0; i < offset; ++i)
        if (text[i] == '\n') {
            ++line;
            line_start = i + 1;
        }
    return "line " + std::to_string(line) + ", column " + std::to_string(offset - line_start + 1);
}

// nlohmann's message without its "[json.exception.parse_error.101] parse error at line 1, column 2: " prefix.
std::string strip_nlohmann_prefix(std::string message) {
    if (!message.empty() && message[0] == '[') {
        const size_t end = message.find("] ");
        if (end != std::string::npos) message = message.substr(end + 2);
    }
    if (message.rfind("parse error", 0) == 0) {
        const size_t colon = message.find(": ");
        if (colon != std::string::npos) message = message.substr(colon + 2);
    }
    return message;
}

json parse_json(const Context& ctx, const std::string& text) {
    SyntaxCheck check;
    if (!json::sax_parse(text, &check)) {
        if (!check.duplicate_path.empty()) fail(ctx, check.duplicate_path, "duplicate key");
        throw SceneError(ctx.label + ": " + line_column(text, check.error_offset) +
                         ": malformed JSON: " + strip_nlohmann_prefix(check.error_message));
    }
    return json::parse(text);  // cannot fail after the check above
}

}  // namespace

Scene parse_scene(const std::string& json_text, const std::string& file_label, const std::string& base_dir) {
    Context ctx{file_label.empty() ? "<scene>" : file_label, fs::path(base_dir)};
    const json root = parse_json(ctx, json_text);
    if (!root.is_object())
        fail(ctx, "", std::string("the scene must be a JSON object { ... }, got ") + root.type_name());
    return read_scene(ctx, root);
}

Scene load_scene(const std::string& file) {
    std::error_code ec;
    if (fs::is_directory(file, ec)) throw SceneError(file + ": cannot read scene: is a directory");
    // Only a regular file of sane size: /dev/zero or a FIFO would be read forever.
    if (fs::exists(file, ec) && !fs::is_regular_file(file, ec))
        throw SceneError(file + ": cannot read scene: not a regular file");
    if (const std::uintmax_t size = fs::file_size(file, ec); !ec && size > kMaxSceneBytes)
        throw SceneError(file + ": cannot read scene: file too large (" + std::to_string(size) +
                         " bytes; at most 16 MiB)");
    std::ifstream in(file, std::ios::binary);
    if (!in) throw SceneError(file + ": cannot read scene: " + std::generic_category().message(errno));
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw SceneError(file + ": cannot read scene: read error");
    // Relative mesh paths start at the scene file's folder, wherever the lab runs from.
    const fs::path folder = fs::absolute(fs::path(file), ec).parent_path();
    Scene scene = parse_scene(text.str(), file, folder.string());
    scene.file = file;
    return scene;
}

glm::mat4 model_matrix(const ObjectDesc& object) {
    // Read right to left: scale, then rotate about X, Y, Z, then move into place.
    glm::mat4 m = glm::translate(glm::mat4(1.0f), object.position);
    m = glm::rotate(m, glm::radians(object.rotation_deg.z), glm::vec3(0, 0, 1));
    m = glm::rotate(m, glm::radians(object.rotation_deg.y), glm::vec3(0, 1, 0));
    m = glm::rotate(m, glm::radians(object.rotation_deg.x), glm::vec3(1, 0, 0));
    return glm::scale(m, object.scale);
}

}  // namespace lab
