// cpu_lighting.cpp — lab 2's lighting in double precision (see cpu_lighting.h and docs/lighting.md).
#include "reference/cpu_lighting.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace ref {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The documented safety constants (docs/lighting.md, "Numerical safety").
constexpr double kMinLength2 = 1e-20;
constexpr double kMinDenominator = 1e-6;
constexpr double kMinCosView = 1e-3;
constexpr double kMinCosHalf = 1e-4;
constexpr double kMinAlpha = 1e-3;
constexpr double kMinConeWidth = 1e-6;

using Model = lab::LightingDesc::Model;
using Shading = lab::LightingDesc::Shading;
using Type = lab::LightDesc::Type;

glm::dvec3 unit_or(const glm::dvec3& v, const glm::dvec3& fallback) {
    const double len2 = glm::dot(v, v);
    return len2 > kMinLength2 ? v / std::sqrt(len2) : fallback;
}

bool finite(double x) { return std::isfinite(x); }
bool finite(const glm::dvec3& v) { return finite(v.x) && finite(v.y) && finite(v.z); }

// x^n for x ≥ 0, with x^0 = 1 (also for x = 0).
double power(double x, double n) {
    if (n <= 0.0) return 1.0;
    return x > 0.0 ? std::pow(x, n) : 0.0;
}

struct Frame {  // the surface point's unit vectors
    glm::dvec3 N, V, T;
};

// Per unit radiance: what light arriving from unit direction L adds (docs/lighting.md, table of models).
glm::dvec3 reflectance(const lab::Scene& scene, const lab::MaterialDesc& m, const Frame& f, const glm::dvec3& L,
                       bool* bad) {
    const glm::dvec3& N = f.N;
    const glm::dvec3& V = f.V;
    const double nl = glm::dot(N, L);
    if (!(nl > 0.0)) return glm::dvec3(0.0);
    const glm::dvec3 a(m.albedo), s(m.specular);
    const double n = m.shininess;
    const double nv = glm::dot(N, V);
    const glm::dvec3 H = unit_or(L + V, N);
    const double nh = std::max(glm::dot(N, H), 0.0);
    const Model model = scene.lighting.model;

    glm::dvec3 diffuse = a * nl;
    glm::dvec3 specular(0.0);
    switch (model) {
        case Model::Lambert:
            return diffuse;
        case Model::Phong: {
            const glm::dvec3 R = 2.0 * nl * N - L;  // L mirrored about N
            specular = s * power(std::max(glm::dot(R, V), 0.0), n);
            break;
        }
        case Model::BlinnPhong:
            specular = s * power(nh, n);
            break;
        case Model::Toon: {
            const double bands = scene.lighting.toon_bands;
            diffuse = a * (std::ceil(nl * bands) / bands);
            specular = s * (power(nh, n) > 0.5 ? 1.0 : 0.0);
            break;
        }
        case Model::OrenNayar: {
            const double sigma2 = double(m.roughness) * m.roughness;
            const double A = 1.0 - 0.5 * sigma2 / (sigma2 + 0.33);
            const double B = 0.45 * sigma2 / (sigma2 + 0.09);
            const double nvc = std::clamp(nv, 0.0, 1.0);
            const glm::dvec3 lp = L - N * nl, vp = V - N * nvc;  // projections onto the tangent plane
            const double lv = glm::dot(lp, lp) * glm::dot(vp, vp);
            const double cos_phi = lv > kMinLength2 ? glm::dot(lp, vp) / std::sqrt(lv) : 0.0;
            const double cos_alpha = std::min(nl, nvc), cos_beta = std::max(nl, nvc);  // α = max(θi, θr)
            const double sin_alpha = std::sqrt(std::max(1.0 - cos_alpha * cos_alpha, 0.0));
            const double tan_beta = std::sqrt(std::max(1.0 - cos_beta * cos_beta, 0.0)) / cos_beta;
            diffuse = a * nl * (A + B * std::max(cos_phi, 0.0) * sin_alpha * tan_beta);
            specular = s * power(nh, n);
            break;
        }
        case Model::Minnaert: {
            const double k = m.minnaert_k;
            diffuse = a * power(nl, k) * std::pow(std::max(nv, kMinCosView), k - 1.0);
            specular = s * power(nh, n);
            break;
        }
        case Model::CookTorrance: {
            const double alpha = std::max(double(m.roughness) * m.roughness, kMinAlpha), a2 = alpha * alpha;
            const double nvc = std::max(nv, kMinCosView);
            double D;
            if (scene.lighting.distribution == lab::LightingDesc::Distribution::GGX) {
                const double k = nh * nh * (a2 - 1.0) + 1.0;
                D = a2 / (kPi * k * k);
            } else {
                const double c = std::max(nh, kMinCosHalf), c2 = c * c;
                D = std::exp((c2 - 1.0) / (a2 * c2)) / (kPi * a2 * c2 * c2);
            }
            auto g1 = [&](double x) {
                if (scene.lighting.distribution == lab::LightingDesc::Distribution::GGX)
                    return 2.0 * x / (x + std::sqrt(a2 + (1.0 - a2) * x * x));
                const double c = x / (alpha * std::max(std::sqrt(std::max(1.0 - x * x, 0.0)), 1e-7));
                return c < 1.6 ? (3.535 * c + 2.181 * c * c) / (1.0 + 2.276 * c + 2.577 * c * c) : 1.0;
            };
            const glm::dvec3 f0(m.f0);
            const glm::dvec3 F = f0 + (1.0 - f0) * std::pow(1.0 - std::clamp(glm::dot(V, H), 0.0, 1.0), 5.0);
            specular = kPi * D * g1(nl) * g1(nvc) * F / (4.0 * nvc);
            break;
        }
        case Model::Ward: {
            const glm::dvec3 B = glm::cross(N, f.T);
            const double ax = m.roughness_x, ay = m.roughness_y;
            const double hn = std::max(nh, kMinCosHalf);
            const double ht = glm::dot(H, f.T) / ax, hb = glm::dot(H, B) / ay;
            const double e = std::exp(-(ht * ht + hb * hb) / (hn * hn));
            specular = s * nl * e / (4.0 * ax * ay * std::sqrt(nl * std::max(nv, kMinCosView)));
            break;
        }
    }
    if (bad && !(finite(diffuse) && finite(specular) && finite(H))) *bad = true;
    return diffuse + specular;
}

}  // namespace

