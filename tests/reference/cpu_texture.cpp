// cpu_texture.cpp — see cpu_texture.h. Double precision throughout.
#include "reference/cpu_texture.h"

#include "reference/cpu_shadow.h"

#include "reference/cpu_lighting.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <thread>

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace ref {
namespace {

using Wrap = lab::SamplerDesc::Wrap;
using Filter = lab::SamplerDesc::Filter;
using Mipmaps = lab::SamplerDesc::Mipmaps;

// The procedural sources, from their formulas (docs/scene-format.md).
std::vector<unsigned char> procedural(const std::string& name, int* w, int* h) {
    std::vector<unsigned char> p;
    const auto push = [&p](int r, int g, int b) { p.insert(p.end(), {(unsigned char)r, (unsigned char)g, (unsigned char)b, 255}); };
    if (name == "checker") {
        *w = *h = 8;
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) {
                const int v = (x + y) % 2 ? 64 : 255;
                push(v, v, v);
            }
    } else if (name == "metal") {
        *w = *h = 256;
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) {
                // The seed computes in float and truncates; so does this (one float rounding apart
                // from double could move a value across an integer).
                const float m = (std::sin(float(x) * 0.1f) * std::cos(float(y) * 0.1f) + 1.0f) * 0.5f;
                const int v = int(m * 255.0f);
                push(v, v, v);
            }
    } else if (name == "grid") {
        *w = *h = 256;
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) {
                const bool line = x % 32 < 2 || y % 32 < 2;
                push(0, line ? 200 : 0, line ? 255 : 0);
            }
    } else {  // the fallback: magenta / black, 8×8
        *w = *h = 8;
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) push((x + y) % 2 ? 0 : 255, 0, (x + y) % 2 ? 0 : 255);
    }
    return p;
}

double decode_srgb8(unsigned char v) { return srgb_decode(v / 255.0); }

// How much of parent texel [p, p + 1) lies in the child's span [a, b) (one axis, parent units).
double overlap(int p, double a, double b) { return std::max(0.0, std::min(b, p + 1.0) - std::max(a, double(p))); }

// The next mip level: the box filter. The child texel (x, y) covers the parent rectangle
// [x·W/w, (x+1)·W/w) × [y·H/h, (y+1)·H/h) (W, w: parent and child widths); it is the mean of the
// parent over that rectangle, each parent texel weighted by its overlap (area / total area).
TextureLevel downsample(const TextureLevel& in) {
    TextureLevel out;
    out.width = std::max(in.width / 2, 1);
    out.height = std::max(in.height / 2, 1);
    out.texels.resize(size_t(out.width) * size_t(out.height));
    const double sx = double(in.width) / out.width, sy = double(in.height) / out.height;
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            const double ax = x * sx, bx = (x + 1) * sx, ay = y * sy, by = (y + 1) * sy;
            glm::dvec4 sum(0.0);
            for (int py = int(ay); py < in.height && py < by; ++py)
                for (int px = int(ax); px < in.width && px < bx; ++px) sum += overlap(px, ax, bx) * overlap(py, ay, by) * in.at(px, py);
            out.texels[size_t(y) * size_t(out.width) + size_t(x)] = sum / (sx * sy);
        }
    return out;
}

double fract(double x) { return x - std::floor(x); }

// Albedo and emissive maps are colours, sRGB-encoded as image files store them; the specular map is
// data, a factor in [0, 1]: byte / 255, no sRGB decoding. (Internal: exercise texel_format's answer,
// which a student copy's prebuilt library must not answer when called.)
bool map_holds_colour(int binding) { return binding != 1; }

}  // namespace

namespace {
// A material's map at `binding` (0 albedo, 1 specular, 2 emissive); empty: none.
const std::string& map_at(const lab::MaterialDesc& m, int binding) {
    return binding == 0 ? m.albedo_map : binding == 1 ? m.specular_map : m.emissive_map;
}
}  // namespace

