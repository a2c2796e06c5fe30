// Tests for the shared command line (common/app/cli.cpp, dev_options.cpp) and PNG input/output
// (common/content/image_io.cpp).
#include "cli.h"
#include "image_io.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;

namespace {

const std::string kDefaultScene = "scenes/lab1.json";

// Parses `args` as if typed after the program name.
lab::Options parse(std::initializer_list<const char*> args) {
    std::vector<const char*> argv = {"lab"};
    argv.insert(argv.end(), args.begin(), args.end());
    return lab::parse_command_line(static_cast<int>(argv.size()), argv.data(), kDefaultScene);
}

// The CliError message for `args` ("" and a test failure if they parse).
std::string error_of(std::initializer_list<const char*> args) {
    try {
        parse(args);
    } catch (const lab::CliError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
        return message;
    }
    ADD_FAILURE() << "expected a CliError";
    return "";
}

#define EXPECT_CONTAINS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

}  // namespace

// --- command line -------------------------------------------------------------

TEST(Cli, Defaults) {
    const lab::Options o = parse({});
    EXPECT_EQ(o.scene, kDefaultScene);
    EXPECT_FALSE(o.headless);
    EXPECT_EQ(o.out, "");
    EXPECT_EQ(o.width, 1280u);
    EXPECT_EQ(o.height, 720u);
    EXPECT_EQ(o.frames, 0);
    EXPECT_FALSE(o.validate);
    EXPECT_EQ(o.benchmark, 0);
    EXPECT_FALSE(o.help);
}

TEST(Cli, EveryOptionWithSeparateValues) {
    const lab::Options o = parse({"--scene", "my.json", "--headless", "--out", "x.png", "--width", "640",
                                  "--height", "480", "--frames", "3", "--validate"});
    EXPECT_EQ(o.scene, "my.json");
    EXPECT_TRUE(o.headless);
    EXPECT_EQ(o.out, "x.png");
    EXPECT_EQ(o.width, 640u);
    EXPECT_EQ(o.height, 480u);
    EXPECT_EQ(o.frames, 3);
    EXPECT_TRUE(o.validate);
    EXPECT_EQ(o.benchmark, 0);
}

TEST(Cli, EqualsForm) {
    const lab::Options o = parse({"--scene=a=b.json", "--width=1", "--height=16384", "--frames=7",
                                  "--benchmark=100", "--out=dir/OUT.PNG"});
    EXPECT_EQ(o.scene, "a=b.json");  // only the first '=' splits
    EXPECT_EQ(o.width, 1u);
    EXPECT_EQ(o.height, 16384u);
    EXPECT_EQ(o.frames, 7);
    EXPECT_EQ(o.benchmark, 100);
    EXPECT_EQ(o.out, "dir/OUT.PNG");
}

TEST(Cli, OutAndBenchmarkImplyHeadless) {
    EXPECT_TRUE(parse({"--out", "a.png"}).headless);
    EXPECT_TRUE(parse({"--benchmark", "10"}).headless);
    EXPECT_FALSE(parse({"--frames", "10"}).headless);
}

TEST(Cli, WindowBenchmark) {
    const lab::Options o = parse({"--benchmark", "50", "--window"});
    EXPECT_EQ(o.benchmark, 50);
    EXPECT_TRUE(o.window);
    EXPECT_FALSE(o.headless);
    EXPECT_FALSE(parse({"--window", "--benchmark=5"}).headless);  // in either order
    EXPECT_CONTAINS(error_of({"--benchmark", "5", "--window", "--headless"}), "--window cannot be combined with --headless");
    EXPECT_CONTAINS(error_of({"--window", "--out", "a.png"}), "--window cannot be combined with --out");
    EXPECT_CONTAINS(error_of({"--window=1"}), "--window takes no value");
}

TEST(Cli, LaterOptionsOverrideEarlierOnes) {
    EXPECT_EQ(parse({"--width", "100", "--width", "200"}).width, 200u);
}

