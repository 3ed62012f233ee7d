// The --preview window under Xvfb (a virtual X server, Debian's xvfb, installed by
// scripts/setup.sh): it opens, shows the image as rendered (its framebuffer, read back when it
// closes, equals the PNG output pixel for pixel at the window's magnification), and the render
// ends by itself unless --preview-hold; without a display --preview warns once and renders on. Its
// keys are pressed for real (xdotool, tests/app/preview_keys.sh) and do what docs/usage.md says.
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

double mean(const Image& image) {
    double sum = 0;
    for (const Rgb& p : image.pixels) sum += p.average();
    return sum / double(image.pixels.size());
}

TEST(Preview, KeysChangeExposureAndLayerSaveAndQuit) {
    if (!display::preview_available()) GTEST_SKIP() << "built without GLFW";
    ASSERT_TRUE(have_xvfb()) << "xvfb-run is missing: scripts/setup.sh installs xvfb";
    ASSERT_EQ(std::system("command -v xdotool >/dev/null 2>&1"), 0) << "scripts/setup.sh installs xdotool";
    TempDir dir;
    const std::string cmd = "timeout 120 xvfb-run -a -s '-screen 0 1280x1024x24' bash " +
                            source_path("tests/app/preview_keys.sh") + " " + PHOS_BINARY + " " + kScene +
                            " " + dir.path().string() + " >/dev/null 2>&1";
    std::system(cmd.c_str());
    const std::string titles = read_bytes(dir.file("titles")), log = read_bytes(dir.file("log"));
    // Each key's effect shows in the title: exposure +0.5 after '=', -0.5 after '-' twice, the
    // next layer (caustic, the first of --layers) after 'l'; 'q' ends the render as Ctrl-C does.
    for (const char* want : {"[image, exposure +0.0]", "[image, exposure +0.5]", "[image, exposure -0.5]",
                             "[caustic, exposure -0.5]", "exit 130"})
        EXPECT_NE(titles.find(want), std::string::npos) << want << " not in:\n" << titles << log;
    EXPECT_NE(log.find("preview: saved caustic to " + dir.file("out.snapshot-1.exr")), std::string::npos)
        << log;
    EXPECT_NE(log.find("warning: interrupted: the image holds the work done so far"), std::string::npos)
        << log;
    ASSERT_TRUE(std::filesystem::exists(dir.file("out.exr"))) << log;
    ASSERT_TRUE(std::filesystem::exists(dir.file("out.snapshot-1.exr"))) << log;
    // The snapshot is the layer shown (the caustic layer of a box without glass: nearly black),
    // not the image.
    const Image image = io::read_image(dir.file("out.exr")),
                snapshot = io::read_image(dir.file("out.snapshot-1.exr"));
    EXPECT_EQ(snapshot.width, 64);
    EXPECT_EQ(snapshot.height, 48);
    EXPECT_GT(mean(image), 0.01);
    EXPECT_LT(mean(snapshot), 0.1 * mean(image));
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