RefTexture make_texture(int width, int height, const std::vector<unsigned char>& srgb_rgba, bool mipmaps, bool srgb) {
    RefTexture t;
    TextureLevel level;
    level.width = width;
    level.height = height;
    const auto decode = [srgb](unsigned char v) { return srgb ? decode_srgb8(v) : v / 255.0; };
    for (size_t i = 0; i + 3 < srgb_rgba.size(); i += 4)
        level.texels.emplace_back(decode(srgb_rgba[i]), decode(srgb_rgba[i + 1]), decode(srgb_rgba[i + 2]), srgb_rgba[i + 3] / 255.0);
    t.levels.push_back(std::move(level));
    while (mipmaps && (t.levels.back().width > 1 || t.levels.back().height > 1))
        t.levels.push_back(downsample(t.levels.back()));
    return t;
}

RefTexture load_texture(const std::string& map, bool mipmaps, int max_dimension, bool srgb) {
    int w = 0, h = 0;
    const std::string prefix = "procedural:";
    if (map.rfind(prefix, 0) == 0) return make_texture(w, h, procedural(map.substr(prefix.size()), &w, &h), mipmaps, srgb);
    std::error_code ec;
    std::ifstream in(map, std::ios::binary);
    std::vector<unsigned char> bytes;
    if (in && !std::filesystem::is_directory(map, ec)) bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    int channels = 0;
    bool ok = !bytes.empty() && stbi_info_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels) && w > 0 &&
              h > 0 && w <= max_dimension && h <= max_dimension;
    unsigned char* pixels = ok ? stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels, 4) : nullptr;
    if (!pixels) {
        RefTexture t = make_texture(w, h, procedural("", &w, &h), mipmaps, srgb);
        t.fallback = true;
        return t;
    }
    std::vector<unsigned char> rgba(pixels, pixels + size_t(w) * size_t(h) * 4);
    stbi_image_free(pixels);
    return make_texture(w, h, rgba, mipmaps, srgb);
}

int wrap_texel(int i, int size, Wrap wrap) {
    switch (wrap) {
        case Wrap::Repeat: return ((i % size) + size) % size;
        case Wrap::Clamp: return std::clamp(i, 0, size - 1);
        case Wrap::Mirror: {
            // spec: t = (i mod 2·size) − size; mirror(t) = t ≥ 0 ? t : −(1 + t); i' = size − 1 − mirror(t)
            const int t = ((i % (2 * size)) + 2 * size) % (2 * size) - size;
            const int m = t >= 0 ? t : -(1 + t);
            return size - 1 - m;
        }
    }
    return 0;
}

glm::dvec4 sample_level(const TextureLevel& level, glm::dvec2 uv, Filter filter, Wrap wrap, glm::dvec2 texel_shift) {
    // Unnormalized texel coordinates; for huge |u| the repeat is taken first, in double, so
    // that the fraction keeps its precision (what a GPU does with float is documented in the lab).
    if (wrap == Wrap::Repeat) uv = glm::dvec2(fract(uv.x), fract(uv.y));
    const double u = uv.x * level.width + texel_shift.x, v = uv.y * level.height + texel_shift.y;
    if (filter == Filter::Nearest) {
        const int i = wrap_texel(int(std::floor(u)), level.width, wrap);
        const int j = wrap_texel(int(std::floor(v)), level.height, wrap);
        return level.at(i, j);
    }
    const double u0 = u - 0.5, v0 = v - 0.5;
    const int i0 = int(std::floor(u0)), j0 = int(std::floor(v0));
    const double a = u0 - i0, b = v0 - j0;
    const int ia = wrap_texel(i0, level.width, wrap), ib = wrap_texel(i0 + 1, level.width, wrap);
    const int ja = wrap_texel(j0, level.height, wrap), jb = wrap_texel(j0 + 1, level.height, wrap);
    return (1 - a) * (1 - b) * level.at(ia, ja) + a * (1 - b) * level.at(ib, ja) + (1 - a) * b * level.at(ia, jb) +
           a * b * level.at(ib, jb);
}

double lod(const TextureLevel& level0, glm::dvec2 dx, glm::dvec2 dy) {
    const glm::dvec2 size(level0.width, level0.height);
    const double rho = std::max(glm::length(dx * size), glm::length(dy * size));
    return rho > 0.0 ? std::log2(rho) : -1e9;
}

