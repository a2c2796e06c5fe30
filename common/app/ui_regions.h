// ui_regions.h — which pixels of a frame the UI panels cover, and which of those they cover opaquely.
//
// The panels are drawn into an overlay image (imgui_renderer.h) that is put over each frame. Where
// a panel is opaque the frame's pixel is simply the overlay's: it can be *copied* (a memcpy per row
// on a CPU driver) instead of blended (a texture read and a blend per pixel). ImGui starts every
// window's draw list with its background and title bar, axis-aligned rectangles; when their colours
// are opaque, everything drawn over them stays opaque ("over": α = α_src + α_dst·(1 − α_src) = 1
// when α_dst = 1). Only the rest — borders, collapsed title bars, anything translucent — is blended.
#pragma once

#include <imgui.h>

#include <cstdint>
#include <vector>

namespace lab {

// Pixels [x0, x1) × [y0, y1) of the framebuffer.
struct PixelRect {
    int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x0 >= x1 || y0 >= y1; }
    int64_t area() const { return empty() ? 0 : int64_t(x1 - x0) * int64_t(y1 - y0); }
};

struct UiRegions {
    std::vector<PixelRect> copy;   // opaque panel pixels: the overlay replaces the frame's (disjoint)
    std::vector<PixelRect> blend;  // the other pixels that may hold UI: blended "over" (disjoint, none in `copy`)
    PixelRect bounds;              // the bounding box of both (where the overlay must be drawn)
};

// The regions of `draw_data` in a framebuffer of `width` × `height` pixels. `white_uv` is the font
// atlas texel ImGui fills rectangles with (ImFontAtlas::TexUvWhitePixel): a rectangle counts as
// opaque only if it is that texel in a colour of alpha 255. With `allow_copy` false every pixel
// goes into `blend`.
UiRegions find_ui_regions(const ImDrawData& draw_data, int32_t width, int32_t height, ImVec2 white_uv, bool allow_copy);

// a − b as up to four disjoint rectangles, appended to `out`.
void subtract_rect(const PixelRect& a, const PixelRect& b, std::vector<PixelRect>& out);

}  // namespace lab
