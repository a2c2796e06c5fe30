// cpu_reference.cpp — the double-precision CPU ray caster (see cpu_reference.h).
#include "reference/cpu_reference.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <stdexcept>
#include <thread>
#include <utility>

namespace ref {

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------
// A small bounding-volume hierarchy over world-space triangles.
// ---------------------------------------------------------------------------

struct Box {
    glm::dvec3 lo{std::numeric_limits<double>::infinity()};
    glm::dvec3 hi{-std::numeric_limits<double>::infinity()};

    void grow(const glm::dvec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Box& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
};

struct Triangle {
    glm::dvec3 v0, v1, v2;  // world space, in the mesh's index order
    int object_id;
    int triangle_id;         // index within the object's mesh
    int vertex_index[3];     // into that object's mesh.vertices
};

struct Node {
    Box box;
    int first = 0;  // leaf: first triangle; inner: index of the left child (right = left + 1)
    int count = 0;  // leaf: number of triangles; 0 for inner nodes
};

// Slab test: the parameter interval in which the ray is inside the box,
// intersected with [t_min, t_max]. The box was padded when built, so rounding
// here can only let through extra candidates, never lose a triangle.
bool ray_box(const Ray& ray, const glm::dvec3& inv_dir, const Box& box, double t_min,
             double t_max) {
    for (int a = 0; a < 3; ++a) {
        if (ray.dir[a] == 0.0) {
            // Parallel to this slab: inside it or never.
            if (ray.origin[a] < box.lo[a] || ray.origin[a] > box.hi[a]) return false;
            continue;
        }
        double t0 = (box.lo[a] - ray.origin[a]) * inv_dir[a];
        double t1 = (box.hi[a] - ray.origin[a]) * inv_dir[a];
        if (t0 > t1) std::swap(t0, t1);
        t_min = std::max(t_min, t0);
        t_max = std::min(t_max, t1);
        if (t_min > t_max) return false;
    }
    return true;
}

// Walks the BVH: every leaf whose box the ray meets within [t_min, t_max] hands each of its
// triangle indices to leaf(i). `t_max` is read as the walk goes, so a nearest-hit search can
// shrink it; leaf returns false to stop the walk (then walk returns false).
template <class Leaf>
bool walk(const std::vector<Node>& nodes, const Ray& ray, double t_min, const double& t_max, Leaf&& leaf) {
    const glm::dvec3 inv_dir(1.0 / ray.dir.x, 1.0 / ray.dir.y, 1.0 / ray.dir.z);
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes[stack[--top]];
        if (!ray_box(ray, inv_dir, node.box, t_min, t_max)) continue;
        if (node.count == 0) {
            stack[top++] = node.first;
            stack[top++] = node.first + 1;
            continue;
        }
        for (int i = node.first; i < node.first + node.count; ++i)
            if (!leaf(i)) return false;
    }
    return true;
}

}  // namespace

// ---------------------------------------------------------------------------
// Angles and matrices
// ---------------------------------------------------------------------------

namespace {
// Angle reduced to [0, 360) and, if it is a multiple of 90°, which quadrant.
int exact_quadrant(double degrees, double* reduced) {
    double r = std::fmod(degrees, 360.0);
    if (r < 0.0) r += 360.0;
    *reduced = r;
    if (r == 0.0) return 0;
    if (r == 90.0) return 1;
    if (r == 180.0) return 2;
    if (r == 270.0) return 3;
    return -1;
}
}  // namespace

double sin_deg(double degrees) {
    double r = 0.0;
    switch (exact_quadrant(degrees, &r)) {
        case 0: return 0.0;
        case 1: return 1.0;
        case 2: return 0.0;
        case 3: return -1.0;
        default: return std::sin(r * kPi / 180.0);
    }
}

double cos_deg(double degrees) {
    double r = 0.0;
    switch (exact_quadrant(degrees, &r)) {
        case 0: return 1.0;
        case 1: return 0.0;
        case 2: return -1.0;
        case 3: return 0.0;
        default: return std::cos(r * kPi / 180.0);
    }
}