glm::dvec2 lod_bounds(const TextureLevel& level0, glm::dvec2 dx, glm::dvec2 dy) {
    const glm::dvec2 size(level0.width, level0.height);
    const glm::dvec2 mx = glm::abs(dx * size), my = glm::abs(dy * size);  // |∂u/∂x|, |∂v/∂x| in texels
    const double low = std::max(std::max(mx.x, mx.y), std::max(my.x, my.y));
    const double high = std::sqrt(3.0) * std::max(mx.x + mx.y, my.x + my.y);
    return low > 0.0 ? glm::dvec2(std::log2(low), std::log2(high)) : glm::dvec2(-1e9);
}

glm::dvec4 sample(const RefTexture& texture, const lab::SamplerDesc& desc, glm::dvec2 uv, glm::dvec2 dx,
                  glm::dvec2 dy, const SamplingVariant& variant) {
    const int q = int(texture.levels.size()) - 1;
    double exact = lod(texture.levels[0], dx, dy);
    if (variant.lod_between >= 0.0) {
        const glm::dvec2 range = lod_bounds(texture.levels[0], dx, dy);
        exact = glm::mix(range.x, range.y, variant.lod_between);
    }
    const double lambda = desc.mipmaps == Mipmaps::None ? std::min(exact, 0.0) : std::min(exact, double(q));
    // The variant's texel coordinates at level d (SamplingVariant): the sub-texel rounding plus the
    // vertex snapping's move across this lookup's footprint, both in level d's texels.
    const auto shift = [&](int d) {
        const glm::dvec2 size(texture.levels[size_t(d)].width, texture.levels[size_t(d)].height);
        const glm::dvec2 footprint = (glm::abs(dx) + glm::abs(dy)) * size;  // texels per pixel, per axis
        return variant.corner * (variant.texel_step + variant.pixel_step * footprint);
    };
    if (lambda <= 0.0 || q == 0) return sample_level(texture.levels[0], uv, desc.filter, desc.wrap, shift(0));
    if (desc.mipmaps == Mipmaps::Nearest) {
        const int d = std::clamp(int(std::ceil(lambda + 0.5)) - 1, 0, q);
        return sample_level(texture.levels[size_t(d)], uv, desc.filter, desc.wrap, shift(d));
    }
    const int d = std::min(int(std::floor(lambda)), q);
    const double delta = lambda - d;
    const glm::dvec4 hi = sample_level(texture.levels[size_t(d)], uv, desc.filter, desc.wrap, shift(d));
    if (d >= q || delta == 0.0) return hi;
    return (1.0 - delta) * hi + delta * sample_level(texture.levels[size_t(d + 1)], uv, desc.filter, desc.wrap, shift(d + 1));
}

namespace {

struct TexturedScene {
    std::vector<lab::Mesh> meshes;
    std::vector<glm::dmat4> models;
    Camera camera;
    int width = 0, height = 0;
    bool level0 = false;
    std::map<std::tuple<std::string, bool, bool>, std::shared_ptr<const RefTexture>> textures;  // [map, mipmaps, sRGB colour]

