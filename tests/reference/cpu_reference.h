// cpu_reference.h — an independent, double-precision CPU ray caster: the test oracle.
//
// The GPU labs rasterise a scene; this file computes, for every pixel centre,
// what that rasterisation *should* produce, straight from docs/conventions.md:
//
//   * one primary ray per pixel centre (x + ½, y + ½), row 0 = top of the image;
//   * every triangle of every object (lab::make_mesh, the same geometry the GPU
//     draws) moved to world space by M = T · Rz · Ry · Rx · S, built here in double;
//   * back faces culled by the winding of the *transformed* triangle, exactly
//     like the rasteriser (so a negative scale flips which side is the front);
//   * the nearest hit whose view depth lies in [near, far] wins (what the
//     near/far clip planes plus a LESS depth test produce).
//
// It deliberately shares no code with the labs' camera classes and uses none of
// glm's lookAt / perspective helpers: an oracle that reuses the code under test
// can only confirm that code's mistakes. glm is used only for vector storage
// and plain arithmetic.
//
// Shading is pluggable: render_reference() finds the visible surface of every
// pixel (a Hit) and hands it to a ShadeFn. Lab 1 draws unlit albedo
// (shade_unlit); a later lab passes a Blinn-Phong ShadeFn using the same hits.
#pragma once

#include "image_io.h"
#include "mesh.h"
#include "scene.h"

#include <glm/glm.hpp>

#include <functional>
#include <string>
#include <vector>

namespace ref {

// ---------------------------------------------------------------------------
// Small double-precision helpers (exposed so the unit tests can check them).
// ---------------------------------------------------------------------------

// sin / cos of an angle in degrees; exact (0, ±1) at multiples of 90° so that
// axis-aligned scenes stay exactly axis-aligned in the reference.
double sin_deg(double degrees);
double cos_deg(double degrees);

// Rotations about the world axes (counter-clockwise looking down the axis
// towards the origin, i.e. the right-hand rule), translation and scale.
glm::dmat4 rotate_x(double degrees);
glm::dmat4 rotate_y(double degrees);
glm::dmat4 rotate_z(double degrees);
glm::dmat4 translate(const glm::dvec3& t);
glm::dmat4 scale(const glm::dvec3& s);

// M = T(position) · Rz(rz) · Ry(ry) · Rx(rx) · S(scale), rotation_deg = [rx, ry, rz].
glm::dmat4 model_matrix(const lab::ObjectDesc& object);

// ---------------------------------------------------------------------------
// Camera
// ---------------------------------------------------------------------------

// The camera as an orthonormal frame in world space plus the projection data.
// Camera space: +X = right, +Y = up, the camera looks down −Z (forward = −Z axis).
struct Camera {
    glm::dvec3 eye{0.0};
    glm::dvec3 right{1.0, 0.0, 0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    glm::dvec3 forward{0.0, 0.0, -1.0};  // world direction of camera −Z
    double fov_y_deg = 60.0;
    double near_plane = 0.01;
    double far_plane = 100.0;

    // Camera-to-world matrix and its inverse, the view matrix.
    glm::dmat4 camera_to_world() const;
    glm::dmat4 view() const;
};

// Builds the camera of either mode of a scene file (docs/conventions.md): look-at with its
// documented fallbacks, or transform mode from position and angles.
Camera make_camera(const lab::CameraDesc& desc);
// The same in double precision, one mode each (the camera unit tests compare lab 1 with them).
Camera look_at_camera(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up);
Camera transform_camera(const glm::dvec3& position, double yaw_deg, double pitch_deg, double roll_deg);
// The camera → clip-space matrix of `camera` for an image of width / height = aspect, in
// Vulkan's clip space (docs/conventions.md). The ray caster needs none; the tests compare with it.
glm::dmat4 projection(const Camera& camera, double aspect);

// A ray origin + t · dir. Primary rays are built with a *non-normalised*
// direction whose camera-space z is −1, so the ray parameter t of a hit is its
// view depth (distance along the camera's −Z axis), the quantity the near and
// far planes clip.
struct Ray {
    glm::dvec3 origin{0.0};
    glm::dvec3 dir{0.0, 0.0, -1.0};
};

// The primary ray through the point (px, py) of a width × height image, in
// pixel units (a pixel centre is (x + 0.5, y + 0.5); py grows downwards).
Ray primary_ray(const Camera& camera, int width, int height, double px, double py);

// ---------------------------------------------------------------------------
// Ray / triangle intersection
// ---------------------------------------------------------------------------

struct TriangleHit {
    double t = 0.0;   // ray parameter
    double b1 = 0.0;  // barycentric weight of v1
    double b2 = 0.0;  // barycentric weight of v2 (v0 gets 1 − b1 − b2)
};

// Watertight ray/triangle test (Woop, Benthin & Wald, JCGT 2013) with back-face
// culling: a triangle is hit only if its front side — counter-clockwise as seen
// from the ray origin, i.e. dot(dir, (v1 − v0) × (v2 − v0)) < 0 — faces the ray.
// Points exactly on an edge count as inside; two triangles sharing an edge never
// leave a gap between them. Returns false for misses, back faces, degenerate
// triangles and t outside [t_min, t_max].
bool intersect_triangle(const Ray& ray, const glm::dvec3& v0, const glm::dvec3& v1,
                        const glm::dvec3& v2, double t_min, double t_max, TriangleHit* hit);

// ---------------------------------------------------------------------------
// Rendering
// ---------------------------------------------------------------------------

// Everything known about the visible surface at one pixel.
struct Hit {
    bool hit = false;             // false: the ray sees the background
    int object_id = -1;           // index into Scene::objects
    int triangle_id = -1;         // triangle index within that object's mesh
    double depth = 0.0;           // view depth (along camera −Z), in [near, far]
    glm::dvec3 position{0.0};     // world-space hit point
    glm::dvec3 normal{0.0};       // interpolated vertex normal × normal matrix, normalised
    glm::dvec3 geometric_normal{0.0};  // normalised (v1 − v0) × (v2 − v0) in world space (front side)
    glm::dvec2 uv{0.0};           // interpolated texture coordinates
    std::string material;         // Scene::objects[object_id].material
    glm::dvec3 view_dir{0.0};     // normalised direction from the hit point towards the eye
    // Set by the ideal tracer (reference/ideal.h) for an exact curved surface: then `normal`
    // and `geometric_normal` are the surface's exact normal, `tangent` its unit world tangent
    // along +u, and triangle_id names the part (0 side, 1 top cap, 2 bottom cap), not a triangle.
    bool analytic = false;
    glm::dvec3 tangent{0.0};
    // Lab 4: the ray crossed the triangle from its back side (SceneGeometry::trace with
    // Facing::Back or Both). `geometric_normal` and `normal` still point to the front side.
    bool back_face = false;
};

// Which sides of a triangle a ray may hit: the rasteriser's culled view (Front), or both, for
// lab 4's translucent layers and shadow rays.
enum class Facing { Front, Back, Both };

// One triangle a ray crosses (SceneGeometry::for_each_hit).
struct CrossedTriangle {
    double t = 0.0;
    int object_id = -1;
    int triangle_id = -1;
    bool front = true;  // crossed from the front side (counter-clockwise as seen from the ray origin)
    double b1 = 0.0, b2 = 0.0;  // barycentric weights of the (unreversed) triangle's v1, v2
    int index = -1;             // SceneGeometry's own triangle number (for hit_of)
};

// Turns a hit (or a miss: hit.hit == false) into a linear RGB colour.
using ShadeFn = std::function<glm::dvec3(const lab::Scene& scene, const Hit& hit)>;

// Lab 1 shading: the material's albedo; the scene background for misses.
glm::dvec3 shade_unlit(const lab::Scene& scene, const Hit& hit);

struct RefImage {
    int width = 0;
    int height = 0;
    std::vector<glm::dvec3> linear;  // linear RGB, row 0 = top, width * height entries
    std::vector<int> object_id;      // −1 = background
    std::vector<int> triangle_id;    // −1 = background
    std::vector<Hit> hits;           // full hit record per pixel (for lighting labs and tests)
    // Lab 4 (render_shadowed): how many different translucent objects show in front of the opaque
    // surface. Where it is 2 or more, the order of the blend is per pixel here but per object in
    // the lab (sorted by centre), which can differ where such objects overlap on screen.
    std::vector<uint8_t> translucent_objects;

