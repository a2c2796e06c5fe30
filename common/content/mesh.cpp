// mesh.cpp — the built-in primitives and the OBJ loader (docs/meshes.md has the
// dimensions, default tessellations, UV layouts and the loader's rules).
//
// Conventions used by every mesh here:
//   * counter-clockwise winding seen from outside (front face);
//   * UV origin at the top-left of the image: u grows to the right, v grows
//     downwards (Vulkan / stb_image row order);
//   * tangent.xyz points along +u; the bitangent is B = tangent.w · cross(N, T)
//     and points towards the image top (−v, like glTF and OpenGL-style normal
//     maps). A texture that is not mirrored therefore has w = +1.
#include "mesh.h"

#include "scene.h"

#include <glm/gtc/constants.hpp>

#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_map>

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

// Exact-bits key of a vertex, for welding identical vertices (−0 counts as +0).
struct VertexKey {
    float f[8];
    explicit VertexKey(const Vertex& v) {
        const float in[8] = {v.position.x, v.position.y, v.position.z, v.normal.x,
                             v.normal.y,   v.normal.z,   v.uv.x,       v.uv.y};
        for (int i = 0; i < 8; ++i) f[i] = in[i] + 0.0f;
    }
    bool operator==(const VertexKey& o) const { return std::memcmp(f, o.f, sizeof f) == 0; }
};
struct VertexKeyHash {
    size_t operator()(const VertexKey& k) const {
        uint64_t h = 1469598103934665603ull;  // FNV-1a over the 32 bytes
        const unsigned char* p = reinterpret_cast<const unsigned char*>(k.f);
        for (size_t i = 0; i < sizeof k.f; ++i) h = (h ^ p[i]) * 1099511628211ull;
        return static_cast<size_t>(h);
    }
};

// Adds `v` unless an identical vertex exists; returns its index.
class VertexWelder {
public:
    explicit VertexWelder(Mesh& m) : m_(m) {}
    uint32_t add(const Vertex& v) {
        auto [it, inserted] = map_.try_emplace(VertexKey(v), static_cast<uint32_t>(m_.vertices.size()));
        if (inserted) m_.vertices.push_back(v);
        return it->second;
    }

private:
    Mesh& m_;
    std::unordered_map<VertexKey, uint32_t, VertexKeyHash> map_;
};

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

