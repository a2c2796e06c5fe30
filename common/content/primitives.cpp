// primitives.cpp — the built-in shapes of primitives.h (docs/meshes.md has the
// dimensions, default tessellations and UV layouts).
//
// Conventions used by every mesh here:
//   * counter-clockwise winding seen from outside (front face);
//   * UV origin at the top-left of the image: u grows to the right, v grows
//     downwards (Vulkan / stb_image row order);
//   * tangent.xyz points along +u; the bitangent is B = tangent.w · cross(N, T)
//     and points towards the image top (−v, like glTF and OpenGL-style normal
//     maps). A texture that is not mirrored therefore has w = +1.
#include "primitives.h"

#include "vertex_welder.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace lab {
namespace {

constexpr float kPi = glm::pi<float>();

// Appends one flat rectangle: centre c, unit normal n, half extents along
// `right` and `up` (right × up = n, so "right" and "up" are as seen from the
// front). The texture covers the whole rectangle, upright when seen from the front.
void add_quad(Mesh& m, glm::vec3 c, glm::vec3 n, glm::vec3 right, glm::vec3 up) {
    const uint32_t base = static_cast<uint32_t>(m.vertices.size());
    const glm::vec4 t(glm::normalize(right), 1.0f);
    m.vertices.push_back({c - right - up, n, {0.0f, 1.0f}, t});  // bottom-left
    m.vertices.push_back({c + right - up, n, {1.0f, 1.0f}, t});  // bottom-right
    m.vertices.push_back({c + right + up, n, {1.0f, 0.0f}, t});  // top-right
    m.vertices.push_back({c - right + up, n, {0.0f, 0.0f}, t});  // top-left
    // bottom-left → bottom-right → top-right is counter-clockwise seen from the front.
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
}

// Direction on the unit sphere for longitude u ∈ [0,1] and polar angle theta
// (0 = +Y). u = 0 and u = 1 are the seam at −Z; u = 0.5 faces +Z. Seen from
// outside with +Y up, u increases to the right.
glm::vec3 sphere_dir(float u, float theta) {
    const float phi = kPi + 2.0f * kPi * u;
    return {std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi)};
}

}  // namespace

Mesh make_plane() {
    Mesh m;
    // Seen from above (+Y) the top of the texture is at −Z.
    add_quad(m, {0, 0, 0}, {0, 1, 0}, {0.5f, 0, 0}, {0, 0, -0.5f});
    return m;
}

Mesh make_cube() {
    Mesh m;
    // One quad per face (right × up = outward normal); 4 own vertices each so
    // that every face keeps its flat normal: the cube's edges stay hard.
    const glm::vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
    struct Face { glm::vec3 n, right, up; };
    const Face faces[] = {
        {Z, X, Y}, {-Z, -X, Y}, {X, -Z, Y}, {-X, Z, Y}, {Y, X, -Z}, {-Y, X, Z},
    };
    for (const Face& f : faces) add_quad(m, 0.5f * f.n, f.n, 0.5f * f.right, 0.5f * f.up);
    return m;
}