    int index(int x, int y) const { return y * width + x; }
};

// A scene's triangles in world space with a bounding-volume hierarchy over
// them, built once and then traced any number of times.
class SceneGeometry {
public:
    explicit SceneGeometry(const lab::Scene& scene);
    ~SceneGeometry();
    SceneGeometry(const SceneGeometry&) = delete;
    SceneGeometry& operator=(const SceneGeometry&) = delete;

    // Nearest front-facing hit with t in [t_min, t_max]; fills everything in
    // Hit except `material` and `view_dir` when found.
    bool trace(const Ray& ray, double t_min, double t_max, Hit* hit, Facing facing = Facing::Front) const;

    // Calls visit() for every triangle the ray crosses with t in [t_min, t_max], either side, in
    // no particular order; stops early when visit() returns false. Returns false if it stopped.
    bool for_each_hit(const Ray& ray, double t_min, double t_max,
                      const std::function<bool(const CrossedTriangle&)>& visit) const;

    // The full hit record of a crossing for_each_hit reported (like trace fills it).
    Hit hit_of(const CrossedTriangle& crossing) const;

    size_t triangle_count() const;

private:
    struct Impl;
    Impl* impl_;
};

// Renders `scene` at width × height: one ray per pixel centre, nearest hit in
// [near, far], shaded by `shade`.
RefImage render_reference(const lab::Scene& scene, int width, int height,
                          const ShadeFn& shade = shade_unlit);

// Finds the visible surface along a ray: nearest front-facing hit with t in [t_min, t_max]
// (SceneGeometry::trace, or the ideal shapes of reference/ideal.h).
using TraceFn = std::function<bool(const Ray& ray, double t_min, double t_max, Hit* hit)>;

// render_reference() with any tracer and `supersample`² samples per pixel: the pixel is
// split into N × N equal cells, one sample at a fixed pseudo-random place in each
// (stratified), and the pixel gets the mean of their linear colours (a box filter: the
// pixel's area integral). N = 1 is the single ray through the pixel centre. The ids and
// the hit record of a pixel are those of its middle cell's sample.
RefImage render_with(const lab::Scene& scene, int width, int height, const ShadeFn& shade, const TraceFn& trace,
                     int supersample = 1);

// The standard sRGB transfer curve (linear → encoded), for one channel in [0, 1].
double srgb_encode(double linear);
// Its inverse (encoded → linear).
double srgb_decode(double encoded);

// The PNG the GPU should produce: linear clamped to [0, 1], sRGB-encoded,
// rounded to the nearest 8-bit value, alpha 255.
lab::Image8 encode_srgb(const RefImage& image);

}  // namespace ref