// ---------------------------------------------------------------------------
// Tangent frames from UVs.
// ---------------------------------------------------------------------------
void compute_tangents(Mesh& mesh) {
    // Inside a triangle the position is linear in (u, v):
    //     P − P0 = (u − u0)·∂P/∂u + (v − v0)·∂P/∂v.
    // With edges e1 = P1 − P0, e2 = P2 − P0 and their UV differences
    // (du1, dv1), (du2, dv2) this is a 2×2 linear system; solving it gives
    //     ∂P/∂u = ( dv2·e1 − dv1·e2) / det,   ∂P/∂v = (−du2·e1 + du1·e2) / det,
    //     det = du1·dv2 − du2·dv1.
    // The tangent is the direction of ∂P/∂u; the "image up" direction is −∂P/∂v.
    // Each vertex averages the directions of its triangles weighted by their area,
    // then the tangent is made perpendicular to the normal (Gram–Schmidt) and
    // w records whether (T, cross(N, T)) matches image-up (+1) or is mirrored (−1).
    std::vector<glm::vec3> tsum(mesh.vertices.size(), glm::vec3(0.0f));
    std::vector<glm::vec3> usum(mesh.vertices.size(), glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
        const Vertex &v0 = mesh.vertices[i0], &v1 = mesh.vertices[i1], &v2 = mesh.vertices[i2];
        const glm::vec3 e1 = v1.position - v0.position, e2 = v2.position - v0.position;
        const glm::vec2 d1 = v1.uv - v0.uv, d2 = v2.uv - v0.uv;
        const float det = d1.x * d2.y - d2.x * d1.y;
        const float area = 0.5f * glm::length(glm::cross(e1, e2));
        if (std::abs(det) < 1e-12f || !(area > 0.0f)) continue;  // no usable UV mapping here
        const glm::vec3 dpdu = (d2.y * e1 - d1.y * e2) / det;
        const glm::vec3 dpdv = (-d2.x * e1 + d1.x * e2) / det;
        const float lu = glm::length(dpdu), lv = glm::length(dpdv);
        if (!(lu > 0.0f) || !(lv > 0.0f) || !std::isfinite(lu) || !std::isfinite(lv)) continue;
        for (uint32_t i : {i0, i1, i2}) {
            tsum[i] += area * dpdu / lu;
            usum[i] -= area * dpdv / lv;
        }
    }
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        Vertex& v = mesh.vertices[i];
        const glm::vec3 n = v.normal;
        glm::vec3 t = tsum[i] - n * glm::dot(n, tsum[i]);  // remove the part along the normal
        if (glm::length(t) < 1e-6f * glm::length(tsum[i]) || glm::length(t) < 1e-20f) {
            // No UVs here: any unit vector perpendicular to the normal will do.
            // Cross with the axis least aligned with n (never parallel to it).
            const glm::vec3 a = std::abs(n.x) < 0.6f ? glm::vec3(1, 0, 0)
                              : std::abs(n.y) < 0.6f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
            t = glm::cross(a, n);
        }
        t = glm::normalize(t);
        const float w = glm::dot(glm::cross(n, t), usum[i]) < 0.0f ? -1.0f : 1.0f;
        v.tangent = glm::vec4(t, w);
    }
}

// ---------------------------------------------------------------------------
// Wavefront OBJ models.
//
// tinyobjloader does the parsing (faces of any size are triangulated by it).
// Before it sees the text, one cheap pass over the lines checks what it
// would silently accept or misread: binary data, truncated `v`/`vt`/`vn`
// lines, bad or huge numbers, faces with fewer than 3 corners and indices that
// are 0 or out of range (tinyobjloader's polygon triangulation could read out
// of bounds with those). It is a validator, not a second parser: the lines are
// not interpreted beyond that.
// ---------------------------------------------------------------------------
namespace {

constexpr double kMaxCoordinate = 1e6;              // |x| above this is rejected
constexpr std::uintmax_t kMaxObjBytes = 1u << 30;   // 1 GiB
constexpr std::uintmax_t kMaxMtlBytes = 64u << 20;  // 64 MiB
constexpr size_t kMaxFanForCrease = 4096;           // see compute_crease_normals
constexpr size_t kMaxFaceCorners = 4096;            // ear clipping costs ~corners² per face

[[noreturn]] void fail(const std::string& file, size_t line, const std::string& reason) {
    std::string msg = file;
    if (line > 0) msg += ":" + std::to_string(line);
    msg += ": " + reason;
    for (char& ch : msg) {
        if (static_cast<unsigned char>(ch) < 0x20) ch = ' ';  // keep it one line
    }
    throw std::runtime_error(msg);
}

// Shortens a piece of the input for an error message.
std::string quote(std::string_view s) {
    std::string q(s.substr(0, 40));
    for (char& ch : q) {
        const unsigned char u = static_cast<unsigned char>(ch);
        if (u < 0x20 || u >= 0x7f) ch = '?';
    }
    return "'" + q + (s.size() > 40 ? "...'" : "'");
}

// Reads a whole regular file. Returns false if it cannot be read; `why` says why.
bool read_small_file(const std::string& path, std::uintmax_t limit, std::string& out, std::string& why) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) { why = "file not found"; return false; }
    if (!std::filesystem::is_regular_file(path, ec)) { why = "not a regular file"; return false; }
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) { why = "cannot read file size"; return false; }
    if (size > limit) { why = "file too large (" + std::to_string(size) + " bytes)"; return false; }
    std::ifstream in(path, std::ios::binary);
    if (!in) { why = "cannot open file"; return false; }
    out.resize(static_cast<size_t>(size));
    in.read(out.data(), static_cast<std::streamsize>(size));
    if (static_cast<std::uintmax_t>(in.gcount()) != size) { why = "read error"; return false; }
    return true;
}

