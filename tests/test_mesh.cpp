// Tests for common/content/: the built-in primitives (primitives.cpp), the OBJ loader
// (obj_model.cpp, with the line checks of obj_text.cpp) and make_mesh (mesh.cpp);
// dimensions, UV layouts and error rules are in docs/meshes.md.
//
// Primitive invariants: valid indices, unit normals, unit tangents ⟂ normals,
// UVs in [0,1], counter-clockwise winding that agrees with the normals, closed
// 2-manifolds (every edge used exactly twice, in opposite directions) with
// positive volume close to the analytic one, triangle counts per tessellation.
// OBJ: polygons, negative indices, groups, crease-angle normals, materials,
// normalize, every kind of broken file (each must give a one-line
// std::runtime_error, never a crash), and a sweep over assimp's test models.
#include "mesh.h"
#include "scene.h"
#include "temp_dir.h"

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;
using lab::Mesh;
using lab::Vertex;

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------


size_t triangle_count(const Mesh& m) { return m.indices.size() / 3; }

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Index validity, finite data, unit normals, unit tangents perpendicular to
// the normal, handedness ±1. Reports the first few failures only.
void expect_valid_vertices(const Mesh& m, const std::string& what) {
    SCOPED_TRACE(what);
    ASSERT_FALSE(m.vertices.empty());
    ASSERT_FALSE(m.indices.empty());
    ASSERT_EQ(m.indices.size() % 3, 0u);
    for (uint32_t i : m.indices) ASSERT_LT(i, m.vertices.size());
    int failures = 0;
    for (size_t i = 0; i < m.vertices.size() && failures < 5; ++i) {
        const Vertex& v = m.vertices[i];
        const glm::vec3 t(v.tangent);
        const bool ok = finite(v.position) && finite(v.normal) && finite(t) && std::isfinite(v.uv.x) &&
                        std::isfinite(v.uv.y) && std::abs(glm::length(v.normal) - 1.0f) < 1e-4f &&
                        std::abs(glm::length(t) - 1.0f) < 1e-4f && std::abs(glm::dot(t, v.normal)) < 1e-4f &&
                        (v.tangent.w == 1.0f || v.tangent.w == -1.0f);
        if (!ok) {
            ++failures;
            ADD_FAILURE() << "vertex " << i << ": |n| = " << glm::length(v.normal) << ", |t| = " << glm::length(t)
                          << ", t·n = " << glm::dot(t, v.normal) << ", w = " << v.tangent.w;
        }
    }
}

void expect_uvs_in_unit_square(const Mesh& m) {
    for (const Vertex& v : m.vertices) {
        ASSERT_TRUE(v.uv.x >= 0.0f && v.uv.x <= 1.0f && v.uv.y >= 0.0f && v.uv.y <= 1.0f)
            << "uv (" << v.uv.x << ", " << v.uv.y << ")";
    }
}

// Counter-clockwise seen from the front: the geometric normal of every
// triangle, (b − a) × (c − a), points to the same side as its vertex normals.
void expect_winding_matches_normals(const Mesh& m) {
    int failures = 0;
    for (size_t t = 0; t < triangle_count(m) && failures < 5; ++t) {
        const Vertex &a = m.vertices[m.indices[3 * t]], &b = m.vertices[m.indices[3 * t + 1]],
                     &c = m.vertices[m.indices[3 * t + 2]];
        const glm::vec3 g = glm::cross(b.position - a.position, c.position - a.position);
        ASSERT_GT(glm::length(g), 0.0f) << "zero-area triangle " << t;
        for (const Vertex* v : {&a, &b, &c}) {
            if (!(glm::dot(g, v->normal) > 0.0f)) {
                ++failures;
                ADD_FAILURE() << "triangle " << t << " winding disagrees with its vertex normal";
            }
        }
    }
}

// Welded point id per vertex (positions rounded to 1e-5: seams and hard
// edges duplicate vertices, which are the same point of the surface).
std::vector<int> weld(const Mesh& m) {
    std::map<std::tuple<long, long, long>, int> ids;
    std::vector<int> out;
    for (const Vertex& v : m.vertices) {
        const auto key = std::make_tuple(std::lround(v.position.x * 1e5), std::lround(v.position.y * 1e5),
                                         std::lround(v.position.z * 1e5));
        out.push_back(ids.emplace(key, int(ids.size())).first->second);
    }
    return out;
}

// Closed, consistently oriented surface: after welding, every directed edge
// a→b appears exactly once and its twin b→a exactly once.
void expect_closed(const Mesh& m) {
    const std::vector<int> p = weld(m);
    std::map<std::pair<int, int>, int> directed;
    for (size_t t = 0; t < triangle_count(m); ++t) {
        const int a = p[m.indices[3 * t]], b = p[m.indices[3 * t + 1]], c = p[m.indices[3 * t + 2]];
        ASSERT_TRUE(a != b && b != c && c != a) << "triangle " << t << " collapses after welding";
        ++directed[{a, b}];
        ++directed[{b, c}];
        ++directed[{c, a}];
    }
    int failures = 0;
    for (const auto& [edge, n] : directed) {
        const auto twin = directed.find({edge.second, edge.first});
        const int twins = twin == directed.end() ? 0 : twin->second;
        if ((n != 1 || twins != 1) && failures++ < 5) {
            ADD_FAILURE() << "edge " << edge.first << "->" << edge.second << " used " << n << "x, reverse " << twins
                          << "x";
        }
    }
}