double attenuation(const glm::dvec3& k, double d) {
    if (k.x + k.y + k.z <= 0.0) return 1.0;
    return 1.0 / std::max(k.x + k.y * d + k.z * d * d, kMinDenominator);
}

double packed_spot_factor(const glm::dvec2& cone, double cos_theta) {
    // (cos outer, 1 / width): a linear ramp from the outer edge, clamped; no width: a hard edge.
    return cone.y > 0.0 ? std::clamp((cos_theta - cone.x) * cone.y, 0.0, 1.0) : (cos_theta >= cone.x ? 1.0 : 0.0);
}

double spot_factor(double inner_deg, double outer_deg, lab::LightingDesc::SpotFalloff falloff, double cos_theta) {
    const double cos_outer = cos_deg(outer_deg);
    const double cos_start = falloff == lab::LightingDesc::SpotFalloff::Edge ? 1.0 : cos_deg(inner_deg);
    const double width = cos_start - cos_outer;
    if (!(width >= kMinConeWidth)) return cos_theta >= cos_outer ? 1.0 : 0.0;
    return std::clamp((cos_theta - cos_outer) / width, 0.0, 1.0);
}

glm::dmat3 normal_matrix(const glm::dmat4& model) {
    return glm::transpose(glm::inverse(glm::dmat3(model)));
}

