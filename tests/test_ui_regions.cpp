// Which UI pixels are copied and which are blended (common/app/ui_regions.h), checked against real
// ImGui draw data and pixel by pixel: the copied pixels are exactly the opaque panels, no pixel is
// copied or blended twice, and nothing translucent is ever copied.
#include "ui_regions.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <functional>
#include <vector>

namespace {

using lab::PixelRect;
using lab::UiRegions;

constexpr int kWidth = 640, kHeight = 480;

// How many rectangles of `rects` cover each pixel of the framebuffer.
std::vector<int> coverage(const std::vector<PixelRect>& rects, int width = kWidth, int height = kHeight) {
    std::vector<int> count(size_t(width) * size_t(height), 0);
    for (const PixelRect& r : rects) {
        EXPECT_GE(r.x0, 0);
        EXPECT_GE(r.y0, 0);
        EXPECT_LE(r.x1, width);
        EXPECT_LE(r.y1, height);
        EXPECT_FALSE(r.empty());
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) ++count[size_t(y) * size_t(width) + size_t(x)];
    }
    return count;
}

bool inside(const PixelRect& r, int x, int y) { return x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1; }

// An ImGui context with the labs' opaque panels (or ImGui's translucent dark style).
class UiRegionsTest : public ::testing::Test {
protected:
    void SetUp() override {
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;
        io.DisplaySize = ImVec2(float(kWidth), float(kHeight));
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);  // builds the atlas
        ImGui::StyleColorsDark();
    }
    void TearDown() override { ImGui::DestroyContext(); }

    void opaque_style() {
        ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 1.0f;
        ImGui::GetStyle().Colors[ImGuiCol_PopupBg].w = 1.0f;
    }
    // One UI frame: `build` makes the windows; the regions of its draw data.
    UiRegions frame(const std::function<void()>& build, bool allow_copy = true, ImVec2 scale = ImVec2(1, 1)) {
        ImGuiIO& io = ImGui::GetIO();
        io.DisplayFramebufferScale = scale;
        io.DeltaTime = 1.0f / 60.0f;
        ImGui::NewFrame();
        build();
        ImGui::Render();
        return lab::find_ui_regions(*ImGui::GetDrawData(), int(float(kWidth) * scale.x), int(float(kHeight) * scale.y),
                                    io.Fonts->TexUvWhitePixel, allow_copy);
    }
    static void window(const char* name, ImVec2 pos, ImVec2 size, ImGuiWindowFlags flags = 0) {
        ImGui::SetNextWindowPos(pos);
        ImGui::SetNextWindowSize(size);
        ImGui::Begin(name, nullptr, flags);
        ImGui::Text("some text");
        ImGui::Button("a button");
        ImGui::End();
    }
};

TEST(SubtractRect, PiecesAreDisjointAndCoverExactlyTheDifference) {
    const PixelRect a{10, 20, 50, 60};
    const std::vector<PixelRect> cuts{{0, 0, 5, 5},      {30, 30, 40, 40}, {0, 0, 100, 100}, {10, 20, 50, 30},
                                      {45, 10, 70, 70},   {20, 10, 30, 70}, {50, 20, 60, 60}, {10, 20, 50, 60}};
    for (const PixelRect& b : cuts) {
        std::vector<PixelRect> pieces;
        lab::subtract_rect(a, b, pieces);
        const std::vector<int> count = coverage(pieces, 100, 100);
        for (int y = 0; y < 100; ++y)
            for (int x = 0; x < 100; ++x)
                ASSERT_EQ(count[size_t(y) * 100 + size_t(x)], inside(a, x, y) && !inside(b, x, y) ? 1 : 0)
                    << "pixel " << x << "," << y << " of a − {" << b.x0 << "," << b.y0 << "," << b.x1 << "," << b.y1 << "}";
    }
}

TEST_F(UiRegionsTest, AnOpaquePanelIsCopiedWholeAndOnlyItsRimIsBlended) {
    opaque_style();
    const UiRegions r = frame([] { window("panel", ImVec2(100, 50), ImVec2(300, 200)); });
    const PixelRect panel{100, 50, 400, 250};
    const std::vector<int> copied = coverage(r.copy), blended = coverage(r.blend);
    int64_t copied_px = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const size_t i = size_t(y) * kWidth + size_t(x);
            ASSERT_LE(copied[i] + blended[i], 1) << "pixel " << x << "," << y << " is drawn twice";
            if (copied[i]) {
                ASSERT_TRUE(inside(panel, x, y)) << "copied pixel " << x << "," << y << " outside the panel";
                ++copied_px;
            }
            if (copied[i] || blended[i]) {
                ASSERT_TRUE(inside(r.bounds, x, y));
            }
        }
    // The background and title bar cover the whole window: every pixel of it is copied.
    EXPECT_EQ(copied_px, panel.area());
}