// glm matrices are column-major: m[column][row].
glm::dmat4 rotate_x(double degrees) {
    const double c = cos_deg(degrees), s = sin_deg(degrees);
    glm::dmat4 m(1.0);
    // y' = c·y − s·z,  z' = s·y + c·z
    m[1][1] = c;
    m[1][2] = s;
    m[2][1] = -s;
    m[2][2] = c;
    return m;
}

glm::dmat4 rotate_y(double degrees) {
    const double c = cos_deg(degrees), s = sin_deg(degrees);
    glm::dmat4 m(1.0);
    // x' = c·x + s·z,  z' = −s·x + c·z   (+Z turns towards +X)
    m[0][0] = c;
    m[0][2] = -s;
    m[2][0] = s;
    m[2][2] = c;
    return m;
}

glm::dmat4 rotate_z(double degrees) {
    const double c = cos_deg(degrees), s = sin_deg(degrees);
    glm::dmat4 m(1.0);
    // x' = c·x − s·y,  y' = s·x + c·y   (+X turns towards +Y)
    m[0][0] = c;
    m[0][1] = s;
    m[1][0] = -s;
    m[1][1] = c;
    return m;
}

glm::dmat4 translate(const glm::dvec3& t) {
    glm::dmat4 m(1.0);
    m[3] = glm::dvec4(t, 1.0);
    return m;
}

glm::dmat4 scale(const glm::dvec3& s) {
    glm::dmat4 m(1.0);
    m[0][0] = s.x;
    m[1][1] = s.y;
    m[2][2] = s.z;
    return m;
}

glm::dmat4 model_matrix(const lab::ObjectDesc& object) {
    const glm::dvec3 r(object.rotation_deg);
    return translate(glm::dvec3(object.position)) * rotate_z(r.z) * rotate_y(r.y) *
           rotate_x(r.x) * scale(glm::dvec3(object.scale));
}

// ---------------------------------------------------------------------------
// Camera
// ---------------------------------------------------------------------------

glm::dmat4 Camera::camera_to_world() const {
    glm::dmat4 c(1.0);
    c[0] = glm::dvec4(right, 0.0);
    c[1] = glm::dvec4(up, 0.0);
    c[2] = glm::dvec4(-forward, 0.0);  // camera +Z points backwards
    c[3] = glm::dvec4(eye, 1.0);
    return c;
}

glm::dmat4 Camera::view() const {
    // The inverse of a rigid transform [R | e] is [Rᵀ | −Rᵀ·e].
    const glm::dvec3 back = -forward;
    glm::dmat4 v(1.0);
    for (int col = 0; col < 3; ++col) {
        v[col][0] = right[col];
        v[col][1] = up[col];
        v[col][2] = back[col];
    }
    v[3] = glm::dvec4(-glm::dot(right, eye), -glm::dot(up, eye), -glm::dot(back, eye), 1.0);
    return v;
}

Camera make_camera(const lab::CameraDesc& desc) {
    Camera cam = desc.mode == lab::CameraDesc::Mode::Transform
                     ? transform_camera(glm::dvec3(desc.position), desc.yaw_deg, desc.pitch_deg, desc.roll_deg)
                     : look_at_camera(glm::dvec3(desc.position), glm::dvec3(desc.target), glm::dvec3(desc.up));
    cam.fov_y_deg = desc.fov_y_deg;
    cam.near_plane = desc.near_plane;
    cam.far_plane = desc.far_plane;
    return cam;
}

Camera transform_camera(const glm::dvec3& position, double yaw_deg, double pitch_deg, double roll_deg) {
    Camera cam;
    cam.eye = position;
    // C = T(position) · Ry(yaw) · Rx(pitch) · Rz(roll); the columns of the
    // rotation part are the camera's axes in world space.
    const glm::dmat4 r = rotate_y(yaw_deg) * rotate_x(pitch_deg) * rotate_z(roll_deg);
    cam.right = glm::dvec3(r[0]);
    cam.up = glm::dvec3(r[1]);
    cam.forward = -glm::dvec3(r[2]);
    return cam;
}

