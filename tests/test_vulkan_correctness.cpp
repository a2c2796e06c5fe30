// test_vulkan_correctness.cpp — the framework's Vulkan obligations, checked on every lab binary.
//
// Each test runs a real lab as a user would (with --validate: the Khronos layer with
// synchronization validation and best practices, where any message fails the run):
//  - a failure injected right after a frame is submitted (--dev-fail-after-submit N, a
//    test-only hook: common/dev/instruments.cpp) must end the run with exit code 1 and
//    *no* validation message: the frame loop waits for the GPU before the lab's renderer
//    (a local of the lab's body) is destroyed while the stack unwinds;
//  - --validate really reports synchronization hazards and best-practices warnings;
//  - an image larger than the device allows (its limits queried here, independently of the
//    labs, through the Vulkan API) is bad input: one line, exit code 2, no PNG.
#include "lab_runner.h"

#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const std::string kOutDir = test_output_dir("vulkan_correctness");

struct LabExe {
    const char* name;
    const char* path;
};
const LabExe kLabs[] = {{"lab1_camera", LAB1_EXE}, {"lab2_lighting", LAB2_EXE}};

bool has_xvfb_run() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }

// Runs `lab` with `args` (lab_runner.h), the log in test_output/vulkan_correctness/LAB_NAME.log; in
// a window under xvfb-run, judged by the lab's own exit code.
RunResult run_case(const LabExe& lab, const std::string& args, const std::string& name, bool window = false) {
    const std::string log = kOutDir + "/" + lab.name + "_" + name + ".log";
    return window ? run_lab_in_window(lab.path, args, log) : run_lab(lab.path, args, log);
}

bool mentions_validation(const std::string& log) { return log.find("validation") != std::string::npos; }

// --- resources outlive the frames that use them -----------------------------------------

// Headless: with two frames in flight, a throw right after the first or second submit used
// to destroy the renderer's pipelines and memory while the GPU still ran them
// (VUID-vkDestroyPipeline-pipeline-00765, VUID-vkFreeMemory-memory-00677).
TEST(VulkanCorrectness, FailureAfterSubmitHeadlessExitsWithCode1ValidationClean) {
    for (const LabExe& lab : kLabs) {
        for (int n : {1, 2}) {
            SCOPED_TRACE(std::string(lab.name) + " N=" + std::to_string(n));
            const std::string png = kOutDir + "/" + lab.name + "_fail_" + std::to_string(n) + ".png";
            std::error_code ec;
            fs::remove(png, ec);
            const RunResult run =
                run_case(lab, "--dev-fail-after-submit " + std::to_string(n) +
                             " --headless --validate --frames 4 --width 96 --height 64 --out " + quoted(png),
                    "fail_after_submit_" + std::to_string(n));
            EXPECT_EQ(run.exit_code, 1) << run.log;
            EXPECT_NE(run.log.find("--dev-fail-after-submit"), std::string::npos) << run.log;
            EXPECT_FALSE(mentions_validation(run.log)) << run.log;
            EXPECT_FALSE(fs::exists(png)) << "a failed run wrote " << png;
        }
    }
}

// The same in a window (swapchain, ImGui), under a virtual X server.
TEST(VulkanCorrectness, FailureAfterSubmitInWindowExitsWithCode1ValidationClean) {
    if (!has_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup.sh installs xvfb)";
    for (const LabExe& lab : kLabs) {
        SCOPED_TRACE(lab.name);
        const RunResult run = run_case(lab, "--dev-fail-after-submit 3 --validate --frames 30", "fail_after_submit_window",
                                    /*window=*/true);
        EXPECT_EQ(run.exit_code, 1) << run.log;
        EXPECT_NE(run.log.find("--dev-fail-after-submit"), std::string::npos) << run.log;
        EXPECT_FALSE(mentions_validation(run.log)) << run.log;
    }
}

// --- --validate is strict ------------------------------------------------------------------