// Signed volume by the divergence theorem: sum of the tetrahedra (origin, a, b, c).
double signed_volume(const Mesh& m) {
    double v = 0.0;
    for (size_t t = 0; t < triangle_count(m); ++t) {
        const glm::dvec3 a(m.vertices[m.indices[3 * t]].position), b(m.vertices[m.indices[3 * t + 1]].position),
            c(m.vertices[m.indices[3 * t + 2]].position);
        v += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return v;
}

// Each triangle: the vertex tangents point along +u, i.e. along ∂P/∂u
// solved from the triangle's positions and UVs.
void expect_tangents_follow_u(const Mesh& m) {
    int failures = 0;
    for (size_t t = 0; t < triangle_count(m) && failures < 5; ++t) {
        const Vertex &a = m.vertices[m.indices[3 * t]], &b = m.vertices[m.indices[3 * t + 1]],
                     &c = m.vertices[m.indices[3 * t + 2]];
        const glm::vec3 e1 = b.position - a.position, e2 = c.position - a.position;
        const glm::vec2 d1 = b.uv - a.uv, d2 = c.uv - a.uv;
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (std::abs(det) < 1e-9f) continue;
        const glm::vec3 dpdu = glm::normalize((d2.y * e1 - d1.y * e2) / det);
        for (const Vertex* v : {&a, &b, &c}) {
            if (!(glm::dot(glm::vec3(v->tangent), dpdu) > 0.5f)) {
                ++failures;
                ADD_FAILURE() << "triangle " << t << ": tangent does not follow +u";
            }
        }
    }
}

std::string load_error(const std::string& path) {
    try {
        (void)lab::load_obj(path, 60.0f, false);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

// ---------------------------------------------------------------------------
// Primitives
// ---------------------------------------------------------------------------

struct Primitive {
    std::string name;
    std::function<Mesh()> make;
    bool closed;
    double volume;         // analytic volume of the ideal shape (closed ones)
    double volume_tol;     // relative, for the default tessellation (an inscribed polygon's deficit:
                           // sphere 32×16 −1.6 %, cylinder/cone 32 −0.64 %, torus 48×16 −2.8 %)
    size_t triangles;      // expected count at the default tessellation
};
// How gtest prints a case (else it dumps the struct's bytes into every test name listing).
void PrintTo(const Primitive& p, std::ostream* os) { *os << p.name; }

const std::vector<Primitive>& primitives() {
    const double R = 0.35, r = 0.15;
    // Regular icosahedron with circumradius 0.5: edge a = 0.5 / sin(2π/5).
    const double a = 0.5 / std::sin(2.0 * kPi / 5.0);
    static const std::vector<Primitive> list = {
        {"plane", [] { return lab::make_plane(); }, false, 0.0, 0.0, 2},
        {"cube", [] { return lab::make_cube(); }, true, 1.0, 1e-6, 12},
        {"sphere", [] { return lab::make_sphere(); }, true, 4.0 / 3.0 * kPi * 0.125, 0.02, 2 * 32 * 15},
        {"icosahedron", [] { return lab::make_icosahedron(); }, true, 5.0 / 12.0 * (3.0 + std::sqrt(5.0)) * a * a * a,
         1e-5, 20},
        {"icosphere", [] { return lab::make_icosphere(); }, true, 4.0 / 3.0 * kPi * 0.125, 0.04, 320},
        {"cylinder", [] { return lab::make_cylinder(); }, true, kPi * 0.25, 0.01, 2 * 32 + 2 * 32},
        {"cone", [] { return lab::make_cone(); }, true, kPi * 0.25 / 3.0, 0.01, 2 * 32},
        {"torus", [] { return lab::make_torus(); }, true, 2.0 * kPi * kPi * R * r * r, 0.035, 2 * 48 * 16},
    };
    return list;
}

class PrimitiveTest : public ::testing::TestWithParam<Primitive> {};

TEST_P(PrimitiveTest, VerticesAreValid) {
    const Mesh m = GetParam().make();
    expect_valid_vertices(m, GetParam().name);
    expect_uvs_in_unit_square(m);
}

TEST_P(PrimitiveTest, WindingAgreesWithNormals) { expect_winding_matches_normals(GetParam().make()); }

TEST_P(PrimitiveTest, TangentsFollowUAndAreNotMirrored) {
    const Mesh m = GetParam().make();
    expect_tangents_follow_u(m);
    for (const Vertex& v : m.vertices) ASSERT_EQ(v.tangent.w, 1.0f) << "primitives map textures unmirrored";
}

TEST_P(PrimitiveTest, ClosedWithAnalyticVolume) {
    const Primitive& p = GetParam();
    const Mesh m = p.make();
    if (!p.closed) {
        EXPECT_NEAR(signed_volume(m), 0.0, 1e-9);
        return;
    }
    expect_closed(m);
    const double v = signed_volume(m);
    EXPECT_GT(v, 0.0) << "inside out";
    EXPECT_NEAR(v, p.volume, p.volume * p.volume_tol) << p.name;
}

TEST_P(PrimitiveTest, DefaultTriangleCount) { EXPECT_EQ(triangle_count(GetParam().make()), GetParam().triangles); }

TEST_P(PrimitiveTest, MakeMeshByNameMatches) {
    lab::ObjectDesc o;
    o.mesh = GetParam().name;
    const Mesh m = lab::make_mesh(o);
    EXPECT_EQ(m.indices, GetParam().make().indices);
    EXPECT_EQ(m.vertices.size(), GetParam().make().vertices.size());
}

// Fits in the unit cube around the origin (all primitives are "size 1").
TEST_P(PrimitiveTest, FitsUnitBox) {
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const Vertex& v : GetParam().make().vertices) {
        lo = glm::min(lo, v.position);
        hi = glm::max(hi, v.position);
    }
    for (int k = 0; k < 3; ++k) {
        EXPECT_GE(lo[k], -0.5f - 1e-6f);
        EXPECT_LE(hi[k], 0.5f + 1e-6f);
    }
}

INSTANTIATE_TEST_SUITE_P(All, PrimitiveTest, ::testing::ValuesIn(primitives()),
                         [](const auto& info) { return info.param.name; });

TEST(Primitives, EveryNameTheSceneLoaderAcceptsIsBuilt) {
    for (const std::string& name : lab::primitive_mesh_names()) {
        lab::ObjectDesc o;
        o.mesh = name;
        EXPECT_NO_THROW(expect_valid_vertices(lab::make_mesh(o), name)) << name;
    }
    lab::ObjectDesc bad;
    bad.mesh = "teapot";
    EXPECT_THROW(lab::make_mesh(bad), std::runtime_error);
}

TEST(Primitives, PlaneIsUnitSquareFacingUp) {
    const Mesh m = lab::make_plane();
    ASSERT_EQ(m.vertices.size(), 4u);
    for (const Vertex& v : m.vertices) {
        EXPECT_EQ(v.position.y, 0.0f);
        EXPECT_EQ(std::abs(v.position.x), 0.5f);
        EXPECT_EQ(std::abs(v.position.z), 0.5f);
        EXPECT_EQ(v.normal, glm::vec3(0, 1, 0));
        // u along +X, v along +Z (the image top is at −Z seen from above)
        EXPECT_FLOAT_EQ(v.uv.x, v.position.x + 0.5f);
        EXPECT_FLOAT_EQ(v.uv.y, v.position.z + 0.5f);
    }
}

TEST(Primitives, CubeHasHardEdges) {
    const Mesh m = lab::make_cube();
    ASSERT_EQ(m.vertices.size(), 24u);
    std::set<std::tuple<float, float, float>> normals;
    for (const Vertex& v : m.vertices) {
        normals.insert({v.normal.x, v.normal.y, v.normal.z});
        // a face normal: the position's largest coordinate is ±0.5 along it
        EXPECT_FLOAT_EQ(glm::dot(v.position, v.normal), 0.5f);
    }
    EXPECT_EQ(normals.size(), 6u);
}

// Sphere-like shapes: normals point away from the centre (for the torus: away
// from the centre line of the tube).
TEST(Primitives, NormalsPointOutward) {
    for (const auto& [name, mesh] : std::vector<std::pair<std::string, Mesh>>{
             {"sphere", lab::make_sphere()}, {"icosphere", lab::make_icosphere()},
             {"icosahedron", lab::make_icosahedron()}, {"cube", lab::make_cube()},
             {"cylinder", lab::make_cylinder()}, {"cone", lab::make_cone()}}) {
        for (const Vertex& v : mesh.vertices) ASSERT_GT(glm::dot(v.normal, v.position), 0.0f) << name;
    }
    for (const Vertex& v : lab::make_torus().vertices) {
        const glm::vec3 ring = 0.35f * glm::normalize(glm::vec3(v.position.x, 0.0f, v.position.z));
        ASSERT_GT(glm::dot(v.normal, v.position - ring), 0.0f);
        EXPECT_NEAR(glm::length(v.position - ring), 0.15f, 1e-5f);
    }
}

TEST(Primitives, SphereAndIcosphereLieOnRadius) {
    for (const Mesh& m : {lab::make_sphere(), lab::make_icosphere(), lab::make_icosphere(4), lab::make_icosahedron()}) {
        for (const Vertex& v : m.vertices) ASSERT_NEAR(glm::length(v.position), 0.5f, 1e-5f);
    }
    for (const Vertex& v : lab::make_sphere().vertices) {
        EXPECT_NEAR(glm::dot(v.normal, glm::normalize(v.position)), 1.0f, 1e-5f);
    }
}

TEST(Primitives, TessellationControlsTriangleCount) {
    // Through make_mesh, as a scene file sets them.
    const auto count = [](const std::string& name, int segments, int rings) {
        lab::ObjectDesc o;
        o.mesh = name;
        o.segments = segments;
        o.rings = rings;
        return triangle_count(lab::make_mesh(o));
    };
    EXPECT_EQ(count("sphere", 8, 5), 2u * 8 * (5 - 1));
    EXPECT_EQ(count("cylinder", 7, 3), 2u * 7 * 3 + 2 * 7);
    EXPECT_EQ(count("cone", 9, 4), 2u * 9 * 4);
    EXPECT_EQ(count("torus", 10, 6), 2u * 10 * 6);
    EXPECT_EQ(count("icosphere", 3, 0), 20u * 64);  // level 3
    EXPECT_EQ(count("icosphere", 0, 0), 320u);      // default level 2
    for (int level = 0; level <= 4; ++level) {
        EXPECT_EQ(triangle_count(lab::make_icosphere(level)), 20u << (2 * level));
    }
    // Out-of-range values passed directly are clamped to sane limits.
    EXPECT_EQ(triangle_count(lab::make_sphere(1, 1)), 2u * 3 * (2 - 1));
    EXPECT_EQ(triangle_count(lab::make_icosphere(99)), 20u << 14);
    EXPECT_EQ(triangle_count(lab::make_cylinder(2000, 1)), 2u * 1024 + 2 * 1024);
}

TEST(Primitives, NonDefaultTessellationsStayValid) {
    for (const Mesh& m : {lab::make_sphere(3, 2), lab::make_sphere(5, 3), lab::make_cylinder(3, 1),
                          lab::make_cylinder(5, 4), lab::make_cone(3, 1), lab::make_cone(6, 5),
                          lab::make_torus(3, 3), lab::make_icosphere(0), lab::make_icosphere(3)}) {
        expect_valid_vertices(m, "tessellation");
        expect_winding_matches_normals(m);
        expect_closed(m);
        expect_uvs_in_unit_square(m);
        EXPECT_GT(signed_volume(m), 0.0);
    }
}

TEST(Primitives, VolumesConvergeWithTessellation) {
    EXPECT_NEAR(signed_volume(lab::make_sphere(256, 128)), 4.0 / 3.0 * kPi * 0.125, 0.0005);
    EXPECT_NEAR(signed_volume(lab::make_icosphere(5)), 4.0 / 3.0 * kPi * 0.125, 0.001);
    EXPECT_NEAR(signed_volume(lab::make_cylinder(512, 1)), kPi * 0.25, 0.0001);
    EXPECT_NEAR(signed_volume(lab::make_cone(512, 2)), kPi * 0.25 / 3.0, 0.0001);
    EXPECT_NEAR(signed_volume(lab::make_torus(256, 128)), 2.0 * kPi * kPi * 0.35 * 0.15 * 0.15, 0.0002);
}

// Cylinder and cone rims are hard edges: each point on a rim carries both the
// side normal and the cap normal, on separate vertices.
TEST(Primitives, RimsAreHardEdges) {
    for (const auto& [name, m] : std::vector<std::pair<std::string, Mesh>>{{"cylinder", lab::make_cylinder(16, 1)},
                                                                          {"cone", lab::make_cone(16, 1)}}) {
        int rim_cap = 0, rim_side = 0;
        for (const Vertex& v : m.vertices) {
            if (std::abs(v.position.y + 0.5f) > 1e-6f || std::abs(glm::length(glm::vec2(v.position.x, v.position.z)) - 0.5f) > 1e-5f) continue;
            if (v.normal == glm::vec3(0, -1, 0)) ++rim_cap;
            else if (v.normal.y > -0.9f) ++rim_side;
        }
        EXPECT_EQ(rim_cap, 16) << name;
        EXPECT_EQ(rim_side, 17) << name;  // + the duplicated seam vertex
    }
}

TEST(Primitives, ConeApexHasOneVertexPerSegmentWithMidNormal) {
    const int segments = 12;
    const Mesh m = lab::make_cone(segments, 1);
    int apex = 0;
    std::set<std::tuple<float, float, float>> normals;
    for (const Vertex& v : m.vertices) {
        if (glm::length(v.position - glm::vec3(0, 0.5f, 0)) > 1e-6f) continue;
        ++apex;
        normals.insert({v.normal.x, v.normal.y, v.normal.z});
        // slanted side normal: (radial, y) ∝ (1, 0.5)
        EXPECT_NEAR(v.normal.y, 1.0f / std::sqrt(5.0f), 1e-5f);
    }
    EXPECT_EQ(apex, segments);
    EXPECT_EQ(normals.size(), size_t(segments));
}

// ---------------------------------------------------------------------------
// OBJ loading
// ---------------------------------------------------------------------------

const char* kCubeNoNormals = R"(# unit cube, quads, no normals
v -0.5 -0.5 -0.5
v  0.5 -0.5 -0.5
v  0.5  0.5 -0.5
v -0.5  0.5 -0.5
v -0.5 -0.5  0.5
v  0.5 -0.5  0.5
v  0.5  0.5  0.5
v -0.5  0.5  0.5
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 4 8 7 3
f 1 5 8 4
f 2 3 7 6
)";

TEST(ObjLoader, QuadWithNormalsAndUvs) {
    TempDir dir;
    const std::string path = dir.write("quad.obj", R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
f 1/1/1 2/2/1 3/3/1 4/4/1
)");
    const lab::LoadedModel model = lab::load_obj(path, 60.0f, false);
    const Mesh& m = model.mesh;
    expect_valid_vertices(m, "quad");
    EXPECT_EQ(triangle_count(m), 2u);
    EXPECT_EQ(m.vertices.size(), 4u);
    expect_winding_matches_normals(m);
    expect_tangents_follow_u(m);
    for (const Vertex& v : m.vertices) {
        EXPECT_EQ(v.normal, glm::vec3(0, 0, 1));
        // OBJ's v = 0 is the image bottom; here v = 0 is the top row.
        EXPECT_FLOAT_EQ(v.uv.x, v.position.x);
        EXPECT_FLOAT_EQ(v.uv.y, 1.0f - v.position.y);
        EXPECT_NEAR(v.tangent.x, 1.0f, 1e-6f);  // +u = +X
        EXPECT_EQ(v.tangent.w, 1.0f);           // not mirrored
    }
    EXPECT_EQ(model.triangle_material, std::vector<int>(2, -1));
}

TEST(ObjLoader, PolygonsOfAnySizeIncludingConcave) {
    TempDir dir;
    // A convex hexagon and a concave L shape (6 corners), both in z = 0.
    const std::string path = dir.write("ngon.obj", R"(v 1 0 0
v 0.5 0.866 0
v -0.5 0.866 0
v -1 0 0
v -0.5 -0.866 0
v 0.5 -0.866 0
f 1 2 3 4 5 6
v 10 0 0
v 12 0 0
v 12 1 0
v 11 1 0
v 11 2 0
v 10 2 0
f 7 8 9 10 11 12
)");
    const Mesh m = lab::load_obj(path, 60.0f, false).mesh;
    expect_valid_vertices(m, "ngon");
    EXPECT_EQ(triangle_count(m), 4u + 4u);
    expect_winding_matches_normals(m);
    // Triangulation must cover each polygon exactly: total area = hexagon + L.
    double area = 0.0;
    for (size_t t = 0; t < triangle_count(m); ++t) {
        const glm::vec3 a = m.vertices[m.indices[3 * t]].position, b = m.vertices[m.indices[3 * t + 1]].position,
                        c = m.vertices[m.indices[3 * t + 2]].position;
        area += 0.5 * glm::cross(b - a, c - a).z;
    }
    EXPECT_NEAR(area, 3.0 * std::sqrt(3.0) / 2.0 + 3.0, 1e-3);
}

TEST(ObjLoader, NegativeIndicesMatchPositiveOnes) {
    TempDir dir;
    const std::string pos = dir.write("pos.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nf 1/1 2/1 3/2 4/2\n");
    const std::string neg = dir.write("neg.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nf -4/-2 -3/-2 -2/-1 -1/-1\n");
    const Mesh a = lab::load_obj(pos, 60.0f, false).mesh, b = lab::load_obj(neg, 60.0f, false).mesh;
    ASSERT_EQ(a.indices, b.indices);
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    for (size_t i = 0; i < a.vertices.size(); ++i) {
        EXPECT_EQ(a.vertices[i].position, b.vertices[i].position);
        EXPECT_EQ(a.vertices[i].uv, b.vertices[i].uv);
    }
}

TEST(ObjLoader, GroupsObjectsAndMaterials) {
    TempDir dir;
    dir.write("two.mtl", R"(newmtl red
Kd 1 0 0
Ks 0.5 0.5 0.5
Ns 64
Ke 0 0 0.25
map_Kd tex/red.png
newmtl blue
Kd 0 0 1
map_Kd missing.png
)");
    fs::create_directories(dir.path() / "tex");
    dir.write("tex/red.png", "not really a png");
    const std::string path = dir.write("two.obj", R"(mtllib two.mtl
o first
v 0 0 0
v 1 0 0
v 0 1 0
g a
usemtl red
f 1 2 3
o second
v 0 0 1
v 1 0 1
v 0 1 1
v 1 1 1
g b
usemtl blue
f 4 5 7 6
g c
usemtl nothere
f 4 5 6
)");
    testing::internal::CaptureStderr();
    const lab::LoadedModel model = lab::load_obj(path, 60.0f, false);
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(triangle_count(model.mesh), 4u);
    ASSERT_EQ(model.materials.size(), 2u);
    const lab::ObjMaterial& red = model.materials[0];
    EXPECT_EQ(red.name, "red");
    EXPECT_EQ(red.albedo, glm::vec3(1, 0, 0));
    EXPECT_EQ(red.specular, glm::vec3(0.5f));
    EXPECT_EQ(red.shininess, 64.0f);
    EXPECT_EQ(red.emissive, glm::vec3(0, 0, 0.25f));
    EXPECT_EQ(fs::path(red.albedo_texture), (dir.path() / "tex/red.png").lexically_normal());
    EXPECT_EQ(model.materials[1].albedo_texture, "");  // missing: warning + Kd only
    EXPECT_EQ(model.triangle_material, (std::vector<int>{0, 1, 1, -1}));
    EXPECT_NE(err.find("warning: " + path + ": texture 'missing.png'"), std::string::npos) << err;
    EXPECT_NE(err.find("nothere"), std::string::npos) << err;
}

TEST(ObjLoader, MissingMtlIsAWarning) {
    TempDir dir;
    const std::string path = dir.write("m.obj", "mtllib gone.mtl\nusemtl x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    testing::internal::CaptureStderr();
    const lab::LoadedModel model = lab::load_obj(path, 60.0f, false);
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(triangle_count(model.mesh), 1u);
    EXPECT_TRUE(model.materials.empty());
    EXPECT_EQ(model.triangle_material, std::vector<int>{-1});  // the scene material
    EXPECT_NE(err.find("warning: " + path + ": material library 'gone.mtl'"), std::string::npos) << err;
    EXPECT_FALSE(model.warnings.empty());
    for (const std::string& w : model.warnings) EXPECT_EQ(w.find('\n'), std::string::npos);
}

// The crease angle: a cube without normals gets 6 flat faces (90° > 60°: every
// corner is cloned per face), a smooth shape stays smooth.
TEST(ObjLoader, CreaseSplitsCubeIntoFlatFaces) {
    TempDir dir;
    const std::string path = dir.write("cube.obj", kCubeNoNormals);
    const Mesh m = lab::load_obj(path, 60.0f, false).mesh;
    expect_valid_vertices(m, "cube");
    EXPECT_EQ(m.vertices.size(), 24u);
    std::set<std::tuple<float, float, float>> normals;
    for (const Vertex& v : m.vertices) normals.insert({v.normal.x, v.normal.y, v.normal.z});
    EXPECT_EQ(normals.size(), 6u);
    expect_winding_matches_normals(m);
    expect_closed(m);
    EXPECT_NEAR(signed_volume(m), 1.0, 1e-6);

    // Crease 180°: everything smooth, one vertex per corner, normals close to
    // the diagonals (not exactly: area weighting counts the face whose two
    // triangles meet at this corner twice as much as the others).
    const Mesh smooth = lab::load_obj(path, 180.0f, false).mesh;
    EXPECT_EQ(smooth.vertices.size(), 8u);
    for (const Vertex& v : smooth.vertices) {
        EXPECT_GT(glm::dot(v.normal, glm::normalize(v.position)), 0.95f);
    }
}

TEST(ObjLoader, CreaseKeepsGentleAnglesSmooth) {
    // A 16-sided prism without normals: 22.5° between side faces (smooth at
    // 60°), 90° between sides and caps (hard).
    std::ostringstream obj;
    const int n = 16;
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * kPi * i / n;
        obj << "v " << std::cos(a) << " 0 " << -std::sin(a) << "\n";
        obj << "v " << std::cos(a) << " 1 " << -std::sin(a) << "\n";
    }
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        obj << "f " << 2 * i + 1 << " " << 2 * j + 1 << " " << 2 * j + 2 << " " << 2 * i + 2 << "\n";
    }
    obj << "f";
    for (int i = n - 1; i >= 0; --i) obj << " " << 2 * i + 1;
    obj << "\nf";
    for (int i = 0; i < n; ++i) obj << " " << 2 * i + 2;
    obj << "\n";
    TempDir dir;
    const Mesh m = lab::load_obj(dir.write("prism.obj", obj.str()), 60.0f, false).mesh;
    expect_valid_vertices(m, "prism");
    expect_winding_matches_normals(m);
    expect_closed(m);
    // 2n side vertices (smooth: one per corner, horizontal, nearly radial
    // normals) + 2n cap vertices (exactly ±Y).
    EXPECT_EQ(m.vertices.size(), size_t(4 * n));
    for (const Vertex& v : m.vertices) {
        if (std::abs(v.normal.y) < 0.5f) {
            EXPECT_NEAR(v.normal.y, 0.0f, 1e-6f);
            EXPECT_GT(glm::dot(v.normal, glm::normalize(glm::vec3(v.position.x, 0, v.position.z))), 0.99f);
        } else {
            EXPECT_EQ(std::abs(v.normal.y), 1.0f);
        }
    }
}