TEST_F(UiRegionsTest, TranslucentPanelsAreNeverCopied) {
    // ImGui's own dark style: the window background is 94 % opaque.
    const UiRegions r = frame([] { window("panel", ImVec2(100, 50), ImVec2(300, 200)); });
    EXPECT_TRUE(r.copy.empty());
    ASSERT_EQ(r.blend.size(), 1u);
    EXPECT_LE(r.blend[0].x0, 100);
    EXPECT_GE(r.blend[0].x1, 400);
    EXPECT_LE(r.blend[0].y0, 50);
    EXPECT_GE(r.blend[0].y1, 250);
}

TEST_F(UiRegionsTest, WithoutCopiesEverythingIsBlended) {
    opaque_style();
    const UiRegions r = frame([] { window("panel", ImVec2(100, 50), ImVec2(300, 200)); }, false);
    EXPECT_TRUE(r.copy.empty());
    ASSERT_EQ(r.blend.size(), 1u);
}

TEST_F(UiRegionsTest, WindowsWithoutBackgroundCopyOnlyTheirTitleBar) {
    opaque_style();
    const UiRegions r = frame([] { window("glass", ImVec2(100, 50), ImVec2(300, 200), ImGuiWindowFlags_NoBackground); });
    const float title = ImGui::GetFontSize() + ImGui::GetStyle().FramePadding.y * 2.0f;
    int64_t copied_px = 0;
    for (const PixelRect& c : r.copy) {
        EXPECT_GE(c.y0, 50);
        EXPECT_LE(c.y1, 50 + int(title) + 1);
        copied_px += c.area();
    }
    EXPECT_GT(copied_px, 0);
    const UiRegions none = frame([] {
        window("bare", ImVec2(100, 50), ImVec2(300, 200), ImGuiWindowFlags_NoBackground | ImGuiWindowFlags_NoTitleBar);
    });
    EXPECT_TRUE(none.copy.empty());
    EXPECT_FALSE(none.blend.empty());
}

TEST_F(UiRegionsTest, OverlappingPanelsAreCopiedOnceAndBlendedOnce) {
    opaque_style();
    const UiRegions r = frame([] {
        window("first", ImVec2(40, 40), ImVec2(200, 150));
        window("second", ImVec2(150, 100), ImVec2(220, 180));
    });
    const PixelRect first{40, 40, 240, 190}, second{150, 100, 370, 280};
    const std::vector<int> copied = coverage(r.copy), blended = coverage(r.blend);
    int64_t copied_px = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const size_t i = size_t(y) * kWidth + size_t(x);
            ASSERT_LE(copied[i] + blended[i], 1) << "pixel " << x << "," << y << " is drawn twice";
            ASSERT_EQ(copied[i], inside(first, x, y) || inside(second, x, y) ? 1 : 0) << "pixel " << x << "," << y;
            copied_px += copied[i];
        }
    EXPECT_EQ(copied_px, first.area() + second.area() - 90 * 90);  // their overlap [150,240) × [100,190)
}

TEST_F(UiRegionsTest, FramebufferScaleScalesTheRegions) {
    opaque_style();
    const UiRegions r = frame([] { window("panel", ImVec2(100, 50), ImVec2(150, 100)); }, true, ImVec2(2, 2));
    int64_t copied_px = 0;
    for (const PixelRect& c : r.copy) {
        EXPECT_GE(c.x0, 200);
        EXPECT_LE(c.x1, 500);
        EXPECT_GE(c.y0, 100);
        EXPECT_LE(c.y1, 300);
        copied_px += c.area();
    }
    EXPECT_EQ(copied_px, 300 * 200);
}

TEST_F(UiRegionsTest, NoWindowsNoRegions) {
    opaque_style();
    const UiRegions r = frame([] {});
    EXPECT_TRUE(r.copy.empty());
    EXPECT_TRUE(r.blend.empty());
    EXPECT_TRUE(r.bounds.empty());
}

}  // namespace