Camera look_at_camera(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up_in) {
    Camera cam;
    cam.eye = eye;
    // Look-at: f = normalize(target − eye), r = normalize(f × up), u = r × f.
    glm::dvec3 f = target - cam.eye;
    if (glm::length(f) == 0.0) {
        f = glm::dvec3(0.0, 0.0, -1.0);  // eye == target: look down −Z
    } else {
        f = glm::normalize(f);
    }
    glm::dvec3 up = up_in;
    if (glm::length(glm::cross(f, up)) < 1e-6 * glm::length(up)) {
        // Looking along `up` (e.g. straight down): replace up by ±Z (or ±X when f
        // itself is along Z), signed like f·up. Straight down with up = +Y gives
        // up' = −Z: the top of the image shows world −Z, right is +X.
        const double sign = glm::dot(f, up) < 0.0 ? -1.0 : 1.0;
        const bool f_along_z = glm::length(glm::cross(f, glm::dvec3(0.0, 0.0, 1.0))) < 1e-6;
        up = sign * (f_along_z ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 0.0, 1.0));
    }
    cam.forward = f;
    cam.right = glm::normalize(glm::cross(f, up));
    cam.up = glm::cross(cam.right, f);
    return cam;
}

glm::dmat4 projection(const Camera& camera, double aspect) {
    // Camera space (looking down −Z, +Y up) to Vulkan's clip space: x and y divided by the
    // image plane's half extent at depth 1 (primary_ray's), y negated (Vulkan's framebuffer y
    // points down), w = −z, and depth z/w = 0 at view depth near, 1 at far.
    const double f = 1.0 / std::tan(camera.fov_y_deg * kPi / 360.0);
    const double n = camera.near_plane, fa = camera.far_plane;
    glm::dmat4 p(0.0);
    p[0][0] = f / aspect;
    p[1][1] = -f;
    p[2][2] = fa / (n - fa);
    p[2][3] = -1.0;
    p[3][2] = n * fa / (n - fa);
    return p;
}

Ray primary_ray(const Camera& camera, int width, int height, double px, double py) {
    // Pixel position → normalised device coordinates in [−1, 1], with +y up
    // (row 0 is the top of the image).
    const double ndc_x = 2.0 * px / width - 1.0;
    const double ndc_y = 1.0 - 2.0 * py / height;
    // The image plane at depth 1 spans ±tan(fov/2) vertically, ±aspect·tan(fov/2) horizontally.
    const double tan_half = std::tan(camera.fov_y_deg * kPi / 360.0);
    const double aspect = static_cast<double>(width) / height;
    const double cx = ndc_x * tan_half * aspect;
    const double cy = ndc_y * tan_half;
    // Camera-space direction (cx, cy, −1) in world space: its component along the
    // forward axis is exactly 1, so the ray parameter t equals view depth.
    Ray ray;
    ray.origin = camera.eye;
    ray.dir = cx * camera.right + cy * camera.up + camera.forward;
    return ray;
}

// ---------------------------------------------------------------------------
// Watertight ray / triangle intersection
// ---------------------------------------------------------------------------

