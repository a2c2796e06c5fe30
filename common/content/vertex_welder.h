// vertex_welder.h — merges bit-identical vertices while a mesh is built (internal to
// lab_content: the icosphere and the OBJ loader use it; not part of mesh.h).
#pragma once

#include "mesh.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <unordered_map>

namespace lab::detail {

// Exact-bits key of a vertex's position, normal and uv (−0 counts as +0). The tangent is
// left out: it is computed after welding.
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

// Adds `v` to the mesh unless an identical vertex exists; returns its index.
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

}  // namespace lab::detail