// ---------------------------------------------------------------------------
// Surfaces of revolution: sphere, cylinder, cone and torus are all a profile
// curve (a list of rings, top to bottom) swept around the Y axis.
// ---------------------------------------------------------------------------
namespace {

// One ring of a surface of revolution: its radius and height, the outward
// normal in the (radial, y) half-plane, and the texture v of the ring.
struct Ring {
    float radius, y;
    float n_radial, n_y;
    float v;
};

// Point `i` (of `segments`) on the circle of the given radius and height.
// `half` shifts it half a step (the middle of segment i). The angle comes from
// i mod segments, so the seam column i = segments lands bit-exactly on column 0.
glm::vec3 ring_point(float radius, float y, int i, int segments, bool half = false) {
    const float u = (float(i % segments) + (half ? 0.5f : 0.0f)) / float(segments);
    const glm::vec3 d = sphere_dir(u, 0.5f * kPi);  // unit vector in XZ
    return {radius * d.x, y, radius * d.z};
}

// Sweeps `rings` around +Y in `segments` steps. Each ring gets segments + 1
// vertices (the seam is duplicated: u runs 0 → 1). A ring of radius 0 (a pole
// or an apex) gets one vertex per segment, placed at the segment's middle u,
// so neither the texture nor the normal twists there and no zero-area triangle
// is made. Quad (i, j): a top-left, b top-right, c bottom-right, d bottom-left
// seen from outside; a → d → c and a → c → b are counter-clockwise.
void add_revolution(Mesh& m, int segments, const std::vector<Ring>& rings) {
    std::vector<uint32_t> start(rings.size());
    for (size_t j = 0; j < rings.size(); ++j) {
        const Ring& r = rings[j];
        const bool pole = r.radius == 0.0f;
        start[j] = static_cast<uint32_t>(m.vertices.size());
        for (int i = 0; i < (pole ? segments : segments + 1); ++i) {
            const float u = (float(i) + (pole ? 0.5f : 0.0f)) / float(segments);
            const glm::vec3 radial = ring_point(1.0f, 0.0f, i, segments, pole);
            Vertex v;
            v.position = ring_point(r.radius, r.y, i, segments, pole);
            v.normal = glm::normalize(r.n_radial * radial + glm::vec3(0.0f, r.n_y, 0.0f));
            v.uv = {u, r.v};
            // +u runs along the circle: d/dφ (sin φ, 0, cos φ) = (cos φ, 0, −sin φ).
            v.tangent = glm::vec4(radial.z, 0.0f, -radial.x, 1.0f);
            m.vertices.push_back(v);
        }
    }
    for (size_t j = 0; j + 1 < rings.size(); ++j) {
        const bool top_pole = rings[j].radius == 0.0f;
        const bool bottom_pole = rings[j + 1].radius == 0.0f;
        for (int i = 0; i < segments; ++i) {
            const uint32_t a = start[j] + i, b = a + 1, d = start[j + 1] + i, c = d + 1;
            if (top_pole) {
                m.indices.insert(m.indices.end(), {a, d, c});  // a is the pole vertex of segment i
            } else if (bottom_pole) {
                m.indices.insert(m.indices.end(), {a, d, b});  // d is the pole vertex of segment i
            } else {
                m.indices.insert(m.indices.end(), {a, d, c, a, c, b});
            }
        }
    }
}

// A flat disc (radius r, height y) facing +Y (`up`) or −Y, as a fan around its
// centre. Planar UVs: the texture is upright seen from outside, as on the
// matching face of the cube.
void add_cap(Mesh& m, int segments, float r, float y, bool up) {
    const glm::vec3 n(0.0f, up ? 1.0f : -1.0f, 0.0f);
    const glm::vec4 t(1.0f, 0.0f, 0.0f, 1.0f);
    const auto uv_of = [&](glm::vec3 p) {
        return glm::vec2(0.5f + 0.5f * p.x / r, 0.5f + (up ? 0.5f : -0.5f) * p.z / r);
    };
    const uint32_t centre = static_cast<uint32_t>(m.vertices.size());
    m.vertices.push_back({{0.0f, y, 0.0f}, n, {0.5f, 0.5f}, t});
    for (int i = 0; i < segments; ++i) {
        const glm::vec3 p = ring_point(r, y, i, segments);
        m.vertices.push_back({p, n, uv_of(p), t});
    }
    for (int i = 0; i < segments; ++i) {
        const uint32_t p0 = centre + 1 + i, p1 = centre + 1 + (i + 1) % segments;
        // Going round with growing φ is counter-clockwise seen from +Y.
        if (up) m.indices.insert(m.indices.end(), {centre, p0, p1});
        else m.indices.insert(m.indices.end(), {centre, p1, p0});
    }
}

}  // namespace

