// `phos photons --view` under Xvfb: the viewer opens, draws the photons over the scene's outline
// (its framebuffer, written with --screenshot, is far from blank and holds more lit pixels with
// both maps than with the caustic map alone), and --screenshot without --view is refused.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <regex>

#include "display/preview_window.h"
#include "io/image/image_io.h"
#include "io/image/tonemap.h"
#include "test_util.h"

namespace phos::testing {
namespace {

const std::string kScene = shared_path("bench/scn/cornell-glass-mirror.scn");

// Pixels clearly brighter than the viewer's background (0.08, 0.08, 0.09).
int lit_pixels(const Image& img) {
    int n = 0;
    for (const Rgb& p : img.pixels) n += io::linear_to_srgb8(p.max()) > 60;
    return n;
}

int view(const std::string& maps, const std::string& shot, const std::string& colour = "power") {
    const std::string cmd = "xvfb-run -a -s '-screen 0 1280x1024x24' " + std::string(PHOS_BINARY) +
                            " photons " + kScene + " --global 20000 --caustic 20000 --maps " + maps +
                            " --colour " + colour + " --view --screenshot " + shot + " -q 2>&1";
    return std::system(cmd.c_str());
}

TEST(PhotonViewer, DrawsThePhotonsOverTheScene) {
    if (!display::preview_available()) GTEST_SKIP() << "built without GLFW";
    ASSERT_EQ(std::system("command -v xvfb-run >/dev/null 2>&1"), 0) << "scripts/setup.sh installs xvfb";
    TempDir dir;
    ASSERT_EQ(view("global,caustic", dir.file("both.png")), 0);
    ASSERT_EQ(view("caustic", dir.file("caustic.png")), 0);
    const Image both = io::read_image(dir.file("both.png")),
                caustic = io::read_image(dir.file("caustic.png"));
    EXPECT_EQ(both.width, 1024);
    EXPECT_EQ(both.height, 768);
    const int n_both = lit_pixels(both), n_caustic = lit_pixels(caustic);
    std::printf("lit pixels: both maps %d, caustic map %d\n", n_both, n_caustic);
    EXPECT_GT(n_both, 5000) << "the viewer is (nearly) blank";
    EXPECT_GT(n_caustic, 200);
    EXPECT_GT(n_both, n_caustic * 3 / 2);  // the global map is shown too
}

TEST(PhotonViewer, ColoursByBounceCount) {
    // The caustic map alone: every photon has 1 or more bounces, so in the bounce colouring no
    // point is white (0 bounces) and most are red, orange or yellow (1 bounce off the mirror, 2 or 3
    // through the glass sphere); the power colouring draws the same points differently.
    if (!display::preview_available()) GTEST_SKIP() << "built without GLFW";
    ASSERT_EQ(std::system("command -v xvfb-run >/dev/null 2>&1"), 0) << "scripts/setup.sh installs xvfb";
    TempDir dir;
    ASSERT_EQ(view("caustic", dir.file("power.png")), 0);
    ASSERT_EQ(view("caustic", dir.file("bounces.png"), "bounces"), 0);
    const Image power = io::read_image(dir.file("power.png")),
                bounces = io::read_image(dir.file("bounces.png"));
    int white = 0, warm = 0, lit = 0;
    for (const Rgb& p : bounces.pixels) {
        const int r = io::linear_to_srgb8(p.r), g = io::linear_to_srgb8(p.g), b = io::linear_to_srgb8(p.b);
        if (std::max({r, g, b}) <= 60) continue;
        ++lit;
        white += r > 200 && g > 200 && b > 200;
        warm += r > 200 && b < 80;  // red, orange, yellow: 1-3 bounces
    }
    std::printf("bounce colouring: %d lit, %d white, %d red/orange/yellow\n", lit, white, warm);
    EXPECT_GT(lit, 200);
    EXPECT_EQ(white, 0) << "a caustic photon drawn as straight from the light";
    EXPECT_GT(warm, lit / 2);
    EXPECT_NE(power.pixels, bounces.pixels);
    EXPECT_GT(lit_pixels(power), 200);
}

TEST(PhotonViewer, KeysAndAClickDoWhatTheDocsSay) {
    // Real key presses and a click (xdotool, tests/app/photon_viewer_keys.sh); the title shows the
    // state each key changes, the click prints the picked photon's record, q closes (exit 0).
    if (!display::preview_available()) GTEST_SKIP() << "built without GLFW";
    ASSERT_EQ(std::system("command -v xvfb-run >/dev/null 2>&1"), 0) << "scripts/setup.sh installs xvfb";
    ASSERT_EQ(std::system("command -v xdotool >/dev/null 2>&1"), 0) << "scripts/setup.sh installs xdotool";
    TempDir dir;
    const std::string cmd = "timeout 120 xvfb-run -a -s '-screen 0 1280x1024x24' bash " +
                            source_path("tests/app/photon_viewer_keys.sh") + " " + PHOS_BINARY + " " +
                            kScene + " " + dir.path().string() + " >/dev/null 2>&1";
    std::system(cmd.c_str());
    const std::string titles = read_bytes(dir.file("titles")), log = read_bytes(dir.file("log"));
    for (const char* want :
         {"[colour power; maps global caustic; points 2 px]",
          "[colour map; maps global caustic; points 2 px]",
          "[colour bounces; maps global caustic; points 2 px]", "[colour power; maps caustic; points 2 px]",
          "[colour power; maps global caustic; points 3 px]", "exit 0"})
        EXPECT_NE(titles.find(want), std::string::npos) << want << " not in:\n" << titles << log;
    // The record: every PLY property, the map named, a bounce count.
    const std::regex record(
        R"(photon \d+: x \S+ y \S+ z \S+ red \d+ green \d+ blue \d+ power_r \S+ power_g \S+ )"
        R"(power_b \S+ dx \S+ dy \S+ dz \S+ nx \S+ ny \S+ nz \S+ map \d \((global|caustic)\) )"
        R"(bounces \d+)");
    EXPECT_TRUE(std::regex_search(log, record)) << log;
}

TEST(PhotonViewer, ScreenshotNeedsView) {
    TempDir dir;
    const auto r = run_phos("photons " + kScene + " --global 1000 --screenshot " + dir.file("s.png") +
                            " -o " + dir.file("p.ply"));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--screenshot is for --view"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("p.ply")));
}

}  // namespace
}  // namespace phos::testing