// Bytes that never occur in a text OBJ/MTL file (tab, CR, LF, FF, VT are fine).
bool is_binary_byte(unsigned char c) {
    return c == 0 || c == 0x7f || (c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f' && c != '\v');
}

// Splits at spaces and tabs (what tinyobjloader treats as separators).
std::vector<std::string_view> split_ws(std::string_view s) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
        const size_t b = i;
        while (i < s.size() && s[i] != ' ' && s[i] != '\t') ++i;
        if (i > b) out.push_back(s.substr(b, i - b));
    }
    return out;
}

// A whole token as a number ("+1.5e3" too; anything left over is an error).
bool parse_double(std::string_view tok, double& out) {
    if (tok.size() > 1 && tok[0] == '+' && tok[1] != '-') tok.remove_prefix(1);
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
    if (ec == std::errc::result_out_of_range) out = std::numeric_limits<double>::infinity();
    return !tok.empty() && end == tok.data() + tok.size() && (ec == std::errc() || ec == std::errc::result_out_of_range);
}

bool parse_index(std::string_view tok, long& out) {
    if (tok.size() > 1 && tok[0] == '+' && tok[1] != '-') tok.remove_prefix(1);
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
    return !tok.empty() && ec == std::errc() && end == tok.data() + tok.size();
}