// --dev-validation-probe makes the lab commit one mistake for each of the stricter checks
// (a write-after-write hazard, a command pool with per-buffer reset): both must be reported.
TEST(VulkanCorrectness, ValidateReportsSynchronizationHazardsAndBestPractices) {
    for (const LabExe& lab : kLabs) {
        for (bool window : {false, true}) {
            if (window && !has_xvfb_run()) continue;
            SCOPED_TRACE(std::string(lab.name) + (window ? " window" : " headless"));
            const RunResult run = run_case(lab,
                                        window ? "--dev-validation-probe --validate --frames 2"
                                               : "--dev-validation-probe --validate --headless --frames 1 --width 32 "
                                                 "--height 32 --out " + quoted(kOutDir + "/probe.png"),
                                        window ? "probe_window" : "probe_headless", window);
            EXPECT_EQ(run.exit_code, 1) << run.log;
            EXPECT_NE(run.log.find("SYNC-HAZARD-WRITE-AFTER-WRITE"), std::string::npos) << run.log;
            EXPECT_NE(run.log.find("BestPractices-vkCreateCommandPool-command-buffer-reset"), std::string::npos)
                << run.log;
            EXPECT_NE(run.log.find("error: 2 validation messages"), std::string::npos) << run.log;
        }
    }
}

// --- the device's image size limit ---------------------------------------------------------

// The largest image side any Vulkan device on this machine allows for a colour attachment
// (min of maxImageDimension2D and maxFramebufferWidth/Height), asked of the driver directly.
uint32_t largest_side_any_device_allows() {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_1;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    VkInstance instance = VK_NULL_HANDLE;
    if (vkCreateInstance(&info, nullptr, &instance) != VK_SUCCESS) return 0;
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance, &count, devices.data());
    uint32_t largest = 0;
    for (VkPhysicalDevice d : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(d, &p);
        largest = std::max(largest, std::min({p.limits.maxImageDimension2D, p.limits.maxFramebufferWidth,
                                              p.limits.maxFramebufferHeight}));
    }
    vkDestroyInstance(instance, nullptr);
    return largest;
}

TEST(VulkanCorrectness, ImageLargerThanTheDeviceAllowsExitsWithCode2) {
    const uint32_t limit = largest_side_any_device_allows();
    ASSERT_GE(limit, 4096u) << "no Vulkan device, or one below the guaranteed minimum";
    const std::string too_big = std::to_string(limit + 1);
    for (const LabExe& lab : kLabs) {
        for (const std::string option : {"--width", "--height"}) {
            SCOPED_TRACE(std::string(lab.name) + " " + option);
            const std::string png = kOutDir + "/" + lab.name + "_too_big.png";
            std::error_code ec;
            fs::remove(png, ec);
            const std::string other = option == "--width" ? "--height 8" : "--width 8";
            const RunResult run = run_case(lab, "--validate --out " + quoted(png) + " " + option + " " +
                                                            too_big + " " + other,
                                               "too_big" + option);
            EXPECT_EQ(run.exit_code, 2) << run.log;
            // One line: "--width 16385: the device allows at most 16384".
            EXPECT_NE(run.log.find(option + " " + too_big + ": the device allows at most " + std::to_string(limit)),
                      std::string::npos)
                << run.log;
            EXPECT_EQ(std::count(run.log.begin(), run.log.end(), '\n'), 1) << run.log;
            EXPECT_FALSE(fs::exists(png));
        }
    }
}

// In a window the same check runs before the (hidden) window is shown.
TEST(VulkanCorrectness, WindowLargerThanTheDeviceAllowsExitsWithCode2) {
    if (!has_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup.sh installs xvfb)";
    const uint32_t limit = largest_side_any_device_allows();
    ASSERT_GE(limit, 4096u);
    const std::string too_big = std::to_string(limit + 1);
    const LabExe& lab = kLabs[0];
    const RunResult run =
        run_case(lab, "--validate --frames 1 --height 64 --width " + too_big, "too_big_window", true);
    EXPECT_EQ(run.exit_code, 2) << run.log;
    EXPECT_NE(run.log.find("--width " + too_big + ": the device allows at most " + std::to_string(limit)),
              std::string::npos)
        << run.log;
}

// The largest size the device allows is accepted (a one-pixel-high strip keeps it cheap).
TEST(VulkanCorrectness, ImageAsWideAsTheDeviceAllowsRenders) {
    const uint32_t limit = largest_side_any_device_allows();
    ASSERT_GE(limit, 4096u);
    for (const LabExe& lab : kLabs) {
        SCOPED_TRACE(lab.name);
        const std::string png = kOutDir + "/" + lab.name + "_widest.png";
        const RunResult run = run_case(
            lab, "--validate --out " + quoted(png) + " --width " + std::to_string(limit) + " --height 2", "widest");
        EXPECT_EQ(run.exit_code, 0) << run.log;
        EXPECT_TRUE(fs::exists(png));
    }
}

}  // namespace
