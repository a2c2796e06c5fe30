// image_io.cpp — 8-bit RGBA PNG files via stb_image / stb_image_write.
//
// Both stb libraries are compiled here, as static (file-local) functions, so
// they cannot clash with the copy in Debian's libstb.so.
#include "image_io.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#define STB_IMAGE_STATIC
// lab_content's one stb_image implementation (every format: texture_image.cpp decodes the labs'
// maps with it; read_png() below checks the PNG signature itself).
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push  // third-party code: not our warnings to fix
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace lab {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& reason) {
    throw std::runtime_error(path + ": " + reason);
}

std::string errno_text() { return std::strerror(errno); }

// stb_image_write hands us the encoded PNG in pieces; we collect them in memory.
void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* bytes = static_cast<const unsigned char*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

// Writes all bytes or reports why not (errno text: "No space left on device", ...).
void write_file(const std::string& path, const std::vector<unsigned char>& bytes) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) fail(path, "cannot create file: " + errno_text());
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    const std::string write_error = written ? "" : errno_text();
    if (std::fclose(f) != 0 && written) fail(path, "cannot write file: " + errno_text());
    if (!written) fail(path, "cannot write file: " + write_error);
}

}  // namespace

void write_png(const std::string& path, const Image8& image) {
    if (image.width <= 0 || image.height <= 0)
        fail(path, "cannot write an empty image (" + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + ")");
    const size_t expected = static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 4;
    if (image.rgba.size() != expected)
        fail(path, "image has " + std::to_string(image.rgba.size()) + " bytes, expected " +
                       std::to_string(expected) + " (width x height x 4)");

    // Encode in memory first: stb's own file writer cannot tell us why it failed.
    // The encoder has no timestamps or randomness: same pixels, same bytes.
    std::vector<unsigned char> png;
    if (!stbi_write_png_to_func(append_bytes, &png, image.width, image.height, 4, image.rgba.data(),
                                image.width * 4))
        fail(path, "PNG encoding failed");

    // Write "path.tmp", then rename over "path": a reader (or a crash) never sees
    // a half-written PNG, because rename replaces the file in one step.
    const std::string tmp = path + ".tmp";
    try {
        write_file(tmp, png);
    } catch (...) {
        std::remove(tmp.c_str());
        throw;
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        fail(path, "cannot rename " + tmp + " to it: " + ec.message());
    }
}

Image8 read_png(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) fail(path, "cannot read PNG: is a directory");
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) fail(path, "cannot open file: " + errno_text());
    std::vector<unsigned char> bytes;
    unsigned char buffer[65536];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) bytes.insert(bytes.end(), buffer, buffer + n);
    const bool read_error = std::ferror(f) != 0;
    std::fclose(f);
    if (read_error) fail(path, "cannot read file: " + errno_text());

    // Check the 8-byte PNG signature ourselves so the message is clear.
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (bytes.size() < 8 || std::memcmp(bytes.data(), signature, 8) != 0) fail(path, "not a PNG file");

    int width = 0, height = 0, channels = 0;
    // Ask for 4 channels: grey, grey+alpha and RGB files are expanded to RGBA (alpha 255).
    unsigned char* pixels = stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &width,
                                                  &height, &channels, 4);
    if (!pixels) fail(path, std::string("corrupt or unsupported PNG: ") + stbi_failure_reason());
    Image8 image;
    image.width = width;
    image.height = height;
    image.rgba.assign(pixels, pixels + static_cast<size_t>(width) * static_cast<size_t>(height) * 4);
    stbi_image_free(pixels);
    return image;
}

}  // namespace lab