// The validation pass described above. Line numbers count \n, \r\n and \r
// endings, as tinyobjloader does.
void validate_obj_text(const std::string& text, const std::string& file) {
    const auto byte = [&](size_t i) { return static_cast<unsigned char>(text[i]); };
    if (text.size() >= 2 && ((byte(0) == 0xFE && byte(1) == 0xFF) || (byte(0) == 0xFF && byte(1) == 0xFE))) {
        fail(file, 1, "UTF-16 text is not supported (save the file as UTF-8/ASCII)");
    }
    long count[3] = {0, 0, 0};       // v, vt, vn seen so far
    const char* kind_name[3] = {"vertex", "texture coordinate", "normal"};
    size_t line_no = 0, pos = 0;
    while (pos < text.size()) {
        size_t end = pos;
        while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
        const std::string_view line(text.data() + pos, end - pos);
        ++line_no;
        pos = end;
        if (pos < text.size()) pos += (text[pos] == '\r' && pos + 1 < text.size() && text[pos + 1] == '\n') ? 2 : 1;
        for (unsigned char c : line) {
            if (is_binary_byte(c)) fail(file, line_no, "binary data, not a text OBJ file");
        }
        std::vector<std::string_view> tok = split_ws(line);
        if (tok.empty() || tok[0][0] == '#') continue;
        for (size_t i = 1; i < tok.size(); ++i) {
            if (tok[i][0] == '#') tok.resize(i);  // a trailing comment
        }
        const std::string_view key = tok[0];
        const size_t nargs = tok.size() - 1;
        if (key == "v" || key == "vt" || key == "vn") {
            const size_t need = key == "vt" ? 1 : 3;
            if (nargs < need) fail(file, line_no, "truncated '" + std::string(key) + "' line (" + std::to_string(need) + " numbers expected)");
            for (size_t i = 1; i < tok.size(); ++i) {
                double x = 0.0;
                if (!parse_double(tok[i], x)) fail(file, line_no, "bad number " + quote(tok[i]));
                if (!std::isfinite(x)) fail(file, line_no, "non-finite number " + quote(tok[i]));
                if (i <= 3 && std::abs(x) > kMaxCoordinate) fail(file, line_no, "coordinate " + quote(tok[i]) + " too large (limit 1e6)");
            }
            ++count[key == "v" ? 0 : key == "vt" ? 1 : 2];
        } else if (key == "f" || key == "l" || key == "p") {
            const size_t need = key == "f" ? 3 : 1;
            if (nargs < need) {
                fail(file, line_no, std::string(key == "f" ? "face" : key == "l" ? "line" : "point") + " with " +
                                        std::to_string(nargs) + " vertices (at least " + std::to_string(need) + " needed)");
            }
            if (key == "f" && nargs > kMaxFaceCorners) {
                fail(file, line_no, "face with " + std::to_string(nargs) + " vertices (limit " +
                                        std::to_string(kMaxFaceCorners) + ")");
            }
            for (size_t i = 1; i < tok.size(); ++i) {
                // v, v/vt, v//vn or v/vt/vn
                std::string_view part[3];
                std::string_view rest = tok[i];
                int nparts = 0;
                while (true) {
                    const size_t slash = rest.find('/');
                    if (nparts == 3) fail(file, line_no, "bad face vertex " + quote(tok[i]));
                    part[nparts++] = rest.substr(0, slash);
                    if (slash == std::string_view::npos) break;
                    rest = rest.substr(slash + 1);
                }
                for (int k = 0; k < nparts; ++k) {
                    if (part[k].empty() && k == 1 && nparts == 3) continue;  // v//vn
                    long idx = 0;
                    if (!parse_index(part[k], idx)) fail(file, line_no, "bad index in " + quote(tok[i]));
                    if (idx == 0) fail(file, line_no, std::string(kind_name[k]) + " index 0 (OBJ indices start at 1)");
                    // Negative = relative to the elements read so far (−1 = the last one);
                    // positive ones must refer to elements already read too.
                    if (idx > 0 ? idx > count[k] : idx < -count[k]) {
                        fail(file, line_no, std::string(kind_name[k]) + " index " + std::to_string(idx) + " out of range (" +
                                                std::to_string(count[k]) + " defined so far)");
                    }
                }
            }
        }
        // Everything else (g, o, s, usemtl, mtllib, unknown keywords) is left to tinyobjloader.
    }
}

// Collects warnings: printed once each to stderr as "warning: FILE: reason".
class Warnings {
public:
    Warnings(std::string file, std::vector<std::string>& out, bool print)
        : file_(std::move(file)), out_(out), print_(print) {}
    void add(std::string reason) {
        for (char& ch : reason) {
            if (static_cast<unsigned char>(ch) < 0x20) ch = ' ';
        }
        while (!reason.empty() && (reason.back() == ' ' || reason.back() == '.')) reason.pop_back();
        if (reason.empty() || std::find(out_.begin(), out_.end(), reason) != out_.end()) return;
        out_.push_back(reason);
        if (print_) std::cerr << "warning: " << file_ << ": " << reason << "\n";
    }
    // tinyobjloader reports several problems as one string, one per line.
    void add_lines(const std::string& text) {
        std::istringstream in(text);
        for (std::string line; std::getline(in, line);) {
            // Said already, better, by SafeMtlReader.
            if (line.find("Failed to load material file(s)") != std::string::npos) continue;
            add(line);
        }
    }

private:
    std::string file_;
    std::vector<std::string>& out_;
    bool print_;
};

