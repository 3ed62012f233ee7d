// `phos photons --view` under Xvfb: the viewer opens, draws the photons over the scene's outline
// (its framebuffer, written with --screenshot, is far from blank and holds more lit pixels with
// both maps than with the caustic map alone), and --screenshot without --view is refused.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

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

int view(const std::string& maps, const std::string& shot) {
    const std::string cmd = "xvfb-run -a -s '-screen 0 1280x1024x24' " + std::string(PHOS_BINARY) +
                            " photons " + kScene + " --global 20000 --caustic 20000 --maps " + maps +
                            " --view --screenshot " + shot + " -q 2>&1";
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
