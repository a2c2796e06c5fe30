// translucent_layers.glsl — the per-pixel lists of translucent layers (lab4_shadows/translucent_layers.h):
// lit.frag built with TRANSLUCENT_LAYER appends each translucent fragment to its pixel's list,
// translucent_resolve.frag sorts and composes the lists. The buffers are set 0's bindings 10..13
// (after the shadow maps' 3..9); the C++ side is TranslucentLayers.

const uint LAYER_END = 0xFFFFFFFFu;  // an empty list, or the last node of one

// Three words per pixel p = y · width + x, each array `pixels` long (cleared with vkCmdFillBuffer
// before the pass), written only by that pixel's fragments and read only by its resolve:
//   heads[p]:              the node its list starts with (LAYER_END: none);
//   heads[pixels + p]:     how many translucent fragments it had, stored or not;
//   heads[2·pixels + p]:   Σ optical_depth(α) of those fragments (below).
layout(std430, set = 0, binding = 10) buffer LayerHeads { uint heads[]; };

// One translucent fragment, 16 bytes: its linear colour and opacity as four halfs (packHalf2x16:
// about 3 significant digits, plenty for an 8-bit picture), its depth, the next node of its pixel.
struct LayerNode {
    uint color_rg;  // packHalf2x16(r, g)
    uint color_ba;  // packHalf2x16(b, α)
    float depth;    // gl_FragCoord.z: the nearest is the smallest
    uint next;      // the node appended before it to the same pixel, or LAYER_END
};
// The pool every pixel takes its nodes from: node i is taken by whichever fragment's atomicAdd on
// `taken` returned i. Its length (nodes.length()) is the pool's size.
layout(std430, set = 0, binding = 11) buffer LayerNodes { LayerNode nodes[]; };
layout(std430, set = 0, binding = 12) buffer LayerCounter { uint taken; };  // nodes handed out this frame (zeroed before the pass)

// Per frame in flight, host-visible: the frame's width (the host writes it) and what did not fit,
// counted here and read back by the host after the frame's fence.
layout(std430, set = 0, binding = 13) buffer LayerStats {
    uint width;            // pixels per row of heads[]
    uint overflow_pixels;  // pixels whose list held more layers than the resolve keeps (K)
    uint dropped;          // fragments not stored: the pool was full
    uint pixels;           // width · height: the length of each of heads[]'s three arrays
} layer_stats;

uint layer_pixel() { return uint(gl_FragCoord.y) * layer_stats.width + uint(gl_FragCoord.x); }

// −log2(1 − α) in fixed point, 1/4096 per unit: summed with integer atomics, the total does not
// depend on the order the fragments come in (a float product would, in its last bits), and
// exp2(−Σ / 4096) is the transmittance Π(1 − α). One layer counts at most 24 (1 − α ≥ 2⁻²⁴, black
// on an 8-bit screen), so a pixel's sum holds 43690 such layers before it wraps. Rounding: at most
// 2⁻¹³ in log2 per layer (0.01 % of the light).
const float OPTICAL_DEPTH_UNIT = 4096.0;
uint optical_depth(float alpha) {
    return uint(clamp(-log2(max(1.0 - alpha, 1.0 / 16777216.0)), 0.0, 24.0) * OPTICAL_DEPTH_UNIT + 0.5);
}
float transmittance_of(uint optical) { return exp2(-float(optical) / OPTICAL_DEPTH_UNIT); }