glm::dvec3 shade_point(const lab::Scene& scene, const lab::MaterialDesc& m, const glm::dvec3& P,
                       const glm::dvec3& N, const glm::dvec3& V, const glm::dvec3& tangent, bool* bad,
                       const LightVisibility* visibility) {
    Frame f{N, V, glm::dvec3(0.0)};
    if (scene.lighting.model == Model::Ward) {
        const glm::dvec3 any = glm::normalize(
            glm::cross(std::abs(N.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), N));
        f.T = unit_or(tangent - N * glm::dot(N, tangent), any);
    }
    glm::dvec3 color = glm::dvec3(m.emissive) +
                       glm::dvec3(scene.ambient.color) * double(scene.ambient.intensity) * glm::dvec3(m.albedo);
    int used[3] = {0, 0, 0};
    const int limit[3] = {8, 32, 32};
    for (const lab::LightDesc& light : scene.lights) {
        if (used[int(light.type)]++ >= limit[int(light.type)]) continue;  // the lab drops extra lights too
        const glm::dvec3 radiance = glm::dvec3(light.color) * double(light.intensity);
        const glm::dvec3 axis = unit_or(glm::dvec3(light.direction), glm::dvec3(0, -1, 0));
        // Lab 4: a shadow-casting light is scaled by the fraction that reaches the point (traced
        // only where it would add something).
        const auto shadowed = [&](const glm::dvec3& r, double factor = 1.0) {
            if (!visibility || !light.cast_shadows || r == glm::dvec3(0.0) || factor == 0.0) return r;
            return r * (*visibility)(light);
        };
        if (light.type == Type::Directional) {
            color += radiance * shadowed(reflectance(scene, m, f, -axis, bad));
            continue;
        }
        const glm::dvec3 to_light = glm::dvec3(light.position) - P;
        const double d = glm::length(to_light);
        const glm::dvec3 L = unit_or(to_light, N);  // the light on the surface: L = N
        double factor = attenuation(glm::dvec3(light.attenuation), d);
        if (light.type == Type::Spot)
            factor *= spot_factor(light.inner_deg, light.outer_deg, scene.lighting.spot_falloff, glm::dot(-L, axis));
        color += radiance * factor * shadowed(reflectance(scene, m, f, L, bad), factor);
    }
    if (bad && !finite(color)) *bad = true;
    return color;
}

namespace {

// What the shader needs beyond the Hit: per object its mesh, model matrix and the
// normal matrix scaled like the lab's (largest element ±1), and the eye.
struct SceneData {
    std::vector<lab::Mesh> meshes;
    std::vector<glm::dmat4> models;
    std::vector<glm::dmat3> normals;
    glm::dvec3 eye{0.0};
};

std::shared_ptr<const SceneData> scene_data(const lab::Scene& scene) {
    auto data = std::make_shared<SceneData>();
    lab::MeshLibrary library;  // each model file read once
    for (const lab::ObjectDesc& object : scene.objects) {
        data->meshes.push_back(library.mesh(object));
        const glm::dmat4 m = ref::model_matrix(object);
        glm::dmat3 n = normal_matrix(m);
        double largest = 0.0;
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) largest = std::max(largest, std::abs(n[c][r]));
        if (largest > 0.0) n /= largest;
        data->models.push_back(m);
        data->normals.push_back(n);
    }
    data->eye = make_camera(scene.camera).eye;
    return data;
}

const lab::MaterialDesc& material_of(const lab::Scene& scene, const Hit& hit) {
    const auto it = scene.materials.find(hit.material);
    if (it == scene.materials.end()) throw std::runtime_error("cpu_lighting: unknown material '" + hit.material + "'");
    return it->second;
}

// The hit's triangle: its three mesh vertices, world positions and barycentric weights of hit.position.
struct Corners {
    const lab::Vertex* v[3];
    glm::dvec3 world[3];
    double w[3];
};

Corners corners_of(const SceneData& data, const Hit& hit) {
    const lab::Mesh& mesh = data.meshes.at(size_t(hit.object_id));
    const glm::dmat4& M = data.models[size_t(hit.object_id)];
    Corners c{};
    for (int k = 0; k < 3; ++k) {
        c.v[k] = &mesh.vertices.at(mesh.indices.at(size_t(hit.triangle_id) * 3 + size_t(k)));
        c.world[k] = glm::dvec3(M * glm::dvec4(glm::dvec3(c.v[k]->position), 1.0));
    }
    const glm::dvec3 e1 = c.world[1] - c.world[0], e2 = c.world[2] - c.world[0], p = hit.position - c.world[0];
    const double d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
    const double d20 = glm::dot(p, e1), d21 = glm::dot(p, e2);
    const double det = d00 * d11 - d01 * d01;
    c.w[1] = det != 0.0 ? (d11 * d20 - d01 * d21) / det : 1.0 / 3.0;
    c.w[2] = det != 0.0 ? (d00 * d21 - d01 * d20) / det : 1.0 / 3.0;
    c.w[0] = 1.0 - c.w[1] - c.w[2];
    return c;
}

// The per-pixel unit normal (flat: the face; Phong: the interpolated one, the face if it is zero).
glm::dvec3 pixel_normal(const SceneData& data, const Hit& hit, const Corners& c, Shading shading) {
    const glm::dvec3 face = hit.geometric_normal;
    if (shading == Shading::Flat) return face;
    glm::dvec3 n(0.0);
    for (int k = 0; k < 3; ++k) n += c.w[k] * glm::dvec3(c.v[k]->normal);
    return unit_or(data.normals[size_t(hit.object_id)] * n, face);
}