TEST(ObjLoader, NormalizeFitsUnitBox) {
    TempDir dir;
    const std::string path = dir.write("far.obj", "v 10 0 0\nv 14 0 0\nv 10 1 0\nv 10 0 2\nf 1 2 3\nf 1 4 2\n");
    const Mesh m = lab::load_obj(path, 60.0f, true).mesh;
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const Vertex& v : m.vertices) {
        lo = glm::min(lo, v.position);
        hi = glm::max(hi, v.position);
    }
    EXPECT_NEAR(hi.x - lo.x, 1.0f, 1e-6f);  // the largest side
    EXPECT_NEAR(hi.y - lo.y, 0.25f, 1e-6f);
    EXPECT_NEAR(hi.z - lo.z, 0.5f, 1e-6f);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(lo[k] + hi[k], 0.0f, 1e-6f);
    // make_mesh passes the scene options through.
    lab::ObjectDesc o;
    o.mesh = "far.obj";
    o.mesh_path = path;
    o.normalize = true;
    EXPECT_EQ(lab::make_mesh(o).vertices.size(), m.vertices.size());
    o.normalize = false;
    EXPECT_EQ(lab::make_mesh(o).vertices[0].position.x, 10.0f);
}

TEST(ObjLoader, TangentsWithoutUvsArePerpendicular) {
    TempDir dir;
    const Mesh m = lab::load_obj(dir.write("c.obj", kCubeNoNormals), 60.0f, false).mesh;
    expect_valid_vertices(m, "no uv");  // unit tangents ⟂ normals even without UVs
}

