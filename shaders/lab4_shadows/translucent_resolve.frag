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
// list is longer composes its K nearest in colour and keeps the farther ones' (1 − α) (their
// colour is dropped: they lie behind K others), and is counted as an overflow pixel.
layout(constant_id = 0) const uint K = 16;

// Everything read here was written by this pixel's own fragments (its list, count and optical
// depth: translucent_layers.glsl), which the render pass's by-region dependency orders before this
// shader (TranslucentLayers::resolve()): plain loads see their final values. Nothing global is read
// (the pool's counter `taken` is still being written by other pixels' fragments where the
// dependency is by region).
void main() {
    const uint pixel = layer_pixel();
    const uint fragments = heads[layer_stats.pixels + pixel];
    // The list comes in the order the fragments arrived: sort it by depth, keeping the K nearest
    // (insertion sort into a small local array; a list is a handful of layers), and the optical
    // depth of the rest (an integer sum: the same whatever the order).
    float depth[K];
    uint node_of[K];
    uint kept = 0, total = 0, dropped_optical = 0;
    // No list is longer than the pixel's fragments: the walk's bound. (Lanes that a scissor masks
    // off walked on, as if their loads read 0 — node 0's next again and again — until the driver's
    // loop limit: 100 ms a frame on lavapipe without a bound, about 1 ms with one.)
    uint node = heads[pixel];
    for (; total < fragments && node != LAYER_END; node = nodes[node].next) {
        ++total;
        const float z = nodes[node].depth;
        if (kept == K && z >= depth[K - 1]) {  // farther than the K kept: its colour dropped
            dropped_optical += optical_depth(unpackHalf2x16(nodes[node].color_ba).y);
            continue;
        }
        if (kept == K)  // full: it replaces the farthest kept, whose colour is dropped
            dropped_optical += optical_depth(unpackHalf2x16(nodes[node_of[K - 1]].color_ba).y);
        uint i = kept < K ? kept++ : K - 1;
        for (; i > 0 && depth[i - 1] > z; --i) {
            depth[i] = depth[i - 1];
            node_of[i] = node_of[i - 1];
        }
        depth[i] = z;
        node_of[i] = node;
    }
    if (total > K) atomicAdd(layer_stats.overflow_pixels, 1u);
    if (fragments == 0) discard;  // nothing translucent here: the opaque colour stays as it is

    if (total < fragments) {
        // The pool was full when some of this pixel's fragments came: which of them were lost
        // depends on the order the GPU ran them in. The pixel shows none of its layers' colour and
        // all of their opacity — the transmittance of every fragment it had, stored or not — so it
        // is the same every run, and never brighter than the exact composition C + T·behind.
        out_color = vec4(0.0, 0.0, 0.0, transmittance_of(heads[2u * layer_stats.pixels + pixel]));
        return;
    }
    vec3 C = vec3(0.0);
    float T = 1.0;  // how much of what is behind layer i still shows through the layers before it
    for (uint i = 0; i < kept; ++i) {
        const vec2 rg = unpackHalf2x16(nodes[node_of[i]].color_rg), ba = unpackHalf2x16(nodes[node_of[i]].color_ba);
        C += T * ba.y * vec3(rg, ba.x);
        T *= 1.0 - ba.y;
    }
    if (dropped_optical > 0u) T *= transmittance_of(dropped_optical);  // over K: the farther layers' Π(1 − α)
    out_color = vec4(C, T);
}