// Opens `mtllib` files for tinyobjloader: only regular files of sane size
// (a hostile `mtllib /dev/zero` would otherwise never end), missing files are
// a warning, and Windows separators are accepted.
class SafeMtlReader : public tinyobj::MaterialReader {
public:
    SafeMtlReader(std::string dir, Warnings& warnings) : dir_(std::move(dir)), warnings_(warnings) {}
    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* map, std::string* warn, std::string* err) override {
        std::string rel = name;
        std::replace(rel.begin(), rel.end(), '\\', '/');
        const std::string path = (std::filesystem::path(dir_) / rel).string();
        std::string text, why;
        if (!read_small_file(path, kMaxMtlBytes, text, why)) {
            warnings_.add("material library " + quote(name) + ": " + why + "; using the scene material");
            return false;
        }
        for (unsigned char c : text) {
            if (is_binary_byte(c)) {
                warnings_.add("material library " + quote(name) + " is not a text file; using the scene material");
                return false;
            }
        }
        std::istringstream in(text);
        tinyobj::LoadMtl(map, materials, &in, warn, err);
        return true;
    }

private:
    std::string dir_;
    Warnings& warnings_;
};

float finite_or(float x, float fallback) { return std::isfinite(x) ? x : fallback; }
glm::vec3 color_of(const tinyobj::real_t c[3]) {
    return glm::clamp(glm::vec3(finite_or(c[0], 0.0f), finite_or(c[1], 0.0f), finite_or(c[2], 0.0f)), 0.0f, 1.0f);
}

// One triangle corner as tinyobjloader gives it (indices into the attrib arrays, −1 = none).
struct Corner { int v, vt, vn; };

// Smooth normals with a crease angle, for the corners that have no normal.
//
// Area weighting: the cross product of two edges of a triangle is its normal
// scaled by twice its area, so summing the raw cross products of the
// triangles around a point averages their normals weighted by area — big
// triangles count more than slivers, which keeps the result stable under
// re-triangulation.
//
// Crease angle: a corner of triangle t only sums the triangles around its
// point whose normal is within `crease` of t's own normal. On a smooth
// surface that is all of them (a smooth normal). At a sharp edge, like the
// 90° edges of a cube with the 60° default, each side only sees its own
// faces, so the corners on the two sides get different normals: the vertex
// is "cloned" there (the de-duplication later keeps one vertex per distinct
// normal) and the edge stays hard.
//
// `point_of` maps an OBJ vertex index to a welded point id (equal positions
// share an id even when the file repeats them, so seams in the UVs do not
// become seams in the shading).
std::vector<glm::vec3> compute_crease_normals(const std::vector<glm::dvec3>& face_normal,  // raw cross products
                                              const std::vector<uint32_t>& corner_point,  // 3 per triangle
                                              size_t point_count, float crease_deg, bool& capped_fans) {
    const size_t tri_count = face_normal.size();
    // Triangles around each point, as one flat array (CSR): fan[first[p] .. first[p+1]).
    std::vector<uint32_t> first(point_count + 1, 0), fan(corner_point.size());
    for (uint32_t p : corner_point) ++first[p + 1];
    for (size_t p = 0; p < point_count; ++p) first[p + 1] += first[p];
    std::vector<uint32_t> fill(first.begin(), first.end() - 1);
    for (size_t c = 0; c < corner_point.size(); ++c) fan[fill[corner_point[c]]++] = static_cast<uint32_t>(c / 3);

    std::vector<glm::dvec3> unit(tri_count);
    for (size_t t = 0; t < tri_count; ++t) unit[t] = glm::normalize(face_normal[t]);
    // Two faces are on the same smooth side if the angle between their normals
    // is at most the crease angle: cos(angle) = dot(n1, n2) ≥ cos(crease). A tiny
    // slack keeps coplanar triangles together even with crease 0.
    const double cos_crease = std::cos(glm::radians(double(std::clamp(crease_deg, 0.0f, 180.0f)))) - 1e-5;

    std::vector<glm::vec3> normal(corner_point.size());
    for (size_t c = 0; c < corner_point.size(); ++c) {
        const size_t t = c / 3;
        const uint32_t p = corner_point[c];
        const size_t n_fan = first[p + 1] - first[p];
        glm::dvec3 sum(0.0);
        if (n_fan > kMaxFanForCrease) {
            // Comparing every pair around a point shared by thousands of
            // triangles costs fan² (a hostile file could make that hang); real
            // models never get there, so such a point just keeps flat faces.
            capped_fans = true;
            sum = face_normal[t];
        } else {
            for (uint32_t k = first[p]; k < first[p + 1]; ++k) {
                if (glm::dot(unit[t], unit[fan[k]]) >= cos_crease) sum += face_normal[fan[k]];
            }
        }
        const double len = glm::length(sum);
        normal[c] = glm::vec3(len > 0.0 && std::isfinite(len) ? sum / len : unit[t]);
    }
    return normal;
}

}  // namespace