bool intersect_triangle(const Ray& ray, const glm::dvec3& v0, const glm::dvec3& v1,
                        const glm::dvec3& v2, double t_min, double t_max, TriangleHit* hit) {
    const glm::dvec3& d = ray.dir;
    // 1. Pick the dominant axis of the ray as "z" and the other two as x, y,
    //    swapping x and y when d.z < 0 so the winding of the projection is kept.
    int kz = 0;
    if (std::abs(d.y) > std::abs(d[kz])) kz = 1;
    if (std::abs(d.z) > std::abs(d[kz])) kz = 2;
    int kx = (kz + 1) % 3;
    int ky = (kx + 1) % 3;
    if (d[kz] < 0.0) std::swap(kx, ky);
    if (d[kz] == 0.0) return false;  // zero direction

    // 2. Shear so the ray becomes the +z axis through the origin. Every vertex
    //    is transformed by exactly the same operations whichever triangle it
    //    belongs to — this is what makes shared edges gap-free.
    const double sx = d[kx] / d[kz];
    const double sy = d[ky] / d[kz];
    const double sz = 1.0 / d[kz];
    const glm::dvec3 a = v0 - ray.origin;
    const glm::dvec3 b = v1 - ray.origin;
    const glm::dvec3 c = v2 - ray.origin;
    const double ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
    const double bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
    const double cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];

    // 3. 2-D edge functions: where the (now axis-aligned) ray pierces the
    //    projected triangle. U weighs v0, V weighs v1, W weighs v2.
    double u = cx * by - cy * bx;
    double v = ax * cy - ay * cx;
    double w = bx * ay - by * ax;
    if (u == 0.0 || v == 0.0 || w == 0.0) {
        // On (or rounding to) an edge: decide with extra precision.
        using ld = long double;
        u = static_cast<double>(ld(cx) * ld(by) - ld(cy) * ld(bx));
        v = static_cast<double>(ld(ax) * ld(cy) - ld(ay) * ld(cx));
        w = static_cast<double>(ld(bx) * ld(ay) - ld(by) * ld(ax));
    }
    // With the axis swap above, U + V + W = −dot(d, (v1 − v0) × (v2 − v0)) / |d[kz]|:
    // all three are ≥ 0 exactly when the ray crosses the triangle's *front* side
    // (counter-clockwise as seen). Back faces give all ≤ 0 and are culled here.
    if (u < 0.0 || v < 0.0 || w < 0.0) return false;
    const double det = u + v + w;
    if (det <= 0.0) return false;  // edge-on or degenerate

    // 4. Interpolate the sheared z of the vertices to get the ray parameter.
    const double az = sz * a[kz], bz = sz * b[kz], cz = sz * c[kz];
    const double t = (u * az + v * bz + w * cz) / det;
    if (!(t >= t_min && t <= t_max)) return false;
    if (hit) {
        hit->t = t;
        hit->b1 = v / det;
        hit->b2 = w / det;
    }
    return true;
}

// ---------------------------------------------------------------------------
// SceneGeometry
// ---------------------------------------------------------------------------

struct SceneGeometry::Impl {
    std::vector<Triangle> triangles;
    std::vector<Node> nodes;
    // Per object: its mesh (for normals / uvs) and the normal matrix.
    std::vector<lab::Mesh> meshes;
    std::vector<glm::dmat3> normal_matrices;

    void build(int node, int first, int count, int depth);
    void fill_hit(const Triangle& tri, const TriangleHit& h, bool front, Hit* out) const;
};

void SceneGeometry::Impl::build(int node, int first, int count, int depth) {
    Box box, centroids;
    for (int i = first; i < first + count; ++i) {
        const Triangle& t = triangles[i];
        box.grow(t.v0);
        box.grow(t.v1);
        box.grow(t.v2);
        centroids.grow((t.v0 + t.v1 + t.v2) / 3.0);
    }
    // Pad the box a little so rounding in the slab test can never reject a ray
    // that actually hits a triangle (flat boxes — a plane — have zero thickness).
    const glm::dvec3 pad = 1e-9 * (box.hi - box.lo + glm::abs(box.lo) + glm::abs(box.hi)) +
                           glm::dvec3(1e-300);
    box.lo -= pad;
    box.hi += pad;
    nodes[node].box = box;

    if (count <= 4 || depth > 60) {
        nodes[node].first = first;
        nodes[node].count = count;
        return;
    }
    // Split at the median centroid along the longest axis of the centroid bounds.
    const glm::dvec3 extent = centroids.hi - centroids.lo;
    int axis = 0;
    if (extent.y > extent[axis]) axis = 1;
    if (extent.z > extent[axis]) axis = 2;
    const int mid = first + count / 2;
    std::nth_element(triangles.begin() + first, triangles.begin() + mid,
                     triangles.begin() + first + count,
                     [axis](const Triangle& p, const Triangle& q) {
                         return (p.v0[axis] + p.v1[axis] + p.v2[axis]) <
                                (q.v0[axis] + q.v1[axis] + q.v2[axis]);
                     });
    const int left = static_cast<int>(nodes.size());
    nodes.emplace_back();
    nodes.emplace_back();
    nodes[node].first = left;
    nodes[node].count = 0;
    build(left, first, mid - first, depth + 1);
    build(left + 1, mid, first + count - mid, depth + 1);
}