TEST(Cli, HelpWinsEvenOverMistakes) {
    EXPECT_TRUE(parse({"--help"}).help);
    EXPECT_TRUE(parse({"-h"}).help);
    EXPECT_TRUE(parse({"--bogus", "--width", "0", "-h"}).help);
}

TEST(Cli, UnknownOptionsSuggestTheClosest) {
    EXPECT_CONTAINS(error_of({"--heigth", "5"}), "unknown option '--heigth' (did you mean --height?)");
    EXPECT_CONTAINS(error_of({"--headles"}), "did you mean --headless?");
    EXPECT_CONTAINS(error_of({"--Scene", "a.json"}), "did you mean --scene?");
    EXPECT_CONTAINS(error_of({"--xyzzy"}), "unknown option '--xyzzy' (see --help)");
    EXPECT_CONTAINS(error_of({"-w", "5"}), "unknown option '-w'");
}

TEST(Cli, StrayArguments) {
    EXPECT_CONTAINS(error_of({"extra"}), "unexpected argument 'extra'");
    EXPECT_CONTAINS(error_of({"scene.json"}), "did you mean --scene scene.json?");
}

TEST(Cli, MissingValues) {
    EXPECT_CONTAINS(error_of({"--scene"}), "--scene: missing value");
    EXPECT_CONTAINS(error_of({"--width", "--headless"}), "--width: missing value");
    EXPECT_CONTAINS(error_of({"--out="}), "--out: missing value");
}

TEST(Cli, FlagsTakeNoValue) {
    EXPECT_CONTAINS(error_of({"--headless=yes"}), "--headless takes no value");
    EXPECT_CONTAINS(error_of({"--validate=1"}), "--validate takes no value");
}

TEST(Cli, NonNumericValues) {
    EXPECT_CONTAINS(error_of({"--width", "abc"}), "--width: expected a whole number, got 'abc'");
    EXPECT_CONTAINS(error_of({"--height", "1.5"}), "--height: expected a whole number, got '1.5'");
    EXPECT_CONTAINS(error_of({"--frames", "12px"}), "--frames: expected a whole number");
    EXPECT_CONTAINS(error_of({"--benchmark", " 5"}), "--benchmark: expected a whole number");
    EXPECT_CONTAINS(error_of({"--width", "-"}), "--width: expected a whole number");
}

TEST(Cli, OutOfRangeValues) {
    EXPECT_CONTAINS(error_of({"--width", "0"}), "--width: 0 is out of range (allowed: 1..65536)");
    // Up to 65536 is the device's to refuse (tests/test_vulkan_correctness.cpp); beyond, the command line's.
    EXPECT_CONTAINS(error_of({"--height", "65537"}), "--height: 65537 is out of range");
    EXPECT_CONTAINS(error_of({"--width", "-5"}), "--width: -5 is out of range");
    EXPECT_CONTAINS(error_of({"--width", "99999999999999999999999"}), "out of range");
    EXPECT_CONTAINS(error_of({"--frames", "0"}), "--frames: 0 is out of range");
    EXPECT_CONTAINS(error_of({"--frames", "2147483648"}), "--frames: 2147483648 is out of range");
    EXPECT_CONTAINS(error_of({"--benchmark", "0"}), "--benchmark: 0 is out of range");
    EXPECT_EQ(parse({"--frames", "2147483647"}).frames, 2147483647);
}

TEST(Cli, OutMustBeAPng) {
    EXPECT_CONTAINS(error_of({"--out", "image.jpg"}), "--out: the file name must end in .png");
    EXPECT_CONTAINS(error_of({"--out", ".png"}), "must end in .png");
}

TEST(Cli, UsageListsEveryOptionAndDefault) {
    const std::string text = lab::usage("lab1_camera");
    EXPECT_CONTAINS(text, "usage: lab1_camera");
    for (const char* part : {"--scene", "--headless", "--out", "--width", "--height", "--frames", "--validate",
                             "--benchmark", "--window", "--help", "-h", "1280", "720", "16384", "implies --headless"})
        EXPECT_CONTAINS(text, part);
    EXPECT_GT(std::count(text.begin(), text.end(), '\n'), 10);
}