    const RefTexture* texture(const std::string& map, const lab::SamplerDesc& s, bool srgb) const {
        if (map.empty()) return nullptr;
        return textures.at({map, s.mipmaps != Mipmaps::None, srgb}).get();
    }
};

// A decoded map and its mip chain are the same for every shader made from a scene: a lab 3 test's
// envelope makes 24 shaders and a LOD probe besides the reference's own, and decoding and
// filtering each map 26 times was about half the test's time. One copy per process and (map,
// mipmaps, sRGB), for a file also per its size and modification time (a test may rewrite a file).
std::shared_ptr<const RefTexture> shared_texture(const std::string& map, bool mips, bool srgb) {
    static std::mutex lock;
    static std::map<std::string, std::shared_ptr<const RefTexture>> made;
    std::string key = map + (mips ? "|mips" : "|level0") + (srgb ? "|srgb" : "|unorm");
    std::error_code ec;
    if (map.rfind("procedural:", 0) != 0 && std::filesystem::is_regular_file(map, ec)) {
        const auto size = std::filesystem::file_size(map, ec);
        const auto time = std::filesystem::last_write_time(map, ec).time_since_epoch().count();
        key += "|" + std::to_string(size) + "|" + std::to_string(time);
    }
    const std::lock_guard<std::mutex> guard(lock);
    std::shared_ptr<const RefTexture>& slot = made[key];
    if (!slot) slot = std::make_shared<const RefTexture>(load_texture(map, mips, 16384, srgb));
    return slot;
}

// The hit's triangle: world corners, their UVs and tangents, barycentric weights of the hit.
struct Triangle {
    glm::dvec3 p[3];
    glm::dvec2 uv[3];
    glm::dvec3 tangent[3];
    double w[3];
};

Triangle triangle_of(const TexturedScene& data, const Hit& hit) {
    const lab::Mesh& mesh = data.meshes.at(size_t(hit.object_id));
    const glm::dmat4& M = data.models[size_t(hit.object_id)];
    Triangle t{};
    for (int k = 0; k < 3; ++k) {
        const lab::Vertex& v = mesh.vertices.at(mesh.indices.at(size_t(hit.triangle_id) * 3 + size_t(k)));
        t.p[k] = glm::dvec3(M * glm::dvec4(glm::dvec3(v.position), 1.0));
        t.uv[k] = glm::dvec2(v.uv);
        t.tangent[k] = glm::dmat3(M) * glm::dvec3(v.tangent);
    }
    const glm::dvec3 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0], q = hit.position - t.p[0];
    const double d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
    const double det = d00 * d11 - d01 * d01;
    t.w[1] = det != 0.0 ? (d11 * glm::dot(q, e1) - d01 * glm::dot(q, e2)) / det : 1.0 / 3.0;
    t.w[2] = det != 0.0 ? (d00 * glm::dot(q, e2) - d01 * glm::dot(q, e1)) / det : 1.0 / 3.0;
    t.w[0] = 1.0 - t.w[1] - t.w[2];
    return t;
}

// Ray differentials (Igehy 1999): how the hit point moves when the pixel moves by one in x
// (or y). The primary ray's direction is d = cx·right + cy·up + forward, linear in the pixel
// position; the hit on the triangle's plane is P = eye + t·d with t = n·(v0 − eye)/(n·d), so
// ∂P = t·(∂d − d·(n·∂d)/(n·d)). The barycentric change follows from ∂P in the triangle's basis.
void uv_derivatives(const TexturedScene& data, const Hit& hit, const Triangle& tri, glm::dvec2* duv_dx,
                    glm::dvec2* duv_dy, glm::dvec3* dp_dx, glm::dvec3* dp_dy) {
    const Camera& c = data.camera;
    const double tan_half = std::tan(c.fov_y_deg * 3.14159265358979323846 / 360.0);
    const double aspect = double(data.width) / data.height;
    const glm::dvec3 dd_dx = c.right * (2.0 * tan_half * aspect / data.width);
    const glm::dvec3 dd_dy = -c.up * (2.0 * tan_half / data.height);
    const glm::dvec3 to_hit = hit.position - c.eye;
    const double depth = glm::dot(to_hit, c.forward);
    const glm::dvec3 d = to_hit / depth;  // forward component exactly 1: t = depth
    const glm::dvec3 n = hit.geometric_normal;
    const double nd = glm::dot(n, d);
    const glm::dvec3 e1 = tri.p[1] - tri.p[0], e2 = tri.p[2] - tri.p[0];
    const double d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
    const double det = d00 * d11 - d01 * d01;
    const auto along = [&](const glm::dvec3& dd, glm::dvec3* dp) {
        *dp = nd != 0.0 ? depth * (dd - d * (glm::dot(n, dd) / nd)) : glm::dvec3(0.0);
        if (det == 0.0) return glm::dvec2(0.0);
        const double b1 = (d11 * glm::dot(*dp, e1) - d01 * glm::dot(*dp, e2)) / det;
        const double b2 = (d00 * glm::dot(*dp, e2) - d01 * glm::dot(*dp, e1)) / det;
        return b1 * (tri.uv[1] - tri.uv[0]) + b2 * (tri.uv[2] - tri.uv[0]);
    };
    *duv_dx = along(dd_dx, dp_dx);
    *duv_dy = along(dd_dy, dp_dy);
}


