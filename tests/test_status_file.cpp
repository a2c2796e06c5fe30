// The status line a window writes for bench/soak.py (common/dev/status_file.h): one whole line per
// frame, and the same line marked " idle" once the lab has gone idle after drawing.
#include "status_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace {
std::string read_all(const std::filesystem::path& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
}  // namespace

TEST(StatusFile, FramesCountedIdleMarkedAndClearedByTheNextFrame) {
    const auto path = std::filesystem::path(testing::TempDir()) / "lab_status_test.txt";
    std::filesystem::remove(path);
    lab::dev::StatusFile status(path.string());
    EXPECT_FALSE(std::filesystem::exists(path));  // nothing before the first frame

    status.frame_drawn(640, 480);
    EXPECT_EQ(read_all(path), "frame=1 width=640 height=480\n");
    status.frame_drawn(1, 1);
    EXPECT_EQ(read_all(path), "frame=2 width=1 height=1\n");
    status.went_idle();  // same frame and size, marked idle
    EXPECT_EQ(read_all(path), "frame=2 width=1 height=1 idle\n");
    status.frame_drawn(800, 600);  // a new frame is not idle
    EXPECT_EQ(read_all(path), "frame=3 width=800 height=600\n");
    EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));  // the temporary was renamed
    std::filesystem::remove(path);
}
