// lab_reference — the CPU reference renderer as a command (the ground truth for bench/tradeoff.py).
//
//   lab_reference --lab LAB --scene FILE --width W --height H --out ref.png [--ideal] [--supersample N]
//                 [--unshadowed FILE --unlit FILE]
//
// Renders what the tests' reference renders for that lab (lab1_camera: unlit albedo;
// lab2_lighting: the scene's lighting and shading model, tests/reference/cpu_lighting.h;
// lab3_textures: the textured scene as its samplers describe it, tests/reference/cpu_texture.h,
// anisotropy not modelled).
// --ideal replaces the curved primitives by their exact surfaces (tests/reference/ideal.h) and,
// for lab 2, shades every pixel with the exact normal: the truth a tessellation and a shading
// model approximate. --supersample N takes N×N stratified samples per pixel (box filter); in
// lab 3 it gives the filtering ground truth instead: N×N rays per pixel on a regular grid, each
// with level-0 bilinear lookups, averaged (the texture over the pixel's footprint,
// ref::render_supersampled). Lab 3 has no --ideal: its truth is that supersampled picture.
// lab4_shadows: lab 3's textured shading with ray-traced hard shadows and translucent layers
// (tests/reference/cpu_shadow.h); --unshadowed / --unlit also write the two other pictures the
// shadow error metric needs (every light unoccluded / the shadow-casting lights off; lab_compare --shadow).
// It shares no code with the labs; only lab_content's scene loader, meshes and PNG writer.
#include "reference/cpu_lighting.h"
#include "reference/cpu_reference.h"
#include "reference/cpu_shadow.h"
#include "reference/cpu_texture.h"
#include "reference/ideal.h"

#include "image_io.h"
#include "scene.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace {

const char* kUsage =
    "usage: lab_reference --lab LAB --scene FILE --width W --height H --out ref.png [--ideal] [--supersample N]\n"
    "  LAB: lab1_camera (unlit), lab2_lighting (lit), lab3_textures (textured) or lab4_shadows (shadowed)\n"
    "  --ideal          exact spheres, cylinders, cones, tori (and per-pixel exact normals in lab 2; not lab 3)\n"
    "  --supersample N  N x N stratified samples per pixel, averaged (1 ... 16, default 1); lab 3: the\n"
    "                   filtering ground truth, N x N rays with level-0 bilinear lookups averaged\n"
    "  --unshadowed F, --unlit F  lab4_shadows: also write the picture with every light unoccluded, and with\n"
    "                   the shadow-casting lights off (for lab_compare --shadow)\n";

struct Args {
    std::string lab, scene, out, unshadowed, unlit;
    int width = 0, height = 0, supersample = 1;
    bool ideal = false;
};

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

int parse_int(const std::string& flag, const char* text, int lo, int hi) {
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < lo || v > hi)
        throw UsageError(flag + ": '" + text + "' is not a whole number in " + std::to_string(lo) + " ... " +
                         std::to_string(hi));
    return static_cast<int>(v);
}

Args parse(int argc, char** argv) {
    Args a;
    for (int i = 1; i < argc; ++i) {
        const std::string f = argv[i];
        auto value = [&]() -> const char* {
            if (i + 1 >= argc) throw UsageError(f + " needs a value");
            return argv[++i];
        };
        if (f == "--lab") a.lab = value();
        else if (f == "--scene") a.scene = value();
        else if (f == "--out") a.out = value();
        else if (f == "--width") a.width = parse_int(f, value(), 1, 16384);
        else if (f == "--height") a.height = parse_int(f, value(), 1, 16384);
        else if (f == "--supersample") a.supersample = parse_int(f, value(), 1, 16);
        else if (f == "--ideal") a.ideal = true;
        else if (f == "--unshadowed") a.unshadowed = value();
        else if (f == "--unlit") a.unlit = value();
        else if (f == "--help" || f == "-h") throw UsageError("");
        else throw UsageError("unknown option '" + f + "'");
    }
    if (a.lab.empty() || a.scene.empty() || a.out.empty() || a.width == 0 || a.height == 0)
        throw UsageError("--lab, --scene, --width, --height and --out are required");
    if (a.lab != "lab1_camera" && a.lab != "lab2_lighting" && a.lab != "lab3_textures" && a.lab != "lab4_shadows")
        throw UsageError("--lab: unknown lab '" + a.lab +
                         "' (lab1_camera, lab2_lighting, lab3_textures or lab4_shadows)");
    if (a.lab == "lab4_shadows" && (a.ideal || a.supersample > 1))
        throw UsageError("--ideal / --supersample: not available for lab4_shadows (its truth is the ray-traced shadow)");
    if (a.lab != "lab4_shadows" && (!a.unshadowed.empty() || !a.unlit.empty()))
        throw UsageError("--unshadowed / --unlit: only for lab4_shadows");
    if (a.lab == "lab3_textures" && a.ideal)
        throw UsageError("--ideal: not available for lab3_textures (its truth is --supersample N)");
    return a;
}

}  // namespace

