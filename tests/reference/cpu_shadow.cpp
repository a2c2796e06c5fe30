// cpu_shadow.cpp — see cpu_shadow.h. Double precision throughout.
#include "reference/cpu_shadow.h"

#include "reference/cpu_lighting.h"
#include "reference/cpu_texture.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>

namespace ref {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kMaxLayers = 64;  // translucent layers blended per pixel (more would be absurd)

glm::dvec3 unit_or(const glm::dvec3& v, const glm::dvec3& fallback) {
    const double len2 = glm::dot(v, v);
    return len2 > 1e-20 ? v / std::sqrt(len2) : fallback;
}

}  // namespace

void toward_light(const lab::LightDesc& light, const glm::dvec3& P, glm::dvec3* L, double* distance) {
    if (light.type == lab::LightDesc::Type::Directional) {
        *L = -unit_or(glm::dvec3(light.direction), glm::dvec3(0, -1, 0));
        *distance = kInfinity;
        return;
    }
    const glm::dvec3 to_light = glm::dvec3(light.position) - P;
    *distance = glm::length(to_light);
    *L = unit_or(to_light, glm::dvec3(0, 1, 0));
}

double ShadowCasters::offset(const glm::dvec3& P) {
    return 1e-6 * (1.0 + std::max({std::abs(P.x), std::abs(P.y), std::abs(P.z)}));
}

ShadowCasters::ShadowCasters(const lab::Scene& scene) : geometry_(std::make_shared<SceneGeometry>(scene)) {
    for (const lab::ObjectDesc& object : scene.objects) {
        const auto it = scene.materials.find(object.material);
        const double opacity = it == scene.materials.end() ? 1.0 : std::clamp(double(it->second.opacity), 0.0, 1.0);
        opacity_.push_back(object.cast_shadows ? opacity : -1.0);
    }
}

double ShadowCasters::transmittance(const lab::LightDesc& light, const glm::dvec3& P, const glm::dvec3& normal) const {
    glm::dvec3 L;
    double distance;
    toward_light(light, P, &L, &distance);
    if (distance == 0.0) return 1.0;  // the light sits on the point: nothing lies between
    // Start on the light's side of the surface, ε away (the self-intersection rule).
    const glm::dvec3 n = unit_or(normal, L);
    const double eps = offset(P);
    Ray ray;
    ray.origin = P + (glm::dot(n, L) >= 0.0 ? n : -n) * eps;
    ray.dir = L;
    // The segment ends at the light (the start moved by ε, so it is at most ε longer).
    const double t_max = std::isinf(distance) ? 1e300 : distance;

    // Light-facing crossings of translucent objects, per object (deduplicated below).
    std::map<int, std::vector<double>> crossings;
    const bool open = geometry_->for_each_hit(ray, 0.0, t_max, [&](const CrossedTriangle& c) {
        const double opacity = opacity_[size_t(c.object_id)];
        if (opacity < 0.0) return true;     // cast_shadows = false: invisible to shadow rays
        if (opacity >= 1.0) return false;   // opaque, either side: blocked, stop
        // Seen from the light, a face is in front when the ray (going toward the light) meets
        // its back side.
        if (!c.front) crossings[c.object_id].push_back(c.t);
        return true;
    });
    if (!open) return 0.0;
    double through = 1.0;
    for (auto& [object, ts] : crossings) {
        std::sort(ts.begin(), ts.end());
        const double factor = 1.0 - opacity_[size_t(object)];
        double last = -kInfinity;
        for (double t : ts) {
            // A ray through an edge or vertex shared by several faces crosses the surface once.
            if (t - last > 1e-9 * (1.0 + t)) through *= factor;
            last = t;
        }
    }
    return through;
}

namespace {

// A copy of `scene` with the shadow-casting lights changed by `edit`.
lab::Scene with_lights(const lab::Scene& scene, void (*edit)(lab::LightDesc&)) {
    lab::Scene copy = scene;
    for (lab::LightDesc& light : copy.lights)
        if (light.cast_shadows) edit(light);
    return copy;
}

}  // namespace