std::shared_ptr<TexturedScene> textured_scene(const lab::Scene& scene, int width, int height, bool level0) {
    auto data = std::make_shared<TexturedScene>();
    lab::MeshLibrary library;
    for (const lab::ObjectDesc& object : scene.objects) {
        data->meshes.push_back(library.mesh(object));
        data->models.push_back(ref::model_matrix(object));
    }
    data->camera = make_camera(scene.camera);
    data->width = width;
    data->height = height;
    data->level0 = level0;
    for (const auto& [name, m] : scene.materials)
        for (int binding = 0; binding < 3; ++binding)
            if (const std::string& map = map_at(m, binding); !map.empty()) {
                const bool mips = m.sampler.mipmaps != Mipmaps::None, srgb = map_holds_colour(binding);
                if (!data->textures.count({map, mips, srgb})) data->textures[{map, mips, srgb}] = shared_texture(map, mips, srgb);
            }
    return data;
}

}  // namespace

std::function<double(const Hit&)> make_lod_probe(const lab::Scene& scene, int width, int height) {
    const std::shared_ptr<TexturedScene> data = textured_scene(scene, width, height, false);
    return [data, materials = scene.materials](const Hit& hit) {
        if (!hit.hit) return -1e9;
        const lab::MaterialDesc& m = materials.at(hit.material);
        const int binding = !m.albedo_map.empty() ? 0 : !m.specular_map.empty() ? 1 : 2;
        const std::string& map = map_at(m, binding);
        if (map.empty()) return -1e9;
        const Triangle tri = triangle_of(*data, hit);
        glm::dvec2 dx, dy;
        glm::dvec3 dpx, dpy;
        uv_derivatives(*data, hit, tri, &dx, &dy, &dpx, &dpy);
        const glm::dvec2 scale(m.uv_scale);
        return lod(data->texture(map, m.sampler, map_holds_colour(binding))->levels[0], dx * scale, dy * scale);
    };
}

glm::dvec2 material_uv(const lab::MaterialDesc& m, glm::dvec2 uv) {
    return uv * glm::dvec2(m.uv_scale) + glm::dvec2(m.uv_offset);
}