// Each broken file gives one std::runtime_error line "FILE[:LINE]: reason".
TEST(ObjLoader, BrokenFilesAreRejectedWithOneLine) {
    TempDir dir;
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    struct Case { std::string name, text, line, reason; };
    const std::vector<Case> cases = {
        {"empty", "", "", "no faces"},
        {"only_comments", "# nothing\n\n", "", "no faces"},
        {"index0", tri + "f 0 1 2\n", ":4:", "index 0"},
        {"index_high", tri + "f 1 2 4\n", ":4:", "out of range"},
        {"index_neg", tri + "f -1 -2 -4\n", ":4:", "out of range"},
        {"index_huge", tri + "f 1 2 99999999999999999999\n", ":4:", "bad index"},
        {"uv_index_high", tri + "vt 0 0\nf 1/1 2/2 3/1\n", ":5:", "texture coordinate index 2 out of range"},
        {"normal_index_high", tri + "f 1//1 2//1 3//1\n", ":4:", "normal index 1 out of range"},
        {"forward_reference", "f 1 2 3\n" + tri, ":1:", "out of range"},
        {"nan", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", ":2:", "non-finite"},
        {"inf", "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n", ":2:", "non-finite"},
        {"overflow", "v 0 0 0\nv 1 1e400 0\nv 0 1 0\nf 1 2 3\n", ":2:", "non-finite"},
        {"huge", "v 0 0 0\nv 1e30 0 0\nv 0 1 0\nf 1 2 3\n", ":2:", "too large"},
        {"two_vertices", tri + "f 1 2\n", ":4:", "face with 2 vertices"},
        {"empty_face", tri + "f\n", ":4:", "face with 0 vertices"},
        {"truncated_vertex", "v 0 0 0\nv 1 0 0\nv 0 1", ":3:", "truncated"},
        {"truncated_face", tri + "f 1 2", ":4:", "face with 2 vertices"},
        {"truncated_number", "v 0 0 0\nv 1 0 0\nv 0 1 0.\nf 1 2 3\nv 0 0 1e", ":5:", "bad number"},
        {"bad_number", "v 0 0 0\nv 1 0x 0\nv 0 1 0\nf 1 2 3\n", ":2:", "bad number"},
        {"bad_vertex_ref", tri + "f 1/2/3/4 2 3\n", ":4:", "bad face vertex"},
        {"binary", std::string("v 0 0 0\n\x7f" "ELF\x02\x01\x01\0\0\0", 18), ":2:", "binary"},
        {"nul_bytes", std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\n\0\0\0\0f 1 2 3\n", 36), ":4:", "binary"},
        {"utf16", std::string("\xff\xfev\0 \0" "1\0", 8), ":1:", "UTF-16"},
        {"huge_polygon", tri + "f" + [] { std::string f; for (int i = 0; i < 5000; ++i) f += " " + std::to_string(1 + i % 3); return f; }() + "\n", ":4:", "limit 4096"},
        {"points_only", tri + "p 1 2 3\n", "", "no faces"},
        {"degenerate_only", tri + "f 1 1 2\nf 1 2 1\n", "", "no faces"},
    };
    testing::internal::CaptureStderr();  // the warnings of these are not the point here
    for (const Case& c : cases) {
        const std::string path = dir.write(c.name + ".obj", c.text);
        const std::string msg = load_error(path);
        EXPECT_FALSE(msg.empty()) << c.name << " was accepted";
        EXPECT_EQ(msg.find('\n'), std::string::npos) << c.name << ": " << msg;
        EXPECT_EQ(msg.rfind(path + c.line, 0), 0u) << c.name << ": " << msg;
        EXPECT_NE(msg.find(c.reason), std::string::npos) << c.name << ": " << msg;
    }
    (void)testing::internal::GetCapturedStderr();
    // Not a file at all.
    EXPECT_NE(load_error((dir.path() / "nope.obj").string()).find("not found"), std::string::npos);
    EXPECT_NE(load_error(dir.path().string()).find("not a regular file"), std::string::npos);
    lab::ObjectDesc o;
    o.mesh = o.mesh_path = dir.write("model.stl", "solid x\n");
    EXPECT_THROW(lab::make_mesh(o), std::runtime_error);
}

// Random damage to a valid file: whatever comes out is either a valid mesh or
// a one-line runtime_error, never a crash or a hang (run it under ASan too).
TEST(ObjLoader, RandomlyDamagedFilesNeverCrash) {
    TempDir dir;
    std::ostringstream base;
    base << "mtllib none.mtl\n" << kCubeNoNormals << "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n"
         << "f -1 -2 -3 -4\ng grp\nf 1/1 2/2 3/3 4/1\n";
    const std::string good = base.str();
    static const char kAlphabet[] = "0123456789-+./ \n\tfvtn#e\0\xff";
    const std::string alphabet(kAlphabet, sizeof kAlphabet - 1);
    std::mt19937 rng(12345);
    int accepted = 0, rejected = 0;
    testing::internal::CaptureStderr();
    for (int iter = 0; iter < 400; ++iter) {
        std::string text = good;
        const int edits = 1 + int(rng() % 6);
        for (int e = 0; e < edits; ++e) {
            const size_t at = rng() % text.size();
            switch (rng() % 4) {
                case 0: text[at] = alphabet[rng() % alphabet.size()]; break;
                case 1: text.erase(at, 1 + rng() % 8); break;
                case 2: text.insert(at, 1, alphabet[rng() % alphabet.size()]); break;
                default: text.resize(at); break;  // truncate
            }
            if (text.empty()) text = "f";
        }
        const std::string path = dir.write("fuzz.obj", text);
        try {
            const Mesh m = lab::load_obj(path, 60.0f, iter % 2 == 0).mesh;
            expect_valid_vertices(m, "fuzz " + std::to_string(iter));
            ++accepted;
        } catch (const std::runtime_error& e) {
            const std::string msg = e.what();
            EXPECT_FALSE(msg.empty());
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
            ++rejected;
        }
    }
    (void)testing::internal::GetCapturedStderr();
    std::printf("damaged files: %d loaded, %d rejected\n", accepted, rejected);
    EXPECT_GT(accepted, 0);
    EXPECT_GT(rejected, 0);
}

// A big generated grid: de-duplication keeps it indexed and it loads fast.
TEST(ObjLoader, LargeModelLoadsIndexedAndFast) {
    const int n = 300;  // 300×300 quads = 180k triangles
    std::string text;
    text.reserve(size_t(n + 1) * (n + 1) * 40);
    char buf[96];
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            std::snprintf(buf, sizeof buf, "v %d %.4f %d\n", i, 0.3 * std::sin(i * 0.1) * std::cos(j * 0.1), -j);
            text += buf;
        }
    }
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 2, d = a + n + 1;
            std::snprintf(buf, sizeof buf, "f %d %d %d %d\n", a, b, c, d);
            text += buf;
        }
    }
    TempDir dir;
    const std::string path = dir.write("grid.obj", text);
    const auto t0 = std::chrono::steady_clock::now();
    const Mesh m = lab::load_obj(path, 60.0f, true).mesh;
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(triangle_count(m), size_t(2 * n * n));
    EXPECT_EQ(m.vertices.size(), size_t(n + 1) * (n + 1));  // smooth: one vertex per grid point
    expect_winding_matches_normals(m);
    std::printf("grid %dx%d: %zu triangles, %zu vertices, loaded in %.0f ms\n", n, n, triangle_count(m),
                m.vertices.size(), ms);
    EXPECT_LT(ms, 60000.0);
}

