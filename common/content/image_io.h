// image_io.h — 8-bit RGBA images to and from PNG (stb_image / stb_image_write).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lab {

struct Image8 {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;  // row 0 is the top row, 4 bytes per pixel
};

// Writes atomically (temporary file, then rename): never a half-written PNG.
// Throws std::runtime_error with a one-line message.
void write_png(const std::string& path, const Image8& image);
// Throws std::runtime_error with a one-line message.
Image8 read_png(const std::string& path);

}  // namespace lab