RefImage render_shadowed(const lab::Scene& scene, int width, int height, bool shadows, int margin) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("render_shadowed: empty image");
    if (margin < 0) throw std::invalid_argument("render_shadowed: negative margin");
    const SceneGeometry geometry(scene);
    std::shared_ptr<const ShadowCasters> casters = shadows ? std::make_shared<ShadowCasters>(scene) : nullptr;
    const ShadeFn shade = make_texture_shader(scene, width, height, false, {}, casters);
    const Camera camera = make_camera(scene.camera);
    std::vector<double> opacity;
    for (const lab::ObjectDesc& object : scene.objects) {
        const auto it = scene.materials.find(object.material);
        opacity.push_back(it == scene.materials.end() ? 1.0 : std::clamp(double(it->second.opacity), 0.0, 1.0));
    }

    // The picture is `margin` pixels larger on every side: the same camera and the same pixel grid
    // (rays through the width × height grid's centres, extended past its edges), so its centre crop
    // is the plain picture bit for bit.
    RefImage image;
    image.width = width + 2 * margin;
    image.height = height + 2 * margin;
    const size_t n = size_t(image.width) * size_t(image.height);
    image.linear.assign(n, glm::dvec3(0.0));
    image.object_id.assign(n, -1);
    image.triangle_id.assign(n, -1);
    image.hits.assign(n, Hit{});
    image.translucent_objects.assign(n, 0);

    const auto pixel = [&](int x, int y) {
        const size_t i = size_t(y) * size_t(image.width) + size_t(x);
        const Ray ray = primary_ray(camera, width, height, (x - margin) + 0.5, (y - margin) + 0.5);
        // Everything the ray crosses between the clip planes, near to far.
        std::vector<CrossedTriangle> crossed;
        geometry.for_each_hit(ray, camera.near_plane, camera.far_plane, [&](const CrossedTriangle& c) {
            crossed.push_back(c);
            return true;
        });
        std::sort(crossed.begin(), crossed.end(), [](const CrossedTriangle& a, const CrossedTriangle& b) {
            return a.t != b.t ? a.t < b.t : std::make_pair(a.object_id, a.triangle_id) < std::make_pair(b.object_id, b.triangle_id);
        });
        const auto same_place = [](double a, double b) { return std::abs(a - b) <= 1e-9 * (1.0 + std::abs(a)); };
        const auto opaque_front = [&](const CrossedTriangle& c) { return opacity[size_t(c.object_id)] >= 1.0 && c.front; };
        // Translucent layers (either side) until the first opaque front face; opaque back faces are
        // culled as the rasteriser culls them. At the same distance an opaque surface wins (a LESS
        // depth test rejects the translucent one drawn after it), and a surface crossed at a shared
        // edge counts once.
        std::vector<Hit> layers;
        Hit base;
        const CrossedTriangle* last_layer = nullptr;
        for (size_t k = 0; k < crossed.size() && !base.hit; ++k) {
            const CrossedTriangle& c = crossed[k];
            if (opacity[size_t(c.object_id)] >= 1.0) {
                if (c.front) base = geometry.hit_of(c);
                continue;
            }
            for (size_t j = k + 1; j < crossed.size() && same_place(crossed[j].t, c.t) && !base.hit; ++j)
                if (opaque_front(crossed[j])) base = geometry.hit_of(crossed[j]);
            if (base.hit) break;
            if (last_layer && last_layer->object_id == c.object_id && last_layer->front == c.front &&
                same_place(last_layer->t, c.t))
                continue;
            last_layer = &c;
            Hit hit = geometry.hit_of(c);
            if (hit.back_face) {  // seen from inside: shaded with the normal towards the eye
                hit.normal = -hit.normal;
                hit.geometric_normal = -hit.geometric_normal;
            }
            if (int(layers.size()) < kMaxLayers) layers.push_back(hit);
        }
        const auto complete = [&](Hit& h) {  // what render_with adds to a hit
            h.material = scene.objects[size_t(h.object_id)].material;
            h.view_dir = glm::normalize(camera.eye - h.position);
        };
        for (Hit& h : layers) complete(h);
        if (base.hit)
            complete(base);
        else
            base.view_dir = -glm::normalize(ray.dir);
        glm::dvec3 c = shade(scene, base);
        for (auto it = layers.rbegin(); it != layers.rend(); ++it) {  // back to front
            const double a = opacity[size_t(it->object_id)];
            c = a * shade(scene, *it) + (1.0 - a) * c;
        }
        image.linear[i] = c;
        image.hits[i] = base;
        // Ids for edge masks: the opaque surface, and every translucent layer in front of it.
        int id = base.hit ? base.object_id : -1, tri = base.hit ? base.triangle_id : -1;
        for (const Hit& h : layers) {
            id = (id + 2) * 1009 + h.object_id * 2 + (h.back_face ? 1 : 0);
            tri = (tri + 2) * 7919 + h.triangle_id;
        }
        image.object_id[i] = id & 0x3fffffff;
        std::vector<int> objects;
        for (const Hit& h : layers)
            if (std::find(objects.begin(), objects.end(), h.object_id) == objects.end()) objects.push_back(h.object_id);
        image.translucent_objects[i] = uint8_t(std::min<size_t>(objects.size(), 255));
        image.triangle_id[i] = tri & 0x3fffffff;
    };
    // Rows r ≡ t (mod T) on thread t: the result does not depend on the thread count.
    const unsigned hw = std::thread::hardware_concurrency();
    const int threads = int(std::min<unsigned>(std::max(hw, 1u), 8u));
    std::vector<std::exception_ptr> errors(static_cast<size_t>(threads));
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            try {
                for (int y = t; y < image.height; y += threads)
                    for (int x = 0; x < image.width; ++x) pixel(x, y);
            } catch (...) {
                errors[size_t(t)] = std::current_exception();
            }
        });
    for (std::thread& t : pool) t.join();
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
    return image;
}

