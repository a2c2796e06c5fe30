// texture_image.h — the pixels of a texture map (lab 3), before anything touches Vulkan.
//
// A map is "procedural:NAME" (checker, metal, grid: docs/scene-format.md) or an image file in
// any format stb_image reads (PNG, JPEG, BMP, TGA, ...). Files are untrusted input: their size
// is checked from the header before a single pixel is decoded, and a file that cannot be used
// never stops the lab — it becomes the magenta/black checkerboard and one warning line.
#pragma once

#include "image_io.h"

#include <string>

namespace lab {

// Largest image file read at all, and largest decoded image (RGBA bytes), whatever the device allows.
constexpr size_t kMaxTextureFileBytes = size_t(256) << 20;
constexpr size_t kMaxTexturePixels = size_t(64) << 20;  // 64 Mpixel = 256 MiB of RGBA

struct TextureLoad {
    Image8 image;         // 8-bit RGBA, sRGB-encoded, row 0 = top (v = 0)
    std::string warning;  // "" when the map loaded; else "FILE: reason" (the image is the checkerboard)
};

// Loads a map (see above). `max_dimension` is the device's maxImageDimension2D.
// Never throws for a bad file; throws std::invalid_argument for an unknown procedural name
// (the scene loader rejects those before).
TextureLoad load_texture_image(const std::string& map, int max_dimension);

// The seed's procedural sources:
//   checker: 8×8 texels, alternating white and dark grey (64);
//   metal:   256², every channel (sin(0.1·x)·cos(0.1·y) + 1)/2 · 255, truncated as the seed does;
//   grid:    256², (0, 200, 255) where x mod 32 < 2 or y mod 32 < 2, black elsewhere.
Image8 procedural_texture(const std::string& name);

// What a broken map shows: 8×8 texels of magenta and black (the seed's fallback).
Image8 fallback_texture();

}  // namespace lab
