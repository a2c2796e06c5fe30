// obj_model.cpp — load_obj: a Wavefront OBJ (+ .mtl) into an indexed Mesh with materials
// (docs/meshes.md has the rules).
//
// The file is parsed once, by tinyobjloader, which also triangulates polygons. It reads
// the text through an ObjLineGate (obj_text.h), which checks each line just before
// tinyobjloader reads it and refuses what tinyobjloader would silently misread. What
// tinyobjloader returns is then checked again here (finite coordinates, indices in range)
// before the normals (crease angle), the de-duplicated vertices and the tangents are made.
#include "obj_model.h"

#include "obj_text.h"
#include "vertex_welder.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <istream>
#include <limits>
#include <map>
#include <sstream>
#include <unordered_map>

namespace lab {
namespace {

using detail::fail;
using detail::quote;

constexpr size_t kMaxFanForCrease = 4096;  // see compute_crease_normals

// Collects warnings: printed once each to stderr as "warning: FILE: reason". While held
// (during the parse, see load_obj) they are kept but not printed yet.
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
        flush();
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
    void hold(bool on) {
        held_ = on;
        flush();
    }

private:
    void flush() {
        if (!print_ || held_) return;
        for (; printed_ < out_.size(); ++printed_) std::cerr << "warning: " << file_ << ": " << out_[printed_] << "\n";
    }

    std::string file_;
    std::vector<std::string>& out_;
    bool print_;
    bool held_ = false;
    size_t printed_ = 0;
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
        if (!detail::read_small_file(path, detail::kMaxMtlBytes, text, why)) {
            warnings_.add("material library " + quote(name) + ": " + why + "; using the scene material");
            return false;
        }
        for (unsigned char c : text) {
            if (detail::is_binary_byte(c)) {
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
    if (!detail::read_small_file(path, detail::kMaxObjBytes, text, why)) fail(path, 0, why);
    const size_t bom = text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;  // UTF-8: skipped

    // --- the one parse: tinyobjloader reads the text through the line gate, which checks
    // each line as it is read (obj_text.h). tinyobjloader triangulates polygons: quads
    // along the shorter diagonal, larger polygons by ear clipping ---
    detail::ObjLineGate gate(text.data() + bom, text.data() + text.size());
    std::istream in(&gate);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    const std::string dir = std::filesystem::path(path).parent_path().string();
    SafeMtlReader mtl_reader(dir.empty() ? "." : dir, warnings);
    // A file that fails a line check is an error, not a model: it prints only that error,
    // not the warnings about its .mtl that tinyobjloader gave on the way there.
    warnings.hold(true);
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &mtl_reader,
                                     /*triangulate=*/true, /*default_vcols_fallback=*/false);
    gate.check_rest();  // the lines after an early stop of tinyobjloader's own, if any
    if (gate.error_line() != 0) fail(path, gate.error_line(), gate.error());
    warnings.hold(false);
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
        if (!std::isfinite(attrib.vertices[i]) || std::abs(attrib.vertices[i]) > detail::kMaxCoordinate) {
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
    std::unordered_map<detail::VertexKey, uint32_t, detail::VertexKeyHash> point_id;
    std::vector<uint32_t> point_of(nv);
    for (size_t v = 0; v < nv; ++v) {
        Vertex probe{};
        probe.position = position(int(v));
        point_of[v] = point_id.try_emplace(detail::VertexKey(probe), uint32_t(point_id.size())).first->second;
    }
    std::vector<uint32_t> corner_point(corners.size());
    for (size_t c = 0; c < corners.size(); ++c) corner_point[c] = point_of[corners[c].v];
    bool capped = false;
    const std::vector<glm::vec3> smooth =
        compute_crease_normals(face_normal, corner_point, point_id.size(), crease_deg, capped);
    if (capped) warnings.add("points shared by more than 4096 triangles keep flat normals");

    // --- build the indexed mesh, one vertex per distinct (position, normal, uv) ---
    Mesh& mesh = model.mesh;
    detail::VertexWelder welder(mesh);
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

}  // namespace lab