SceneGeometry::SceneGeometry(const lab::Scene& scene) : impl_(new Impl) {
    lab::MeshLibrary library;  // each model file read once
    for (size_t o = 0; o < scene.objects.size(); ++o) {
        const lab::ObjectDesc& object = scene.objects[o];
        lab::Mesh mesh = library.mesh(object);
        const glm::dmat4 m = ref::model_matrix(object);
        // Normals transform with the inverse transpose of the model matrix's 3×3 part.
        impl_->normal_matrices.push_back(glm::transpose(glm::inverse(glm::dmat3(m))));

        // Each vertex is transformed exactly once, so triangles sharing a vertex
        // see bit-identical coordinates (needed for watertightness).
        std::vector<glm::dvec3> world(mesh.vertices.size());
        for (size_t i = 0; i < mesh.vertices.size(); ++i)
            world[i] = glm::dvec3(m * glm::dvec4(glm::dvec3(mesh.vertices[i].position), 1.0));
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            Triangle tri;
            tri.vertex_index[0] = static_cast<int>(mesh.indices[t]);
            tri.vertex_index[1] = static_cast<int>(mesh.indices[t + 1]);
            tri.vertex_index[2] = static_cast<int>(mesh.indices[t + 2]);
            for (int k = 0; k < 3; ++k)
                if (tri.vertex_index[k] < 0 ||
                    static_cast<size_t>(tri.vertex_index[k]) >= world.size())
                    throw std::runtime_error("cpu_reference: mesh index out of range");
            tri.v0 = world[tri.vertex_index[0]];
            tri.v1 = world[tri.vertex_index[1]];
            tri.v2 = world[tri.vertex_index[2]];
            tri.object_id = static_cast<int>(o);
            tri.triangle_id = static_cast<int>(t / 3);
            impl_->triangles.push_back(tri);
        }
        impl_->meshes.push_back(std::move(mesh));
    }
    impl_->nodes.reserve(2 * impl_->triangles.size() + 1);
    impl_->nodes.emplace_back();
    impl_->build(0, 0, static_cast<int>(impl_->triangles.size()), 0);
}

SceneGeometry::~SceneGeometry() { delete impl_; }