// The model that ships with the scenes (scripts/make_model.py).
TEST(ObjLoader, ShippedPawnModel) {
    const std::string path = std::string(LAB_SOURCE_DIR) + "/scenes/models/pawn.obj";
    if (!fs::exists(path)) GTEST_SKIP() << path << " not generated";
    testing::internal::CaptureStderr();
    const lab::LoadedModel model = lab::load_obj(path, 60.0f, false);
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_TRUE(err.empty()) << err;
    const Mesh& m = model.mesh;
    expect_valid_vertices(m, "pawn");
    expect_winding_matches_normals(m);
    expect_closed(m);
    EXPECT_GT(signed_volume(m), 0.0);
    ASSERT_EQ(model.materials.size(), 1u);
    EXPECT_EQ(model.triangle_material, std::vector<int>(triangle_count(m), 0));
    // Hard edge at the bottom rim: the same point has the down-facing cap
    // normal and the horizontal side normal.
    int down = 0, side = 0;
    for (const Vertex& v : m.vertices) {
        if (std::abs(v.position.y) > 1e-6f || glm::length(glm::vec2(v.position.x, v.position.z)) < 0.49f) continue;
        if (v.normal.y < -0.99f) ++down;
        if (std::abs(v.normal.y) < 0.01f) ++side;
    }
    EXPECT_GT(down, 0);
    EXPECT_GT(side, 0);
}