// --- developer options (common/app/dev_options.h) --------------------------------

TEST(Cli, DeveloperOptionsAreOffByDefault) {
    const lab::DevOptions d = parse({}).dev;
    EXPECT_TRUE(d.status_file.empty());
    EXPECT_EQ(d.fail_after_submit, 0);
    EXPECT_FALSE(d.validation_probe);
    EXPECT_FALSE(d.no_blit);
    EXPECT_TRUE(d.shader_dir.empty());
    EXPECT_TRUE(d.scene_dir.empty());
    EXPECT_FALSE(d.animate_lights);
    EXPECT_EQ(d.shadow_view, -1);
    EXPECT_FALSE(d.mip_view);
    EXPECT_EQ(d.warmup_ms, 1000);  // on, but only --benchmark uses it
}

TEST(Cli, EveryDeveloperOption) {
    const lab::Options o = parse({"--dev-status-file", "s.txt", "--dev-fail-after-submit=3", "--dev-validation-probe",
                                  "--dev-no-blit", "--dev-shader-dir", "/tmp/sh", "--dev-scene-dir=/tmp/sc",
                                  "--dev-animate-lights", "--dev-shadow-view", "2", "--dev-mip-view", "--dev-warmup-ms", "0",
                                  "--width", "64"});
    EXPECT_EQ(o.dev.status_file, "s.txt");
    EXPECT_EQ(o.dev.fail_after_submit, 3);
    EXPECT_TRUE(o.dev.validation_probe);
    EXPECT_TRUE(o.dev.no_blit);
    EXPECT_EQ(o.dev.shader_dir, "/tmp/sh");
    EXPECT_EQ(o.dev.scene_dir, "/tmp/sc");
    EXPECT_TRUE(o.dev.animate_lights);
    EXPECT_EQ(o.dev.shadow_view, 2);
    EXPECT_TRUE(o.dev.mip_view);
    EXPECT_EQ(o.dev.warmup_ms, 0);
    EXPECT_EQ(o.width, 64u);  // the students' options still parse beside them
}

TEST(Cli, DeveloperOptionMistakes) {
    EXPECT_CONTAINS(error_of({"--dev-fail-after-submit", "x"}), "expected a whole number");
    EXPECT_CONTAINS(error_of({"--dev-fail-after-submit", "0"}), "out of range");
    EXPECT_CONTAINS(error_of({"--dev-shadow-view", "-1"}), "out of range");
    EXPECT_CONTAINS(error_of({"--dev-warmup-ms", "-1"}), "out of range");
    EXPECT_CONTAINS(error_of({"--dev-no-blit=1"}), "takes no value");
    EXPECT_CONTAINS(error_of({"--dev-mip-view=1"}), "takes no value");
    EXPECT_CONTAINS(error_of({"--dev-status-file"}), "missing value");
    EXPECT_CONTAINS(error_of({"--dev-animate-light"}), "did you mean --dev-animate-lights?");
    EXPECT_CONTAINS(error_of({"--dev-whatever-else"}), "see --help-dev");
}

TEST(Cli, HelpDevListsEveryDeveloperOptionAndHelpDoesNot) {
    EXPECT_TRUE(parse({"--help-dev"}).help_dev);
    EXPECT_TRUE(parse({"--width", "x", "--help-dev"}).help_dev);  // wins over mistakes, as --help does
    const std::string dev = lab::dev_usage("lab4_shadows");
    const std::string students = lab::usage("lab4_shadows");
    for (const lab::OptionSpec& spec : lab::dev_option_specs()) {
        EXPECT_CONTAINS(dev, std::string("--") + spec.name);
        EXPECT_EQ(students.find(spec.name), std::string::npos) << spec.name << " is in the students' --help";
    }
}

// --- PNG files ------------------------------------------------------------------