int main(int argc, char** argv) {
    Args args;
    try {
        args = parse(argc, argv);
    } catch (const UsageError& e) {
        if (std::strlen(e.what()) == 0) {
            std::fputs(kUsage, stdout);
            return 0;
        }
        std::fprintf(stderr, "lab_reference: %s (see --help)\n", e.what());
        return 2;
    }
    try {
        const lab::Scene scene = lab::load_scene(args.scene);
        // Fail on an unwritable destination before spending the render time.
        const std::filesystem::path parent = std::filesystem::path(args.out).parent_path();
        if (!parent.empty() && !std::filesystem::is_directory(parent))
            throw std::runtime_error(args.out + ": folder '" + parent.string() + "' does not exist");

        const auto start = std::chrono::steady_clock::now();
        ref::ShadeFn shade = ref::shade_unlit;
        if (args.lab == "lab2_lighting")
            shade = args.ideal ? ref::make_ideal_lighting_shader(scene) : ref::make_lighting_shader(scene);
        // Fail on an unwritable extra destination before spending the render time, too.
        for (const std::string& extra : {args.unshadowed, args.unlit}) {
            const std::filesystem::path folder = std::filesystem::path(extra).parent_path();
            if (!extra.empty() && !folder.empty() && !std::filesystem::is_directory(folder))
                throw std::runtime_error(extra + ": folder '" + folder.string() + "' does not exist");
        }
        ref::RefImage image;
        if (args.lab == "lab4_shadows") {
            // Ray-traced shadows and translucent layers (cpu_shadow.h).
            if (args.unshadowed.empty() && args.unlit.empty()) {
                image = ref::render_shadowed(scene, args.width, args.height);
            } else {
                ref::ShadowReference r = ref::render_shadow_reference(scene, args.width, args.height);
                if (!args.unshadowed.empty()) lab::write_png(args.unshadowed, ref::encode_srgb(r.unshadowed));
                if (!args.unlit.empty()) lab::write_png(args.unlit, ref::encode_srgb(r.unlit));
                image = std::move(r.shadowed);
            }
        } else if (args.lab == "lab3_textures") {
            // The textured reference (cpu_texture.h); supersampled, the filtering ground truth.
            image = args.supersample > 1
                        ? ref::render_supersampled(scene, args.width, args.height, args.supersample)
                        : ref::render_reference(scene, args.width, args.height,
                                                ref::make_texture_shader(scene, args.width, args.height));
        } else if (args.ideal) {
            const ref::IdealGeometry geometry(scene);
            image = ref::render_with(scene, args.width, args.height, shade, geometry.tracer(), args.supersample);
        } else {
            const ref::SceneGeometry geometry(scene);
            const ref::TraceFn trace = [&geometry](const ref::Ray& r, double t0, double t1, ref::Hit* h) {
                return geometry.trace(r, t0, t1, h);
            };
            image = ref::render_with(scene, args.width, args.height, shade, trace, args.supersample);
        }
        lab::write_png(args.out, ref::encode_srgb(image));
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        std::printf("reference lab=%s width=%d height=%d ideal=%d supersample=%d ms=%.1f out=%s\n", args.lab.c_str(),
                    args.width, args.height, args.ideal ? 1 : 0, args.supersample, ms, args.out.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "lab_reference: %s\n", e.what());
        return 2;
    }
    return 0;
}
