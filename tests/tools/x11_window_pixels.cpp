// x11_window_pixels — a fingerprint of what a rectangle of an X11 window shows right now, so a
// window test can tell whether the picture there changed (e.g. a UI widget drawn hovered).
//   x11_window_pixels WINDOW_ID X Y WIDTH HEIGHT     prints a 64-bit FNV-1a hash of the pixels
#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

namespace {
bool parse(const char* text, unsigned long& value) {
    char* end = nullptr;
    value = std::strtoul(text, &end, 0);
    return end && end != text && *end == '\0';
}
}  // namespace

int main(int argc, char** argv) {
    unsigned long id = 0, x = 0, y = 0, width = 0, height = 0;
    if (argc != 6 || !parse(argv[1], id) || !parse(argv[2], x) || !parse(argv[3], y) || !parse(argv[4], width) ||
        !parse(argv[5], height) || id == 0 || width == 0 || height == 0) {
        std::fprintf(stderr, "usage: x11_window_pixels WINDOW_ID X Y WIDTH HEIGHT\n");
        return 2;
    }
    Display* display = XOpenDisplay(nullptr);
    if (!display) {
        std::fprintf(stderr, "x11_window_pixels: cannot open the display (DISPLAY unset?)\n");
        return 1;
    }
    XImage* image = XGetImage(display, Window(id), int(x), int(y), unsigned(width), unsigned(height), AllPlanes, ZPixmap);
    if (!image) {
        std::fprintf(stderr, "x11_window_pixels: cannot read %lux%lu+%lu+%lu of window 0x%lx\n", width, height, x, y, id);
        XCloseDisplay(display);
        return 1;
    }
    uint64_t hash = 14695981039346656037ull;  // FNV-1a over the pixel values, row by row
    for (unsigned long row = 0; row < height; ++row)
        for (unsigned long column = 0; column < width; ++column) {
            const unsigned long pixel = XGetPixel(image, int(column), int(row));
            for (int byte = 0; byte < 4; ++byte) {
                hash ^= (pixel >> (8 * byte)) & 0xFF;
                hash *= 1099511628211ull;
            }
        }
    XDestroyImage(image);
    XCloseDisplay(display);
    std::printf("%016" PRIx64 "\n", hash);
    return 0;
}