Mesh make_sphere(int segments, int rings) {
    segments = std::clamp(segments, 3, 1024);
    rings = std::clamp(rings, 2, 1024);
    // Ring j has polar angle θ = π·j/rings (v = j/rings, north pole at the image top);
    // on a sphere the normal is the position direction (sin θ, cos θ).
    std::vector<Ring> profile;
    for (int j = 0; j <= rings; ++j) {
        const float theta = kPi * float(j) / float(rings);
        const bool pole = j == 0 || j == rings;
        const float s = pole ? 0.0f : std::sin(theta), c = std::cos(theta);
        profile.push_back({0.5f * s, 0.5f * c, s, c, float(j) / float(rings)});
    }
    Mesh m;
    add_revolution(m, segments, profile);
    return m;
}

Mesh make_cylinder(int segments, int rings) {
    segments = std::clamp(segments, 3, 1024);
    rings = std::clamp(rings, 1, 1024);
    std::vector<Ring> profile;
    for (int j = 0; j <= rings; ++j) {
        const float v = float(j) / float(rings);
        profile.push_back({0.5f, 0.5f - v, 1.0f, 0.0f, v});
    }
    Mesh m;
    // The side and the caps have their own vertices along the rims: the rim
    // is a hard edge (side normal horizontal, cap normal ±Y).
    add_revolution(m, segments, profile);
    add_cap(m, segments, 0.5f, 0.5f, true);
    add_cap(m, segments, 0.5f, -0.5f, false);
    return m;
}

Mesh make_cone(int segments, int rings) {
    segments = std::clamp(segments, 3, 1024);
    rings = std::clamp(rings, 1, 1024);
    // The side is a line from the apex (0, 0.5) to the rim (0.5, −0.5) in the
    // (radial, y) plane; a normal to it is (height, radius) = (1, 0.5).
    std::vector<Ring> profile;
    for (int j = 0; j <= rings; ++j) {
        const float t = float(j) / float(rings);  // 0 at the apex, 1 at the rim
        profile.push_back({0.5f * t, 0.5f - t, 1.0f, 0.5f, t});
    }
    Mesh m;
    add_revolution(m, segments, profile);  // apex: one vertex per segment, mid normal
    add_cap(m, segments, 0.5f, -0.5f, false);
    return m;
}

Mesh make_torus(int segments, int rings) {
    segments = std::clamp(segments, 3, 1024);
    rings = std::clamp(rings, 3, 1024);
    const float R = 0.35f, r = 0.15f;
    // Ring j sits at angle θ around the tube: θ = π/2 (top of the tube, v = 0),
    // then outside, bottom, inside, and back to the top at v = 1 (θ decreases so
    // that v runs downwards on the outside, like on the sphere). The angle
    // comes from j mod rings so the last ring repeats the first one exactly.
    std::vector<Ring> profile;
    for (int j = 0; j <= rings; ++j) {
        const float theta = 0.5f * kPi - 2.0f * kPi * float(j % rings) / float(rings);
        const float c = std::cos(theta), s = std::sin(theta);
        profile.push_back({R + r * c, r * s, c, s, float(j) / float(rings)});
    }
    Mesh m;
    add_revolution(m, segments, profile);
    return m;
}

