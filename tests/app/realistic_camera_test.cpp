// Camera "realistic" through the phos binary: a double-Gauss lens focused on a glowing half-plane
// shows its edge sharp, and blurred when focused elsewhere; the image is upright and unmirrored (as
// the perspective camera shows it); film corners the lens cannot see are exactly black under every
// integrator (blocked rays contribute nothing), and the integrators agree where the lens sees.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/image/image_io.h"
#include "support/double_gauss_lens.h"
#include "test_util.h"

namespace phos {
namespace {

using testing::CommandResult;
using testing::run_phos;
using testing::TempDir;

// A glowing quad over world x < 0, 1 m in front of the camera (pbrt's camera space: the film at
// the origin, looking along +z), 48 x 32 pixels.
std::string edge_scene(const std::string& camera, const std::string& film = "") {
    return "Film \"rgb\" \"integer xresolution\" [ 48 ] \"integer yresolution\" [ 32 ] " + film +
           "\nLookAt 0 0 0  0 0 1  0 1 0\n" + camera +
           "\nWorldBegin\n"
           "AttributeBegin\n"
           "AreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\n"
           "Shape \"trianglemesh\" \"point3 P\" [ -3 -2 1  0 -2 1  0 2 1  -3 2 1 ] "
           "\"integer indices\" [ 0 2 1 0 3 2 ]\n"
           "AttributeEnd\n";
}

Image render(const TempDir& dir, const std::string& name, const std::string& text, const std::string& args) {
    const std::string file = dir.write(name + ".pbrt", text);
    const CommandResult r =
        run_phos("render " + file + " --seed 5 -o " + dir.file(name + ".pfm") + " " + args);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return io::read_image(dir.file(name + ".pfm"), false);
}

// Over the middle rows: the bright side's level beside the edge (x in [19, 23)) and the light
// spilt onto the dark side (x from 25 on) in units of it. The edge's image is the film's centre
// line, between x = 23 and 24.
double spill(const Image& img, double& bright) {
    double level = 0, spilt = 0;
    for (int y = 12; y < 20; ++y) {
        for (int x = 19; x < 23; ++x) level += img.at(x, y).average() / 32;
        for (int x = 25; x < img.width; ++x) spilt += img.at(x, y).average() / 8;
    }
    bright = level;
    return spilt / level;
}

std::string realistic(double focus, double aperture) {
    return "Camera \"realistic\" \"string lensfile\" \"dgauss.dat\" \"float aperturediameter\" " +
           std::to_string(aperture) + " \"float focusdistance\" " + std::to_string(focus);
}

TEST(RealisticCamera, TheFocusedEdgeIsSharpAndTheDefocusedOneBlurred) {
    TempDir dir;
    dir.write("dgauss.dat", testing::kDoubleGaussLens);
    const std::string args = "--integrator path --spp 64 --filter box --filter-radius 0.5";
    const Image focused = render(dir, "focused", edge_scene(realistic(1.0, 17)), args);
    const Image blurred = render(dir, "blurred", edge_scene(realistic(0.3, 17)), args);
    double b_focused, b_blurred;
    const double s_focused = spill(focused, b_focused), s_blurred = spill(blurred, b_blurred);
    EXPECT_GT(b_focused, 0.01);  // not black
    EXPECT_GT(b_blurred, 0.01);
    EXPECT_LT(s_focused, 0.1);
    EXPECT_GT(s_blurred, 0.3);
    // Bright on the left, dark on the right, as the perspective camera shows the scene.
    const Image pinhole = render(dir, "pinhole", edge_scene("Camera \"perspective\" \"float fov\" 30"), args);
    for (const Image* img : {&focused, &pinhole}) {
        EXPECT_GT(img->at(4, 16).average(), 0.01);
        EXPECT_EQ(img->at(43, 16).average(), 0.0f);
    }
    // The lens's brightness: pbrt-v4's weight makes the glow L = 1 about the projected solid angle
    // of the exit pupil seen from the film, pi / (4 N^2 + 1) at f-number N ~ f / aperture.
    EXPECT_GT(b_focused, 0.02);
    EXPECT_LT(b_focused, 0.5);
}

TEST(RealisticCamera, BlockedRaysAreBlackForEveryIntegrator) {
    TempDir dir;
    dir.write("dgauss.dat", testing::kDoubleGaussLens);
    // A uniform white sky seen through a film far wider than the lens covers (100 mm diagonal):
    // the corners receive no ray, the centre the sky through the lens.
    const std::string text =
        "Film \"rgb\" \"integer xresolution\" [ 24 ] \"integer yresolution\" [ 16 ] "
        "\"float diagonal\" 100\n" +
        realistic(1.0, 17) +
        "\nWorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
        "Material \"diffuse\"\nTranslate 1.5 1 2\nShape \"sphere\" \"float radius\" 0.05\n";
    double centre_path = 0;
    for (const char* integrator : {"path", "bdpt", "vcm", "sppm", "photonmap"}) {
        const Image img =
            render(dir, integrator, text, std::string("--integrator ") + integrator + " --spp 32");
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                ASSERT_TRUE(std::isfinite(img.at(x, y).average())) << integrator;
        EXPECT_EQ(img.at(0, 0).average(), 0.0f) << integrator;
        EXPECT_EQ(img.at(23, 15).average(), 0.0f) << integrator;
        // The sky near the axis (the sphere is far off it).
        double centre = 0;
        for (int y = 7; y < 9; ++y)
            for (int x = 10; x < 14; ++x) centre += img.at(x, y).average() / 8;
        EXPECT_GT(centre, 0.01) << integrator;
        if (centre_path == 0)
            centre_path = centre;
        else
            EXPECT_NEAR(centre / centre_path, 1.0, 0.1) << integrator;
    }
}

}  // namespace
}  // namespace phos
