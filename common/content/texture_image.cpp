// texture_image.cpp — decoding texture maps with stb_image, checking sizes first.
//
// stb_image is compiled here a second time (file-local, STB_IMAGE_STATIC) with every format
// enabled; image_io.cpp's copy reads PNG only.
#include "texture_image.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <stb/stb_image.h>  // implemented once, in image_io.cpp

namespace lab {
namespace {

Image8 blank(int width, int height) {
    Image8 image;
    image.width = width;
    image.height = height;
    image.rgba.assign(size_t(width) * size_t(height) * 4, 255);
    return image;
}

void put(Image8& image, int x, int y, uint8_t r, uint8_t g, uint8_t b) {
    uint8_t* p = &image.rgba[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
    p[0] = r;
    p[1] = g;
    p[2] = b;
    p[3] = 255;
}

// Reads the whole file, or says why not ("" on success).
std::string read_file(const std::string& path, std::vector<unsigned char>& bytes) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(path, ec)) return "cannot open: is a directory";
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return std::string("cannot open: ") + std::strerror(errno);
    const uintmax_t size = fs::file_size(path, ec);
    if (!ec && size > kMaxTextureFileBytes) {
        std::fclose(f);
        return "file of " + std::to_string(size >> 20) + " MiB exceeds the limit of " +
               std::to_string(kMaxTextureFileBytes >> 20) + " MiB";
    }
    unsigned char buffer[65536];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) {
        bytes.insert(bytes.end(), buffer, buffer + n);
        if (bytes.size() > kMaxTextureFileBytes) break;  // the file grew while we read it
    }
    const bool error = std::ferror(f) != 0;
    std::fclose(f);
    if (error) return std::string("cannot read: ") + std::strerror(errno);
    if (bytes.size() > kMaxTextureFileBytes) return "file exceeds the size limit";
    return "";
}

// The size a PNG claims in its IHDR chunk (bytes 16..23, big-endian), or false if it is no PNG.
// Read here because stb_image refuses sizes over 2³⁰ bytes as "unknown image type".
bool png_claimed_size(const std::vector<unsigned char>& b, uint32_t* width, uint32_t* height) {
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (b.size() < 24 || std::memcmp(b.data(), signature, 8) != 0 || std::memcmp(&b[12], "IHDR", 4) != 0) return false;
    const auto be32 = [&b](size_t i) { return uint32_t(b[i]) << 24 | uint32_t(b[i + 1]) << 16 | uint32_t(b[i + 2]) << 8 | b[i + 3]; };
    *width = be32(16);
    *height = be32(20);
    return true;
}

std::string too_big(uint64_t width, uint64_t height, int max_dimension) {
    if (width > uint64_t(max_dimension) || height > uint64_t(max_dimension))
        return std::to_string(width) + " × " + std::to_string(height) + " exceeds the device limit " +
               std::to_string(max_dimension);
    if (width * height > kMaxTexturePixels)
        return std::to_string(width) + " × " + std::to_string(height) + " exceeds the limit of " +
               std::to_string(kMaxTexturePixels >> 20) + " Mpixels";
    return "";
}

// Decodes `bytes`, or says why not ("" on success). The header's size is checked first.
std::string decode(const std::vector<unsigned char>& bytes, int max_dimension, Image8& out) {
    if (bytes.empty()) return "not an image: the file is empty";
    const int length = int(bytes.size());
    uint32_t png_width = 0, png_height = 0;
    if (png_claimed_size(bytes, &png_width, &png_height)) {
        const std::string reason = too_big(png_width, png_height, max_dimension);
        if (!reason.empty()) return reason;
    }
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(bytes.data(), length, &width, &height, &channels))
        return std::string("not an image (") + stbi_failure_reason() + ")";
    if (width <= 0 || height <= 0)
        return std::to_string(width) + " × " + std::to_string(height) + " is an empty image";
    const std::string reason = too_big(uint64_t(width), uint64_t(height), max_dimension);
    if (!reason.empty()) return reason;
    int w = 0, h = 0;
    unsigned char* pixels = stbi_load_from_memory(bytes.data(), length, &w, &h, &channels, 4);
    if (!pixels) return std::string("corrupt image (") + stbi_failure_reason() + ")";
    if (w != width || h != height) {  // the header lied between the two reads: not trusted
        stbi_image_free(pixels);
        return "corrupt image (inconsistent size)";
    }
    out = Image8{w, h, std::vector<uint8_t>(pixels, pixels + size_t(w) * size_t(h) * 4)};
    stbi_image_free(pixels);
    return "";
}

}  // namespace

Image8 procedural_texture(const std::string& name) {
    if (name == "checker") {
        Image8 image = blank(8, 8);
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) {
                const uint8_t v = (x + y) % 2 == 0 ? 255 : 64;
                put(image, x, y, v, v, v);
            }
        return image;
    }
    if (name == "metal") {
        Image8 image = blank(256, 256);
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) {
                const float pattern = std::sin(float(x) * 0.1f) * std::cos(float(y) * 0.1f);
                const uint8_t v = uint8_t((pattern + 1.0f) * 0.5f * 255.0f);  // truncates, as the seed
                put(image, x, y, v, v, v);
            }
        return image;
    }
    if (name == "grid") {
        Image8 image = blank(256, 256);
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) {
                const bool line = x % 32 < 2 || y % 32 < 2;
                put(image, x, y, 0, line ? 200 : 0, line ? 255 : 0);
            }
        return image;
    }
    throw std::invalid_argument("unknown procedural texture '" + name + "'");
}

Image8 fallback_texture() {
    Image8 image = blank(8, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const bool magenta = (x + y) % 2 == 0;
            put(image, x, y, magenta ? 255 : 0, 0, magenta ? 255 : 0);
        }
    return image;
}

TextureLoad load_texture_image(const std::string& map, int max_dimension) {
    const std::string prefix = "procedural:";
    if (map.rfind(prefix, 0) == 0) return {procedural_texture(map.substr(prefix.size())), ""};
    TextureLoad result;
    std::vector<unsigned char> bytes;
    std::string reason = read_file(map, bytes);
    if (reason.empty()) reason = decode(bytes, max_dimension, result.image);
    if (!reason.empty()) {
        result.image = fallback_texture();
        result.warning = map + ": " + reason;
    }
    return result;
}

}  // namespace lab