// ---------------------------------------------------------------------------
// Icosahedron and icosphere.
// ---------------------------------------------------------------------------
namespace {

using detail::VertexWelder;  // neighbouring small triangles share corners: one vertex each

// Builds an icosahedron whose faces are split into n × n small triangles
// (n = 2^level; the same points as splitting every triangle into 4, `level` times).
// smooth: points pushed onto the sphere, normal = direction from the centre;
// otherwise flat faces with the face normal.
//
// UVs come from the classic unfolding (net) of the icosahedron: a strip of 5
// "north" triangles, 10 around the equator and 5 "south" ones, laid out
// left to right with growing longitude (see docs/meshes.md). Small triangles
// get barycentric UVs inside their big face, so the texture is never mirrored.
Mesh make_icosa(int n, bool smooth) {
    // 12 corners on the unit sphere: poles N (0) and S (11), an upper ring U0..U4
    // (1..5) at latitude +atan(1/2) and a lower ring L0..L4 (6..10) at −atan(1/2),
    // turned by half a step (36°).
    const float lat = std::atan(0.5f);
    glm::vec3 P[12];
    P[0] = {0.0f, 1.0f, 0.0f};
    P[11] = {0.0f, -1.0f, 0.0f};
    for (int k = 0; k < 5; ++k) {
        P[1 + k] = sphere_dir(float(k) / 5.0f, 0.5f * kPi - lat);
        P[6 + k] = sphere_dir((float(k) + 0.5f) / 5.0f, 0.5f * kPi + lat);
    }
    const auto U = [](int k) { return 1 + (k + 5) % 5; };
    const auto L = [](int k) { return 6 + (k + 5) % 5; };

    // Net coordinates in triangle units: x in edge lengths, y in rows (row 0 = N).
    struct Corner { int id; float x, y; };
    struct Face { Corner a, b, c; };  // counter-clockwise seen from outside
    std::vector<Face> faces;
    for (int k = 0; k < 5; ++k) {
        const float x = float(k);
        faces.push_back({{0, x + 1.0f, 0}, {U(k), x + 0.5f, 1}, {U(k + 1), x + 1.5f, 1}});
        faces.push_back({{U(k), x + 0.5f, 1}, {L(k - 1), x, 2}, {L(k), x + 1.0f, 2}});
        faces.push_back({{U(k), x + 0.5f, 1}, {L(k), x + 1.0f, 2}, {U(k + 1), x + 1.5f, 1}});
        // South triangles, shifted one place left so the net stays 5.5 edges wide.
        faces.push_back({{L(k - 1), x, 2}, {11, x + 0.5f, 3}, {L(k), x + 1.0f, 2}});
    }
    const float s = 1.0f / 5.5f;                  // edge length in UV units
    const float h = s * 0.5f * std::sqrt(3.0f);   // row height (equilateral triangles)

    Mesh m;
    VertexWelder welder(m);
    const float fn = float(n);
    for (const Face& f : faces) {
        const glm::vec3 A = P[f.a.id], B = P[f.b.id], C = P[f.c.id];
        const glm::vec2 tA(f.a.x * s, f.a.y * h), tB(f.b.x * s, f.b.y * h), tC(f.c.x * s, f.c.y * h);
        const glm::vec3 flat_n = glm::normalize(glm::cross(B - A, C - A));
        // Point (i, j) = A + (B−A)·i/n + (C−A)·j/n, written as a weighted sum so
        // that two faces sharing an edge compute bit-identical points there.
        const auto point = [&](int i, int j) {
            const float wa = float(n - i - j), wb = float(i), wc = float(j);
            const glm::vec3 p = (A * wa + B * wb + C * wc) / fn;
            Vertex v;
            v.normal = smooth ? glm::normalize(p) : flat_n;
            v.position = smooth ? 0.5f * v.normal : 0.5f * p;
            v.uv = (tA * wa + tB * wb + tC * wc) / fn;
            v.tangent = glm::vec4(0.0f);  // computed below from the UVs
            return welder.add(v);
        };
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i + j < n; ++i) {
                // "Upright" small triangle, oriented like A, B, C ...
                m.indices.insert(m.indices.end(), {point(i, j), point(i + 1, j), point(i, j + 1)});
                // ... and the "upside-down" one next to it.
                if (i + j + 1 < n) {
                    m.indices.insert(m.indices.end(), {point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)});
                }
            }
        }
    }
    compute_tangents(m);
    return m;
}

}  // namespace

Mesh make_icosahedron() { return make_icosa(1, false); }

Mesh make_icosphere(int level) {
    level = std::clamp(level, 0, 7);
    return make_icosa(1 << level, true);
}

}  // namespace lab
