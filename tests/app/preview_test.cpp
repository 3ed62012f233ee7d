// The --preview window under Xvfb (a virtual X server, Debian's xvfb, installed by
// scripts/setup.sh): it opens, shows the image as rendered (its framebuffer, read back when it
// closes, equals the PNG output pixel for pixel at the window's magnification), and the render
// ends by itself unless --preview-hold; without a display --preview warns once and renders on.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "display/preview_window.h"
#include "io/image/image_io.h"
#include "io/image/tonemap.h"
#include "test_util.h"

namespace phos::testing {
namespace {

bool have_xvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

const std::string kScene = source_path("scenes/cornell-diffuse.scn");

TEST(Preview, WindowShowsTheRenderedImage) {
    if (!display::preview_available()) GTEST_SKIP() << "built without GLFW";
    ASSERT_TRUE(have_xvfb()) << "xvfb-run is missing: scripts/setup.sh installs xvfb";
    TempDir dir;
    const std::string out = dir.file("out.png"), shot = dir.file("shot.png");
    const std::string cmd = "xvfb-run -a -s '-screen 0 1280x1024x24' " + std::string(PHOS_BINARY) +
                            " render " + kScene +
                            " --integrator path --width 64 --height 48 --spp 16 --preview " +
                            "--preview-screenshot " + shot + " -o " + out + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string output;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) output.append(buf, n);
    ASSERT_EQ(pclose(pipe), 0) << output;
    EXPECT_EQ(output.find("warning"), std::string::npos) << output;
    const Image image = io::read_image(out), window = io::read_image(shot);
    // 64 x 48 is magnified 4 x (window_size in preview_window.cpp), nearest-neighbour.
    ASSERT_EQ(window.width, 256) << output;
    ASSERT_EQ(window.height, 192) << output;
    int lit = 0, differ = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const Rgb a = image.at(x, y), b = window.at(4 * x + 1, 4 * y + 1);
            for (int c = 0; c < 3; ++c) {
                const int ca = io::linear_to_srgb8(a[c]), cb = io::linear_to_srgb8(b[c]);
                differ += std::abs(ca - cb) > 1;
                lit += cb > 10;
            }
        }
    EXPECT_GT(lit, image.width * image.height) << "the window is (nearly) blank";
    EXPECT_EQ(differ, 0) << "the window does not show the rendered image";
}

TEST(Preview, WithoutADisplayItWarnsAndRendersOn) {
    TempDir dir;
    const std::string out = dir.file("out.pfm");
    const auto r =
        run_phos_env("DISPLAY= WAYLAND_DISPLAY=", "render " + kScene +
                                                      " --integrator path --width 16 --height 16 --spp "
                                                      "1 --preview -o " +
                                                      out);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("warning: --preview: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("rendering without the window"), std::string::npos) << r.output;
    EXPECT_TRUE(std::filesystem::exists(out));
}

TEST(Preview, KeysMapToActions) {
    if (!display::preview_available()) GTEST_SKIP() << "built without GLFW";
    // GLFW key codes: '=' 61, '-' 45, 'L' 76, 'S' 83, 'Q' 81, Esc 256, Tab 258.
    EXPECT_EQ(display::preview_key(61), display::PreviewKey::ExposureUp);
    EXPECT_EQ(display::preview_key(45), display::PreviewKey::ExposureDown);
    EXPECT_EQ(display::preview_key(76), display::PreviewKey::NextLayer);
    EXPECT_EQ(display::preview_key(258), display::PreviewKey::NextLayer);
    EXPECT_EQ(display::preview_key(83), display::PreviewKey::Save);
    EXPECT_EQ(display::preview_key(81), display::PreviewKey::Quit);
    EXPECT_EQ(display::preview_key(256), display::PreviewKey::Quit);
    EXPECT_EQ(display::preview_key(65), display::PreviewKey::None);
}

}  // namespace
}  // namespace phos::testing