glm::dvec3 world_tangent(const SceneData& data, const Hit& hit, const Corners& c) {
    glm::dvec3 t(0.0);
    for (int k = 0; k < 3; ++k) t += c.w[k] * glm::dvec3(c.v[k]->tangent);
    return glm::dmat3(data.models[size_t(hit.object_id)]) * t;
}

}  // namespace

ShadeFn make_lighting_shader(const lab::Scene& scene, Shading shading) {
    const std::shared_ptr<const SceneData> data = scene_data(scene);
    return [data, shading](const lab::Scene& s, const Hit& hit) -> glm::dvec3 {
        if (!hit.hit) return glm::dvec3(s.background);
        const lab::MaterialDesc& m = material_of(s, hit);
        const Corners c = corners_of(*data, hit);
        if (shading == Shading::Gouraud) {
            // The equation at each corner (its own position, normal and view direction), then
            // interpolated like any vertex output.
            const glm::dmat4& M = data->models[size_t(hit.object_id)];
            glm::dvec3 color(0.0);
            for (int k = 0; k < 3; ++k) {
                const glm::dvec3 to_eye = data->eye - c.world[k];
                const glm::dvec3 v0 = unit_or(to_eye, glm::dvec3(0, 0, 1));
                const glm::dvec3 N = unit_or(data->normals[size_t(hit.object_id)] * glm::dvec3(c.v[k]->normal), v0);
                const glm::dvec3 V = unit_or(to_eye, N);
                const glm::dvec3 T = glm::dmat3(M) * glm::dvec3(c.v[k]->tangent);
                color += c.w[k] * shade_point(s, m, c.world[k], N, V, T);
            }
            return color;
        }
        const glm::dvec3 N = pixel_normal(*data, hit, c, shading);
        const glm::dvec3 V = unit_or(data->eye - hit.position, N);
        return shade_point(s, m, hit.position, N, V, world_tangent(*data, hit, c));
    };
}

ShadeFn make_lighting_shader(const lab::Scene& scene) { return make_lighting_shader(scene, scene.lighting.shading); }

int discontinuity_key(const lab::Scene& scene, const Hit& hit) {
    if (!hit.hit) return 0;
    const lab::MaterialDesc& m = material_of(scene, hit);
    const glm::dvec3 eye = make_camera(scene.camera).eye;
    // Per-pixel normal as the flat / Phong shader sees it (vertex normals via hit.normal).
    const glm::dvec3 N = scene.lighting.shading == Shading::Flat || glm::dot(hit.normal, hit.normal) == 0.0
                             ? hit.geometric_normal
                             : hit.normal;
    const glm::dvec3 V = unit_or(eye - hit.position, N);
    const bool toon = scene.lighting.model == Model::Toon;
    const bool specular = glm::length(glm::dvec3(m.specular)) > 0.0 && scene.lighting.model != Model::Lambert &&
                          scene.lighting.model != Model::CookTorrance;  // Cook-Torrance: G→0 at N·L = 0
    unsigned key = 1;
    auto mix = [&key](unsigned v) { key = key * 2654435761u + v + 1u; };
    for (const lab::LightDesc& light : scene.lights) {
        glm::dvec3 L;
        const glm::dvec3 axis = unit_or(glm::dvec3(light.direction), glm::dvec3(0, -1, 0));
        if (light.type == Type::Directional) {
            L = -axis;
        } else {
            L = unit_or(glm::dvec3(light.position) - hit.position, N);
            if (light.type == Type::Spot) {
                const double cos_outer = cos_deg(light.outer_deg);
                const double cos_start =
                    scene.lighting.spot_falloff == lab::LightingDesc::SpotFalloff::Edge ? 1.0 : cos_deg(light.inner_deg);
                if (!(cos_start - cos_outer >= kMinConeWidth)) mix(glm::dot(-L, axis) >= cos_outer);  // hard edge
            }
        }
        const double nl = glm::dot(N, L);
        if (specular || toon) mix(nl > 0.0);
        if (toon && nl > 0.0) {
            mix(unsigned(std::ceil(nl * scene.lighting.toon_bands)));
            mix(power(std::max(glm::dot(N, unit_or(L + V, N)), 0.0), m.shininess) > 0.5);
        }
    }
    return int(key & 0x7fffffff);
}

}  // namespace ref
