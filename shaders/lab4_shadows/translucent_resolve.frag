#version 450
// translucent_resolve.frag — composes one pixel's translucent layers (translucent_layers.glsl) in
// depth order and blends them over the opaque picture (lab4_shadows/translucent_layers.h).
//
// The layers, nearest first, with colours c_i and opacities α_i, over the opaque colour d give
//   c = α₁c₁ + (1 − α₁)(α₂c₂ + (1 − α₂)(… + (1 − α_n)d)) = C + T·d,
//   C = Σ α_i c_i Π_{j<i} (1 − α_j),   T = Π (1 − α_i):
// "over", back to front, unrolled front to back. This shader outputs (C, T); the blend state adds
// C to T times what is in the colour attachment (src · 1 + dst · src.a), in linear RGB (the
// attachment is sRGB: the blend unit decodes, blends and encodes).
#extension GL_GOOGLE_include_directive : require
#include "translucent_layers.glsl"

layout(location = 0) out vec4 out_color;

// K: the most layers a pixel composes (TranslucentLayers::kMaxLayers, which sets it). A pixel whose
// list is longer keeps its K nearest and drops the farther ones (they are behind K others: usually
// all but invisible); it is counted as an overflow pixel.
layout(constant_id = 0) const uint K = 16;

void main() {
    // The list comes in the order the fragments arrived: sort it by depth, keeping the K nearest
    // (insertion sort into a small local array; a list is a handful of layers).
    float depth[K];
    uint node_of[K];
    uint kept = 0, total = 0;
    // No list is longer than the nodes taken this frame: the walk's bound. Without one the walk
    // cost 100 ms a frame on lavapipe (the default scene), as if the lanes of pixel blocks that the
    // scissor masks off walked on until the driver's loop limit: their loads read 0, and node 0's
    // next again and again. With it: about 1 ms.
    const uint most = min(taken, uint(nodes.length()));
    uint node = heads[layer_pixel()];
    for (; total < most && node != LAYER_END; node = nodes[node].next) {
        ++total;
        const float z = nodes[node].depth;
        if (kept == K && z >= depth[K - 1]) continue;  // farther than the K kept: dropped
        uint i = kept < K ? kept++ : K - 1;             // full: it replaces the farthest kept
        for (; i > 0 && depth[i - 1] > z; --i) {
            depth[i] = depth[i - 1];
            node_of[i] = node_of[i - 1];
        }
        depth[i] = z;
        node_of[i] = node;
    }
    if (total > K) atomicAdd(layer_stats.overflow_pixels, 1u);
    if (kept == 0) discard;  // nothing translucent here: the opaque colour stays as it is

    vec3 C = vec3(0.0);
    float T = 1.0;  // how much of what is behind layer i still shows through the layers before it
    for (uint i = 0; i < kept; ++i) {
        const vec2 rg = unpackHalf2x16(nodes[node_of[i]].color_rg), ba = unpackHalf2x16(nodes[node_of[i]].color_ba);
        C += T * ba.y * vec3(rg, ba.x);
        T *= 1.0 - ba.y;
    }
    out_color = vec4(C, T);
}