void SceneGeometry::Impl::fill_hit(const Triangle& tri, const TriangleHit& h, bool front, Hit* out) const {
    const double b0 = 1.0 - h.b1 - h.b2;
    const lab::Mesh& mesh = meshes[tri.object_id];
    const lab::Vertex& p0 = mesh.vertices[tri.vertex_index[0]];
    const lab::Vertex& p1 = mesh.vertices[tri.vertex_index[1]];
    const lab::Vertex& p2 = mesh.vertices[tri.vertex_index[2]];

    out->hit = true;
    out->back_face = !front;
    out->object_id = tri.object_id;
    out->triangle_id = tri.triangle_id;
    out->depth = h.t;
    out->position = b0 * tri.v0 + h.b1 * tri.v1 + h.b2 * tri.v2;
    const glm::dvec3 n_model = b0 * glm::dvec3(p0.normal) + h.b1 * glm::dvec3(p1.normal) + h.b2 * glm::dvec3(p2.normal);
    const glm::dvec3 n_world = normal_matrices[tri.object_id] * n_model;
    out->normal = glm::length(n_world) > 0.0 ? glm::normalize(n_world) : glm::dvec3(0.0);
    out->geometric_normal = glm::normalize(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
    out->uv = b0 * glm::dvec2(p0.uv) + h.b1 * glm::dvec2(p1.uv) + h.b2 * glm::dvec2(p2.uv);
}

Hit SceneGeometry::hit_of(const CrossedTriangle& c) const {
    Hit hit;
    TriangleHit h;
    h.t = c.t;
    h.b1 = c.b1;
    h.b2 = c.b2;
    impl_->fill_hit(impl_->triangles.at(size_t(c.index)), h, c.front, &hit);
    return hit;
}

size_t SceneGeometry::triangle_count() const { return impl_->triangles.size(); }

namespace {
// intersect_triangle() on the side(s) `facing` allows; *front tells which side was hit. The back
// side is the front side of the reversed triangle (v0, v2, v1), so b1 and b2 swap back.
bool intersect_facing(const Ray& ray, const glm::dvec3& v0, const glm::dvec3& v1, const glm::dvec3& v2, double t_min,
                      double t_max, Facing facing, TriangleHit* hit, bool* front) {
    if (facing != Facing::Back && intersect_triangle(ray, v0, v1, v2, t_min, t_max, hit)) {
        *front = true;
        return true;
    }
    if (facing != Facing::Front && intersect_triangle(ray, v0, v2, v1, t_min, t_max, hit)) {
        std::swap(hit->b1, hit->b2);
        *front = false;
        return true;
    }
    return false;
}
}  // namespace

bool SceneGeometry::for_each_hit(const Ray& ray, double t_min, double t_max,
                                 const std::function<bool(const CrossedTriangle&)>& visit) const {
    const Impl& g = *impl_;
    if (g.triangles.empty()) return true;
    return walk(g.nodes, ray, t_min, t_max, [&](int i) {
        const Triangle& tri = g.triangles[i];
        TriangleHit h;
        bool front = true;
        if (!intersect_facing(ray, tri.v0, tri.v1, tri.v2, t_min, t_max, Facing::Both, &h, &front)) return true;
        return visit(CrossedTriangle{h.t, tri.object_id, tri.triangle_id, front, h.b1, h.b2, i});
    });
}

bool SceneGeometry::trace(const Ray& ray, double t_min, double t_max, Hit* out, Facing facing) const {
    const Impl& g = *impl_;
    if (g.triangles.empty()) return false;

    const Triangle* best = nullptr;
    TriangleHit best_hit;
    bool best_front = true;
    double best_t = t_max;  // shrinks as nearer hits are found: the walk skips boxes beyond it
    walk(g.nodes, ray, t_min, best_t, [&](int i) {
        const Triangle& tri = g.triangles[i];
        TriangleHit h;
        bool front = true;
        if (!intersect_facing(ray, tri.v0, tri.v1, tri.v2, t_min, best_t, facing, &h, &front)) return true;
        // Ties (a ray exactly through a shared edge, or coplanar overlap) go
        // to the lower (object, triangle) so the result never depends on BVH order.
        if (best && h.t == best_t &&
            std::make_pair(tri.object_id, tri.triangle_id) > std::make_pair(best->object_id, best->triangle_id))
            return true;
        best = &tri;
        best_hit = h;
        best_front = front;
        best_t = h.t;
        return true;
    });
    if (!best) return false;

    if (out) g.fill_hit(*best, best_hit, best_front, out);
    return true;
}

// ---------------------------------------------------------------------------
// Rendering
// ---------------------------------------------------------------------------

glm::dvec3 shade_unlit(const lab::Scene& scene, const Hit& hit) {
    if (!hit.hit) return glm::dvec3(scene.background);
    const auto it = scene.materials.find(hit.material);
    if (it == scene.materials.end())
        throw std::runtime_error("cpu_reference: unknown material '" + hit.material + "'");
    return glm::dvec3(it->second.albedo);
}

RefImage render_reference(const lab::Scene& scene, int width, int height, const ShadeFn& shade) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("render_reference: empty image");
    const SceneGeometry geometry(scene);
    const TraceFn trace = [&geometry](const Ray& ray, double t_min, double t_max, Hit* hit) {
        return geometry.trace(ray, t_min, t_max, hit);
    };
    return render_with(scene, width, height, shade, trace, 1);
}

namespace {
// A fixed pseudo-random number in [0, 1) for (pixel, cell, axis): the jitter of a
// stratified sample. Deterministic, so a reference render is reproducible.
double jitter(uint64_t key) {
    key += 0x9E3779B97F4A7C15ull;  // splitmix64
    key = (key ^ (key >> 30)) * 0xBF58476D1CE4E5B9ull;
    key = (key ^ (key >> 27)) * 0x94D049BB133111EBull;
    key ^= key >> 31;
    return double(key >> 11) * (1.0 / 9007199254740992.0);  // 53 bits
}
}  // namespace

