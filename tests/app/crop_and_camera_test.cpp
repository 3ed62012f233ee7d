// Cropped renders and the spherical camera through the phos binary: a crop (Film cropwindow /
// pixelbounds, --crop-window / --pixel-bounds) writes only its part of the image, and that part
// shows what the same region of the whole image shows — for path tracing and for bdpt, whose light
// tracing weighs its splats by the film area the crop samples. A spherical camera inside a
// uniformly glowing sphere sees the same radiance in every pixel, for both mappings and for path
// and bdpt (light tracing projects onto the sphere of directions with the camera's importance).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/image/image_io.h"
#include "test_util.h"

namespace phos {
namespace {

using testing::CommandResult;
using testing::run_phos;
using testing::TempDir;

// A lit sphere on a floor, 32 x 32 pixels; `film` adds Film parameters.
std::string sphere_scene(const std::string& film) {
    return "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ] " + film +
           "\n"
           "LookAt 0 1 6  0 0.5 0  0 1 0\n"
           "Camera \"perspective\" \"float fov\" [ 40 ]\n"
           "WorldBegin\n"
           "LightSource \"point\" \"point3 from\" [ 2 4 3 ] \"rgb I\" [ 20 20 20 ]\n"
           "Material \"diffuse\" \"rgb reflectance\" [ 0.6 0.5 0.4 ]\n"
           "Shape \"sphere\" \"float radius\" 1\n"
           "Shape \"trianglemesh\" \"point3 P\" [ -9 -1 -9 9 -1 -9 9 -1 9 -9 -1 9 ] "
           "\"integer indices\" [ 0 2 1 0 3 2 ]\n";
}

Image render(const TempDir& dir, const std::string& name, const std::string& text, const std::string& args) {
    const std::string file = dir.write(name + ".pbrt", text);
    const CommandResult r =
        run_phos("render " + file + " --seed 3 -o " + dir.file(name + ".pfm") + " " + args);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return io::read_image(dir.file(name + ".pfm"), false);
}

double region_mean(const Image& img, int x0, int y0, int w, int h) {
    double sum = 0;
    for (int y = y0; y < y0 + h; ++y)
        for (int x = x0; x < x0 + w; ++x) sum += img.at(x, y).average();
    return sum / (double(w) * h);
}

TEST(Crop, TheCropShowsItsRegionOfTheWholeImage) {
    TempDir dir;
    for (const char* integrator : {"path", "bdpt"}) {
        const std::string args = std::string("--integrator ") + integrator + " --spp 64";
        const Image whole = render(dir, "whole", sphere_scene(""), args);
        // Pixels [8, 24) x [4, 20): the sphere's lit side and some floor.
        const Image cropped =
            render(dir, "crop", sphere_scene("\"integer pixelbounds\" [ 8 24 4 20 ]"), args);
        ASSERT_EQ(cropped.width, 16);
        ASSERT_EQ(cropped.height, 16);
        const double a = region_mean(whole, 8, 4, 16, 16), b = region_mean(cropped, 0, 0, 16, 16);
        EXPECT_NEAR(b / a, 1.0, 0.03) << integrator;
        // Pixel by pixel within noise (a few percent at 64 samples).
        double err = 0;
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
                err += std::fabs(cropped.at(x, y).average() - whole.at(x + 8, y + 4).average());
        EXPECT_LT(err / 256 / a, 0.06) << integrator;
    }
    // The same by fractions on the command line: [ceil(32 x 0.25), ceil(32 x 0.75)) = [8, 24).
    const Image by_window = render(dir, "window", sphere_scene(""),
                                   "--integrator path --spp 4 --crop-window 0.25 0.75 0.125 0.625");
    EXPECT_EQ(by_window.width, 16);
    EXPECT_EQ(by_window.height, 16);
}

TEST(Crop, BoundsOutsideTheImageAreRefused) {
    TempDir dir;
    const std::string file = dir.write("s.pbrt", sphere_scene(""));
    const CommandResult r = run_phos("render " + file + " --pixel-bounds 0 40 0 8 -o " + dir.file("x.pfm"));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("pixel-bounds"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("x.pfm")));
}

TEST(SphericalCamera, AGlowingSphereLooksUniformInEveryDirection) {
    TempDir dir;
    for (const char* mapping : {"equalarea", "equirectangular"})
        for (const char* integrator : {"path", "bdpt"}) {
            const std::string text =
                std::string(
                    "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\n"
                    "Camera \"spherical\" \"string mapping\" \"") +
                mapping +
                "\"\n"
                "WorldBegin\n"
                "AttributeBegin\n"
                "AreaLightSource \"diffuse\" \"rgb L\" [ 0.5 0.5 0.5 ]\n"
                "ReverseOrientation\n"
                "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
                "Shape \"sphere\" \"float radius\" 3\n"
                "AttributeEnd\n";
            // Radiance everywhere: L / (1 - albedo) = 1 (a furnace), whatever direction a pixel looks.
            const Image img = render(dir, std::string("sph-") + mapping + integrator, text,
                                     std::string("--integrator ") + integrator + " --spp 64 --max-depth 100");
            const double mean = region_mean(img, 0, 0, 16, 16);
            EXPECT_NEAR(mean, 1.0, 0.03) << mapping << " " << integrator;
            // Rows near the poles of the equirectangular map too.
            EXPECT_NEAR(region_mean(img, 0, 0, 16, 2), 1.0, 0.06) << mapping << " " << integrator;
        }
}

}  // namespace
}  // namespace phos