LoadedModel load_obj(const std::string& path, float crease_deg, bool normalize, bool print_warnings) {
    LoadedModel model;
    Warnings warnings(path, model.warnings, print_warnings);

    std::string text, why;
    if (!read_small_file(path, kMaxObjBytes, text, why)) fail(path, 0, why);
    if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);  // UTF-8 BOM
    validate_obj_text(text, path);

    // --- parse with tinyobjloader (it triangulates polygons: quads along the
    // shorter diagonal, larger polygons by ear clipping) ---
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    const std::string dir = std::filesystem::path(path).parent_path().string();
    SafeMtlReader mtl_reader(dir.empty() ? "." : dir, warnings);
    std::istringstream in(text);
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &mtl_reader,
                                     /*triangulate=*/true, /*default_vcols_fallback=*/false);
    warnings.add_lines(warn);
    if (!ok || !err.empty()) {
        std::string first_line = err.substr(0, err.find('\n'));
        if (first_line.empty()) first_line = "tinyobjloader could not parse the file";
        fail(path, 0, first_line);
    }

    // --- materials ---
    for (const tinyobj::material_t& mt : materials) {
        ObjMaterial m;
        m.name = mt.name;
        m.albedo = color_of(mt.diffuse);
        m.specular = color_of(mt.specular);
        m.emissive = glm::max(glm::vec3(finite_or(mt.emission[0], 0.0f), finite_or(mt.emission[1], 0.0f),
                                        finite_or(mt.emission[2], 0.0f)), glm::vec3(0.0f));
        m.shininess = std::clamp(finite_or(mt.shininess, 32.0f), 1.0f, 1000.0f);
        // Texture maps: paths relative to the .mtl; Windows exporters write backslashes.
        const auto texture = [&](const std::string& name, const char* what, std::string& out) {
            if (name.empty()) return;
            std::string rel = name;
            std::replace(rel.begin(), rel.end(), '\\', '/');
            const std::filesystem::path tex = std::filesystem::path(dir.empty() ? "." : dir) / rel;
            std::error_code ec;
            if (std::filesystem::is_regular_file(tex, ec)) {
                out = std::filesystem::absolute(tex, ec).lexically_normal().string();
            } else {
                warnings.add(std::string(what) + " " + quote(name) + " of material " + quote(mt.name) +
                             " not found; the map is left out");
            }
        };
        texture(mt.diffuse_texname, "texture", m.albedo_texture);
        texture(mt.specular_texname, "specular map", m.specular_texture);
        texture(mt.emissive_texname, "emissive map", m.emissive_texture);
        model.materials.push_back(m);
    }

    // --- gather the triangles, checking tinyobjloader's output ourselves ---
    const size_t nv = attrib.vertices.size() / 3, nt = attrib.texcoords.size() / 2, nn = attrib.normals.size() / 3;
    const auto position = [&](int v) {
        return glm::vec3(attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]);
    };
    for (size_t i = 0; i < attrib.vertices.size(); ++i) {
        if (!std::isfinite(attrib.vertices[i]) || std::abs(attrib.vertices[i]) > kMaxCoordinate) {
            fail(path, 0, "invalid vertex coordinate");
        }
    }
    // Twice-area-long normal of a triangle (in double: tiny models must not underflow).
    const auto face_normal_of = [&](const Corner* tri) {
        const glm::dvec3 p0(position(tri[0].v)), p1(position(tri[1].v)), p2(position(tri[2].v));
        return glm::cross(p1 - p0, p2 - p0);
    };
    std::vector<Corner> corners;
    std::vector<int> tri_material;
    size_t dropped = 0, lines_or_points = 0;
    for (const tinyobj::shape_t& shape : shapes) {
        lines_or_points += shape.lines.num_line_vertices.size() + shape.points.indices.size();
        size_t offset = 0;
        for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            const size_t fv = shape.mesh.num_face_vertices[f];
            if (offset + fv > shape.mesh.indices.size()) fail(path, 0, "inconsistent face data from the OBJ parser");
            std::vector<Corner> poly;
            for (size_t k = 0; k < fv; ++k) {
                const tinyobj::index_t& ix = shape.mesh.indices[offset + k];
                if (ix.vertex_index < 0 || size_t(ix.vertex_index) >= nv || ix.texcoord_index >= int(nt) ||
                    ix.normal_index >= int(nn) || ix.texcoord_index < -1 || ix.normal_index < -1) {
                    fail(path, 0, "face index out of range");
                }
                poly.push_back({ix.vertex_index, ix.texcoord_index, ix.normal_index});
            }
            offset += fv;
            int mat = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
            if (mat < 0 || size_t(mat) >= model.materials.size()) mat = -1;
            // tinyobjloader already made triangles; a fan covers anything else.
            for (size_t k = 1; k + 1 < poly.size(); ++k) {
                const Corner tri[3] = {poly[0], poly[k], poly[k + 1]};
                const double len = glm::length(face_normal_of(tri));
                if (!(len > 0.0) || !std::isfinite(len)) {  // zero area: nothing to draw
                    ++dropped;
                    continue;
                }
                corners.insert(corners.end(), tri, tri + 3);
                tri_material.push_back(mat);
            }
        }
    }
    if (lines_or_points > 0) warnings.add("line and point elements ignored (only faces are drawn)");
    if (dropped > 0) warnings.add(std::to_string(dropped) + " zero-area triangle(s) dropped");
    if (corners.empty()) fail(path, 0, "no faces (nothing to draw)");
    const size_t tri_count = corners.size() / 3;

    // --- normals: from the file where given, else smooth with a crease angle ---
    std::vector<glm::dvec3> face_normal(tri_count);
    for (size_t t = 0; t < tri_count; ++t) face_normal[t] = face_normal_of(&corners[3 * t]);
    // Weld equal positions into points.
    std::unordered_map<VertexKey, uint32_t, VertexKeyHash> point_id;
    std::vector<uint32_t> point_of(nv);
    for (size_t v = 0; v < nv; ++v) {
        Vertex probe{};
        probe.position = position(int(v));
        point_of[v] = point_id.try_emplace(VertexKey(probe), uint32_t(point_id.size())).first->second;
    }
    std::vector<uint32_t> corner_point(corners.size());
    for (size_t c = 0; c < corners.size(); ++c) corner_point[c] = point_of[corners[c].v];
    bool capped = false;
    const std::vector<glm::vec3> smooth =
        compute_crease_normals(face_normal, corner_point, point_id.size(), crease_deg, capped);
    if (capped) warnings.add("points shared by more than 4096 triangles keep flat normals");

    // --- build the indexed mesh, one vertex per distinct (position, normal, uv) ---
    Mesh& mesh = model.mesh;
    VertexWelder welder(mesh);
    mesh.indices.reserve(corners.size());
    for (size_t c = 0; c < corners.size(); ++c) {
        const Corner& k = corners[c];
        Vertex v{};
        v.position = position(k.v);
        v.normal = smooth[c];
        if (k.vn >= 0) {
            const glm::vec3 n(attrib.normals[3 * k.vn], attrib.normals[3 * k.vn + 1], attrib.normals[3 * k.vn + 2]);
            const float len = glm::length(n);
            if (len > 1e-12f && std::isfinite(len)) v.normal = n / len;  // else keep the computed one
        }
        if (k.vt >= 0) {
            // OBJ puts v = 0 at the bottom of the image; here v = 0 is the top row.
            v.uv = {attrib.texcoords[2 * k.vt], 1.0f - attrib.texcoords[2 * k.vt + 1]};
        }
        mesh.indices.push_back(welder.add(v));
    }
    model.triangle_material = std::move(tri_material);

    if (normalize) {
        // Fit into a unit box: centre the bounding box on the origin and scale
        // its largest side to 1 (uniform scale, so normals stay valid).
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (const Vertex& v : mesh.vertices) {
            lo = glm::min(lo, v.position);
            hi = glm::max(hi, v.position);
        }
        const glm::vec3 size = hi - lo, centre = 0.5f * (lo + hi);
        const float extent = std::max(size.x, std::max(size.y, size.z));
        for (Vertex& v : mesh.vertices) v.position = (v.position - centre) / extent;  // extent > 0: no zero-area triangles
    }
    compute_tangents(mesh);
    return model;
}

