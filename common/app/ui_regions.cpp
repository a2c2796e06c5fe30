#include "ui_regions.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>

namespace lab {

namespace {

bool overlap(const PixelRect& a, const PixelRect& b) {
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

PixelRect bounding_box(const PixelRect& a, const PixelRect& b) {
    return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

// Framebuffer pixels from display coordinates. `outward`: every pixel the rectangle touches;
// otherwise only the pixels it covers whole. Clamped to the framebuffer.
struct ToPixels {
    ImVec2 origin, scale;
    int32_t width, height;
    PixelRect operator()(float x0, float y0, float x1, float y1, bool outward) const {
        const auto px = [&](float v, float o, float s) { return (v - o) * s; };
        const auto lo = [&](float v) { return int32_t(outward ? std::floor(v) : std::ceil(v)); };
        const auto hi = [&](float v) { return int32_t(outward ? std::ceil(v) : std::floor(v)); };
        PixelRect r;
        r.x0 = std::max(0, lo(px(x0, origin.x, scale.x)));
        r.y0 = std::max(0, lo(px(y0, origin.y, scale.y)));
        r.x1 = std::min(width, hi(px(x1, origin.x, scale.x)));
        r.y1 = std::min(height, hi(px(y1, origin.y, scale.y)));
        return r;
    }
};

// The opaque rectangles a draw list starts with (a window's background, then its title bar), each
// as ImDrawList::PrimRect writes it: 4 corners (x0,y0) (x1,y0) (x1,y1) (x0,y1), indices 0 1 2 0 2 3,
// the white texel, alpha 255 — in the list's first command (its clip rectangle applies).
void opaque_rects(const ImDrawList& list, const ToPixels& to_pixels, ImVec2 white_uv, std::vector<PixelRect>& out) {
    if (list.CmdBuffer.Size == 0) return;
    const ImDrawCmd& first = list.CmdBuffer[0];
    if (first.UserCallback || first.VtxOffset != 0 || first.IdxOffset != 0) return;
    const PixelRect clip = to_pixels(first.ClipRect.x, first.ClipRect.y, first.ClipRect.z, first.ClipRect.w, false);
    static const int kQuad[6] = {0, 1, 2, 0, 2, 3};
    for (int q = 0; 6 * (q + 1) <= int(first.ElemCount) && 4 * (q + 1) <= list.VtxBuffer.Size &&
                    6 * (q + 1) <= list.IdxBuffer.Size;
         ++q) {
        const ImDrawVert* v = &list.VtxBuffer[4 * q];
        const ImDrawIdx* idx = &list.IdxBuffer[6 * q];
        bool is_rect = v[1].pos.x == v[2].pos.x && v[0].pos.x == v[3].pos.x && v[0].pos.y == v[1].pos.y &&
                       v[2].pos.y == v[3].pos.y && v[0].pos.x < v[1].pos.x && v[0].pos.y < v[3].pos.y;
        for (int k = 0; k < 6 && is_rect; ++k) is_rect = idx[k] == ImDrawIdx(4 * q + kQuad[k]);
        for (int k = 0; k < 4 && is_rect; ++k)
            is_rect = (v[k].col & IM_COL32_A_MASK) == IM_COL32_A_MASK && v[k].uv.x == white_uv.x && v[k].uv.y == white_uv.y;
        if (!is_rect) return;  // the opaque start of the list ends here
        PixelRect r = to_pixels(v[0].pos.x, v[0].pos.y, v[2].pos.x, v[2].pos.y, false);
        r = {std::max(r.x0, clip.x0), std::max(r.y0, clip.y0), std::min(r.x1, clip.x1), std::min(r.y1, clip.y1)};
        if (!r.empty()) out.push_back(r);
    }
}

}  // namespace

void subtract_rect(const PixelRect& a, const PixelRect& b, std::vector<PixelRect>& out) {
    if (a.empty()) return;
    if (!overlap(a, b)) {
        out.push_back(a);
        return;
    }
    // Above b, below b (full width of a), then left and right of b in the rows between.
    const int32_t top = std::max(a.y0, b.y0), bottom = std::min(a.y1, b.y1);
    const PixelRect pieces[4] = {{a.x0, a.y0, a.x1, top},
                                 {a.x0, bottom, a.x1, a.y1},
                                 {a.x0, top, std::max(a.x0, b.x0), bottom},
                                 {std::min(a.x1, b.x1), top, a.x1, bottom}};
    for (const PixelRect& p : pieces)
        if (!p.empty()) out.push_back(p);
}

// `r` minus every rectangle of `minus`, as disjoint pieces.
static std::vector<PixelRect> subtract_all(const PixelRect& r, const std::vector<PixelRect>& minus) {
    std::vector<PixelRect> pieces{r}, rest;
    for (const PixelRect& m : minus) {
        rest.clear();
        for (const PixelRect& piece : pieces) subtract_rect(piece, m, rest);
        pieces.swap(rest);
    }
    return pieces;
}

UiRegions find_ui_regions(const ImDrawData& draw_data, int32_t width, int32_t height, ImVec2 white_uv, bool allow_copy) {
    const ToPixels to_pixels{draw_data.DisplayPos, draw_data.FramebufferScale, width, height};
    std::vector<PixelRect> panels, opaque;
    for (int i = 0; i < draw_data.CmdListsCount; ++i) {
        const ImDrawList& list = *draw_data.CmdLists[i];
        if (list.VtxBuffer.Size == 0) continue;
        // A draw list is one panel (or tooltip, popup): its pixels lie inside both the bounding
        // box of its vertices and the union of its clip rectangles.
        float bx0 = FLT_MAX, by0 = FLT_MAX, bx1 = -FLT_MAX, by1 = -FLT_MAX;
        for (const ImDrawVert& v : list.VtxBuffer) {
            bx0 = std::min(bx0, v.pos.x), by0 = std::min(by0, v.pos.y);
            bx1 = std::max(bx1, v.pos.x), by1 = std::max(by1, v.pos.y);
        }
        float cx0 = FLT_MAX, cy0 = FLT_MAX, cx1 = -FLT_MAX, cy1 = -FLT_MAX;
        for (const ImDrawCmd& c : list.CmdBuffer) {
            cx0 = std::min(cx0, c.ClipRect.x), cy0 = std::min(cy0, c.ClipRect.y);
            cx1 = std::max(cx1, c.ClipRect.z), cy1 = std::max(cy1, c.ClipRect.w);
        }
        const PixelRect r = to_pixels(std::max(bx0, cx0), std::max(by0, cy0), std::min(bx1, cx1), std::min(by1, cy1), true);
        if (r.empty()) continue;
        panels.push_back(r);
        if (allow_copy) opaque_rects(list, to_pixels, white_uv, opaque);
    }

    UiRegions regions;
    // Overlapping panel rectangles (a tooltip over a panel) are merged, so that no pixel is blended twice.
    for (bool merged = true; merged;) {
        merged = false;
        for (size_t i = 0; i < panels.size() && !merged; ++i)
            for (size_t j = i + 1; j < panels.size() && !merged; ++j)
                if (overlap(panels[i], panels[j])) {
                    panels[i] = bounding_box(panels[i], panels[j]);
                    panels.erase(panels.begin() + std::ptrdiff_t(j));
                    merged = true;
                }
    }
    for (const PixelRect& p : panels) regions.bounds = regions.bounds.empty() ? p : bounding_box(regions.bounds, p);

    // The copied rectangles made disjoint (a copy region may not overlap another in one vkCmdCopyImage).
    for (const PixelRect& o : opaque) {
        const std::vector<PixelRect> pieces = subtract_all(o, regions.copy);
        regions.copy.insert(regions.copy.end(), pieces.begin(), pieces.end());
    }
    // What is left of the panels is blended.
    for (const PixelRect& p : panels) {
        const std::vector<PixelRect> pieces = subtract_all(p, regions.copy);
        regions.blend.insert(regions.blend.end(), pieces.begin(), pieces.end());
    }
    return regions;
}

}  // namespace lab