namespace {


// 3×2 pixels, all different, including transparent and half-transparent alpha.
lab::Image8 test_image() {
    lab::Image8 image;
    image.width = 3;
    image.height = 2;
    image.rgba = {255, 0,   0,   255, 0,  255, 0,  255, 0,   0,   255, 255,  // top row
                  10,  20,  30,  0,   40, 50,  60, 128, 255, 255, 255, 255};
    return image;
}

std::string file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string png_error(const std::string& path) {
    try {
        lab::read_png(path);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected an error reading " << path;
    return "";
}

}  // namespace

TEST(ImageIo, RoundTripKeepsEveryByte) {
    TempDir dir;
    const std::string path = dir.file("out.png");
    const lab::Image8 original = test_image();
    lab::write_png(path, original);
    const lab::Image8 back = lab::read_png(path);
    EXPECT_EQ(back.width, 3);
    EXPECT_EQ(back.height, 2);
    EXPECT_EQ(back.rgba, original.rgba);
    EXPECT_FALSE(fs::exists(path + ".tmp")) << "the temporary file is renamed away";
}

TEST(ImageIo, SamePixelsGiveIdenticalFiles) {
    TempDir dir;
    lab::write_png(dir.file("a.png"), test_image());
    lab::write_png(dir.file("b.png"), test_image());
    const std::string a = file_bytes(dir.file("a.png"));
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a, file_bytes(dir.file("b.png")));
    EXPECT_EQ(a.substr(1, 3), "PNG");
}

TEST(ImageIo, OverwritesAnExistingFile) {
    TempDir dir;
    const std::string path = dir.file("same.png");
    lab::write_png(path, test_image());
    lab::Image8 one_pixel;
    one_pixel.width = one_pixel.height = 1;
    one_pixel.rgba = {1, 2, 3, 4};
    lab::write_png(path, one_pixel);
    EXPECT_EQ(lab::read_png(path).rgba, one_pixel.rgba);
}

TEST(ImageIo, WriteErrorsNameTheFile) {
    TempDir dir;
    const std::string path = dir.file("no/such/folder/x.png");
    try {
        lab::write_png(path, test_image());
        FAIL() << "expected an error";
    } catch (const std::runtime_error& e) {
        EXPECT_CONTAINS(e.what(), "x.png");
        EXPECT_CONTAINS(e.what(), "No such file or directory");
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
    EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST(ImageIo, InconsistentImagesAreNotWritten) {
    TempDir dir;
    lab::Image8 bad = test_image();
    bad.rgba.pop_back();
    EXPECT_THROW(lab::write_png(dir.file("bad.png"), bad), std::runtime_error);
    EXPECT_THROW(lab::write_png(dir.file("empty.png"), lab::Image8{}), std::runtime_error);
    EXPECT_FALSE(fs::exists(dir.file("bad.png")));
    EXPECT_FALSE(fs::exists(dir.file("empty.png")));
}

TEST(ImageIo, MissingFile) {
    TempDir dir;
    const std::string path = dir.file("missing.png");
    const std::string message = png_error(path);
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_CONTAINS(message, "No such file or directory");
}

TEST(ImageIo, NotAPng) {
    TempDir dir;
    const std::string path = dir.file("text.png");
    std::ofstream(path) << "this is not an image";
    const std::string message = png_error(path);
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_CONTAINS(message, "not a PNG");
    std::ofstream(dir.file("empty.png"));
    EXPECT_CONTAINS(png_error(dir.file("empty.png")), "not a PNG");
}

TEST(ImageIo, TruncatedPngIsCorrupt) {
    TempDir dir;
    lab::write_png(dir.file("whole.png"), test_image());
    const std::string bytes = file_bytes(dir.file("whole.png"));
    const std::string path = dir.file("cut.png");
    std::ofstream(path, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    const std::string message = png_error(path);
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_CONTAINS(message, "corrupt");
}

TEST(ImageIo, ReadingAFolderFails) {
    TempDir dir;
    fs::create_directories(dir.file("folder.png"));
    EXPECT_CONTAINS(png_error(dir.file("folder.png")), "is a directory");
}