Mesh make_mesh(const ObjectDesc& object) {
    MeshLibrary library;
    return library.mesh(object);
}

Mesh MeshLibrary::mesh(const ObjectDesc& object) {
    if (!object.mesh_path.empty()) {
        std::string ext = std::filesystem::path(object.mesh_path).extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        if (ext != ".obj") fail(object.mesh_path, 0, "unsupported model format (only .obj)");
        // A model split into one object per .mtl material is read once. Its warnings were
        // printed when the scene loader split it; a whole model prints them here.
        const std::string key = object.mesh_path + "|" + std::to_string(object.crease_deg) + "|" +
                                std::to_string(object.normalize);
        auto it = models_.find(key);
        if (it == models_.end()) {
            const bool split = object.obj_material != ObjectDesc::kAllTriangles;
            it = models_.emplace(key, load_obj(object.mesh_path, object.crease_deg, object.normalize, !split)).first;
        }
        const LoadedModel& model = it->second;
        if (object.obj_material == ObjectDesc::kAllTriangles) return model.mesh;
        if (object.obj_material < -1 || object.obj_material >= int(model.materials.size()))
            fail(object.mesh_path, 0, "no material number " + std::to_string(object.obj_material));
        // Keep only the triangles of one .mtl material (see expand_model_materials in scene.cpp).
        Mesh part;
        part.vertices = model.mesh.vertices;
        for (size_t t = 0; t < model.triangle_material.size(); ++t)
            if (model.triangle_material[t] == object.obj_material)
                part.indices.insert(part.indices.end(), model.mesh.indices.begin() + long(3 * t),
                                    model.mesh.indices.begin() + long(3 * t + 3));
        return part;
    }
    // 0 = the primitive's default tessellation (see docs/meshes.md).
    const auto pick = [](int value, int fallback) { return value > 0 ? value : fallback; };
    const std::string& name = object.mesh;
    if (name == "plane") return make_plane();
    if (name == "cube") return make_cube();
    if (name == "sphere") return make_sphere(pick(object.segments, 32), pick(object.rings, 16));
    if (name == "icosahedron") return make_icosahedron();
    if (name == "icosphere") return make_icosphere(pick(object.segments, 2));
    if (name == "cylinder") return make_cylinder(pick(object.segments, 32), pick(object.rings, 1));
    if (name == "cone") return make_cone(pick(object.segments, 32), pick(object.rings, 1));
    if (name == "torus") return make_torus(pick(object.segments, 48), pick(object.rings, 16));
    throw std::runtime_error(name + ": unknown mesh (expected plane, cube, sphere, icosahedron, icosphere, "
                                    "cylinder, cone, torus or an .obj file)");
}

}  // namespace lab