// ---------------------------------------------------------------------------
// Every .obj of the assimp-testmodels package: valid ones load into finite,
// non-empty meshes with unit normals, broken ones are rejected with a one-line
// message. The table printed here is copied into docs/meshes.md.
// ---------------------------------------------------------------------------
TEST(AssimpSweep, EveryObjLoadsOrIsRejectedCleanly) {
    const fs::path root = "/usr/share/assimp/models";
    if (!fs::is_directory(root)) GTEST_SKIP() << root << " missing (apt install assimp-testmodels)";
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(root)) {
        std::string ext = e.path().extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        if (e.is_regular_file() && ext == ".obj") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    ASSERT_FALSE(files.empty());

    std::printf("| file | result |\n|---|---|\n");
    std::set<std::string> loaded;
    fs::path biggest;
    std::uintmax_t biggest_size = 0;
    for (const fs::path& file : files) {
        const std::string rel = fs::relative(file, root).string();
        testing::internal::CaptureStderr();
        try {
            const lab::LoadedModel model = lab::load_obj(file.string(), 60.0f, false);
            const std::string warnings = testing::internal::GetCapturedStderr();
            expect_valid_vertices(model.mesh, rel);
            EXPECT_EQ(model.triangle_material.size(), triangle_count(model.mesh));
            std::printf("| %s | loaded: %zu triangles, %zu vertices%s |\n", rel.c_str(), triangle_count(model.mesh),
                        model.mesh.vertices.size(),
                        model.warnings.empty() ? "" : (", " + std::to_string(model.warnings.size()) + " warning(s)").c_str());
            loaded.insert(rel);
            if (fs::file_size(file) > biggest_size) {
                biggest_size = fs::file_size(file);
                biggest = file;
            }
        } catch (const std::runtime_error& e) {
            (void)testing::internal::GetCapturedStderr();
            const std::string msg = e.what();
            EXPECT_FALSE(msg.empty()) << rel;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << rel;
            EXPECT_EQ(msg.rfind(file.string(), 0), 0u) << msg;
            // "FILE:LINE: reason" -> "line LINE: reason", "FILE: reason" -> "reason"
            std::string reason = msg.substr(std::min(msg.size(), file.string().size() + 1));
            if (!reason.empty() && std::isdigit(static_cast<unsigned char>(reason[0]))) reason = "line " + reason;
            else if (reason.rfind(' ', 0) == 0) reason.erase(0, 1);
            std::printf("| %s | rejected: %s |\n", rel.c_str(), reason.c_str());
        }
    }
    // Known-good models must load; the "invalid" folder must not.
    for (const char* good : {"OBJ/box.obj", "OBJ/spider.obj", "OBJ/WusonOBJ.obj", "OBJ/regr01.obj", "OBJ/concave_polygon.obj"}) {
        if (fs::exists(root / good)) {
            EXPECT_EQ(loaded.count(good), 1u) << good;
        }
    }
    for (const std::string& rel : loaded) EXPECT_NE(rel.rfind("invalid/", 0), 0u) << rel << " should be rejected";

    // Load time and memory of the biggest one.
    ASSERT_FALSE(biggest.empty());
    testing::internal::CaptureStderr();
    const auto t0 = std::chrono::steady_clock::now();
    const Mesh m = lab::load_obj(biggest.string(), 60.0f, false).mesh;
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    (void)testing::internal::GetCapturedStderr();
    const size_t bytes = m.vertices.size() * sizeof(Vertex) + m.indices.size() * sizeof(uint32_t);
    std::printf("biggest: %s (%ju bytes): %zu triangles, %zu vertices, loaded in %.1f ms, "
                "vertex+index memory %zu bytes (%.1f KiB)\n",
                fs::relative(biggest, root).c_str(), biggest_size, triangle_count(m), m.vertices.size(), ms, bytes,
                bytes / 1024.0);
}

}  // namespace