ShadowReference render_shadow_reference(const lab::Scene& scene, int width, int height, int margin) {
    ShadowReference r;
    r.shadowed = render_shadowed(scene, width, height, true, margin);
    r.unshadowed = render_shadowed(scene, width, height, false, margin);
    r.unlit = render_shadowed(with_lights(scene, [](lab::LightDesc& l) { l.intensity = 0.0f; }), width, height, false, margin);
    return r;
}

RefImage crop_margin(const RefImage& image, int margin) {
    if (margin < 0 || 2 * margin >= image.width || 2 * margin >= image.height)
        throw std::invalid_argument("crop_margin: margin " + std::to_string(margin) + " does not fit a " +
                                    std::to_string(image.width) + "x" + std::to_string(image.height) + " picture");
    RefImage out;
    out.width = image.width - 2 * margin;
    out.height = image.height - 2 * margin;
    const auto crop = [&](const auto& in, auto& result) {
        if (in.empty()) return;
        for (int y = 0; y < out.height; ++y) {
            const auto row = in.begin() + std::ptrdiff_t(image.index(margin, y + margin));
            result.insert(result.end(), row, row + out.width);
        }
    };
    crop(image.linear, out.linear);
    crop(image.object_id, out.object_id);
    crop(image.triangle_id, out.triangle_id);
    crop(image.hits, out.hits);
    crop(image.translucent_objects, out.translucent_objects);
    return out;
}

ShadowMetric judge_shadows(const lab::Scene& scene, const lab::Image8& actual, ShadowMetricOptions options,
                           ShadowReference* reference) {
    options.margin = options.band;
    const ShadowReference wide = render_shadow_reference(scene, actual.width, actual.height, options.margin);
    ShadowMetric metric = shadow_metric(actual, encode_srgb(wide.shadowed), encode_srgb(wide.unshadowed),
                                        encode_srgb(wide.unlit), options);
    *reference = {crop_margin(wide.shadowed, options.margin), crop_margin(wide.unshadowed, options.margin),
                  crop_margin(wide.unlit, options.margin)};
    return metric;
}

}  // namespace ref