RefImage render_with(const lab::Scene& scene, int width, int height, const ShadeFn& shade, const TraceFn& trace,
                     int supersample) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("render_reference: empty image");
    if (supersample < 1) throw std::invalid_argument("render_reference: supersample must be >= 1");
    const Camera camera = make_camera(scene.camera);

    RefImage image;
    image.width = width;
    image.height = height;
    const size_t n = static_cast<size_t>(width) * height;
    image.linear.assign(n, glm::dvec3(0.0));
    image.object_id.assign(n, -1);
    image.triangle_id.assign(n, -1);
    image.hits.assign(n, Hit{});

    const int ss = supersample, middle = supersample / 2;
    // One sample at (px, py): its hit (with material and view direction) and colour.
    auto sample = [&](double px, double py, Hit* hit) {
        const Ray ray = primary_ray(camera, width, height, px, py);
        if (trace(ray, camera.near_plane, camera.far_plane, hit)) {
            hit->material = scene.objects[hit->object_id].material;
            hit->view_dir = glm::normalize(camera.eye - hit->position);
        } else {
            *hit = Hit{};
            hit->view_dir = -glm::normalize(ray.dir);
        }
        return shade(scene, *hit);
    };
    // Rows are independent: trace and shade them on a few threads (row r goes
    // to thread r mod T, so the result does not depend on the thread count).
    // `shade` is therefore called concurrently and must not modify shared state.
    auto render_rows = [&](int first_row, int step) {
        for (int y = first_row; y < height; y += step) {
            for (int x = 0; x < width; ++x) {
                const size_t i = static_cast<size_t>(y) * width + x;
                Hit& hit = image.hits[i];
                if (ss == 1) {
                    image.linear[i] = sample(x + 0.5, y + 0.5, &hit);
                } else {
                    glm::dvec3 sum(0.0);
                    for (int cy = 0; cy < ss; ++cy) {
                        for (int cx = 0; cx < ss; ++cx) {
                            const uint64_t key = ((uint64_t(i) * ss + cy) * ss + cx) * 2;
                            const double px = x + (cx + jitter(key)) / ss, py = y + (cy + jitter(key + 1)) / ss;
                            Hit h;
                            sum += sample(px, py, &h);
                            if (cx == middle && cy == middle) hit = h;
                        }
                    }
                    image.linear[i] = sum / double(ss * ss);
                }
                if (hit.hit) {
                    image.object_id[i] = hit.object_id;
                    image.triangle_id[i] = hit.triangle_id;
                }
            }
        }
    };
    const unsigned hw = std::thread::hardware_concurrency();
    const int threads = static_cast<int>(std::min<unsigned>(std::max(hw, 1u), 8u));
    if (threads <= 1 || n < 4096) {
        render_rows(0, 1);
    } else {
        // An exception in a worker (e.g. from `shade`) is passed on to the caller.
        std::vector<std::exception_ptr> errors(threads);
        std::vector<std::thread> pool;
        for (int t = 0; t < threads; ++t)
            pool.emplace_back([&, t] {
                try {
                    render_rows(t, threads);
                } catch (...) {
                    errors[t] = std::current_exception();
                }
            });
        for (std::thread& t : pool) t.join();
        for (const std::exception_ptr& e : errors)
            if (e) std::rethrow_exception(e);
    }
    return image;
}

// ---------------------------------------------------------------------------
// sRGB
// ---------------------------------------------------------------------------

double srgb_encode(double c) {
    if (c <= 0.0031308) return 12.92 * c;
    return 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double e) {
    if (e <= 0.04045) return e / 12.92;
    return std::pow((e + 0.055) / 1.055, 2.4);
}

lab::Image8 encode_srgb(const RefImage& image) {
    lab::Image8 out;
    out.width = image.width;
    out.height = image.height;
    out.rgba.resize(static_cast<size_t>(image.width) * image.height * 4);
    for (size_t i = 0; i < image.linear.size(); ++i) {
        for (int ch = 0; ch < 3; ++ch) {
            double c = image.linear[i][ch];
            if (!(c >= 0.0)) c = 0.0;  // also maps NaN to 0
            if (c > 1.0) c = 1.0;
            const double e = srgb_encode(c) * 255.0;
            out.rgba[4 * i + ch] = static_cast<uint8_t>(std::lround(e));
        }
        out.rgba[4 * i + 3] = 255;
    }
    return out;
}

}  // namespace ref