ShadeFn make_texture_shader(const lab::Scene& scene, int width, int height, bool supersample_level0,
                            const SamplingVariant& variant, std::shared_ptr<const ShadowCasters> shadows) {
    const std::shared_ptr<TexturedScene> data = textured_scene(scene, width, height, supersample_level0);
    const lab::LightingDesc::Shading shading_model = scene.lighting.shading;
    return [data, shading_model, variant, shadows](const lab::Scene& s, const Hit& hit) -> glm::dvec3 {
        if (!hit.hit) return glm::dvec3(s.background);
        const lab::MaterialDesc& m = s.materials.at(hit.material);
        const glm::dvec3 N = shading_model == lab::LightingDesc::Shading::Flat || glm::dot(hit.normal, hit.normal) == 0.0
                                 ? hit.geometric_normal
                                 : hit.normal;
        const glm::dvec3 to_eye = data->camera.eye - hit.position;
        const glm::dvec3 V = glm::length(to_eye) > 1e-10 ? glm::normalize(to_eye) : N;
        const Triangle tri = triangle_of(*data, hit);
        glm::dvec3 tangent(0.0);
        for (int k = 0; k < 3; ++k) tangent += tri.w[k] * tri.tangent[k];
        // Lab 4: the light of shadow-casting lights that reaches the hit.
        const LightVisibility visible = [&](const lab::LightDesc& light) {
            return shadows->transmittance(light, hit.position, hit.geometric_normal);
        };
        const LightVisibility* visibility = shadows ? &visible : nullptr;
        if (!m.has_maps()) return shade_point(s, m, hit.position, N, V, tangent, nullptr, visibility);

        glm::dvec2 dx(0.0), dy(0.0);
        glm::dvec3 dpx(0.0), dpy(0.0);
        if (!data->level0) uv_derivatives(*data, hit, tri, &dx, &dy, &dpx, &dpy);
        const glm::dvec2 scale(m.uv_scale);
        const glm::dvec2 uv = material_uv(m, hit.uv);
        dx *= scale;
        dy *= scale;
        lab::SamplerDesc sampler = m.sampler;
        if (data->level0) sampler.filter = Filter::Linear;  // derivatives 0: level 0, bilinear
        // The map at `binding` (map_at), read as map_holds_colour says.
        const auto lookup = [&](int binding, glm::dvec2 at, glm::dvec2 ddx, glm::dvec2 ddy) {
            return glm::dvec3(sample(*data->texture(map_at(m, binding), m.sampler, map_holds_colour(binding)), sampler, at, ddx, ddy, variant));
        };
        lab::MaterialDesc textured = m;
        if (!m.albedo_map.empty()) {
            glm::dvec3 A;
            if (m.distorted) {
                // d = uv + (ax·sin(fx·v + px·P.y), ay·cos(fy·u + py·P.x)) and its derivatives (chain rule).
                const lab::DistortionDesc& k = m.distortion;
                const double su = double(k.frequency.x) * uv.y + double(k.position_frequency.x) * hit.position.y;
                const double sv = double(k.frequency.y) * uv.x + double(k.position_frequency.y) * hit.position.x;
                const glm::dvec2 d = uv + glm::dvec2(k.amplitude.x * std::sin(su), k.amplitude.y * std::cos(sv));
                const auto dd = [&](glm::dvec2 duv, glm::dvec3 dp) {
                    return duv + glm::dvec2(k.amplitude.x * std::cos(su) * (k.frequency.x * duv.y + k.position_frequency.x * dp.y),
                                            -k.amplitude.y * std::sin(sv) * (k.frequency.y * duv.x + k.position_frequency.y * dp.x));
                };
                const double s1 = k.scales.x, s2 = k.scales.y;
                const glm::dvec3 t0 = lookup(0, d, dd(dx, dpx), dd(dy, dpy));
                const glm::dvec3 t1 = lookup(0, s1 * uv, s1 * dx, s1 * dy);
                const glm::dvec3 t2 = lookup(0, s2 * uv, s2 * dx, s2 * dy);
                A = glm::mix(glm::mix(t0, t1, double(k.weights.x)), t2, double(k.weights.y));
            } else {
                A = lookup(0, uv, dx, dy);
            }
            textured.albedo = glm::vec3(glm::dvec3(m.albedo) * A);
        }
        if (!m.specular_map.empty())
            textured.specular = glm::vec3(glm::dvec3(m.specular) * lookup(1, uv, dx, dy));
        if (!m.emissive_map.empty())
            textured.emissive = glm::vec3(glm::dvec3(m.emissive) +
                                          double(m.emissive_strength) * lookup(2, uv, dx, dy));
        return shade_point(s, textured, hit.position, N, V, tangent, nullptr, visibility);
    };
}

RefImage render_supersampled(const lab::Scene& scene, int width, int height, int n) {
    const ShadeFn shade = make_texture_shader(scene, width, height, true);
    const SceneGeometry geometry(scene);
    const Camera camera = make_camera(scene.camera);
    RefImage image;
    image.width = width;
    image.height = height;
    image.linear.assign(size_t(width) * size_t(height), glm::dvec3(0.0));
    image.object_id.assign(image.linear.size(), -1);
    image.triangle_id.assign(image.linear.size(), -1);
    image.hits.assign(image.linear.size(), Hit{});
    const auto row = [&](int y) {
        for (int x = 0; x < width; ++x) {
            glm::dvec3 sum(0.0);
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const Ray ray = primary_ray(camera, width, height, x + (i + 0.5) / n, y + (j + 0.5) / n);
                    Hit hit;
                    if (geometry.trace(ray, camera.near_plane, camera.far_plane, &hit)) {
                        hit.material = scene.objects[size_t(hit.object_id)].material;
                        hit.view_dir = glm::normalize(camera.eye - hit.position);
                    }
                    sum += shade(scene, hit);
                }
            image.linear[size_t(image.index(x, y))] = sum / double(n * n);
        }
    };
    // The pixel-centre ray gives the ids (for edge masks).
    const RefImage centre = render_reference(scene, width, height, shade);
    image.object_id = centre.object_id;
    image.triangle_id = centre.triangle_id;
    image.hits = centre.hits;
    const unsigned threads = std::max(1u, std::min(std::thread::hardware_concurrency(), 8u));
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            for (int y = int(t); y < height; y += int(threads)) row(y);
        });
    for (std::thread& th : pool) th.join();
    return image;
}

}  // namespace ref
