// translucent_layers.glsl — the per-pixel lists of translucent layers (lab4_shadows/translucent_layers.h):
// lit.frag built with TRANSLUCENT_LAYER appends each translucent fragment to its pixel's list,
// translucent_resolve.frag sorts and composes the lists. The buffers are set 0's bindings 10..13
// (after the shadow maps' 3..9); the C++ side is TranslucentLayers.

const uint LAYER_END = 0xFFFFFFFFu;  // an empty list, or the last node of one

// heads[y · width + x]: the node the pixel's list starts with (LAYER_END: none). Cleared with
// vkCmdFillBuffer before the pass.
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
} layer_stats;

uint layer_pixel() { return uint(gl_FragCoord.y) * layer_stats.width + uint(gl_FragCoord.x); }
