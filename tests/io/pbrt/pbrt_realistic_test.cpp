// Camera "realistic": pbrt-v4's lens files read with errors at their own line and column (and the
// scene line that names them), the scene's aperture diameter narrowing the stop, focus distance
// and film diagonal reaching the camera.
#include <gtest/gtest.h>

#include <string>

#include "io/image/image_io.h"
#include "io/pbrt/lens_aperture.h"
#include "io/pbrt/lens_file.h"
#include "pbrt_test_util.h"
#include "scene/scene.h"
#include "support/double_gauss_lens.h"

namespace phos::io::pbrt {
namespace {

using test::expect_pbrt_error;
using test::PbrtTempDir;
using test::QuietLog;

void expect_lens_error(const std::string& text, int line, int col, const std::string& message) {
    phos::testing::expect_parse_error_from([&] { parse_lens_file("lens.dat", text); }, "lens.dat", line, col,
                                           message);
}

TEST(PbrtLensFile, ElementsInMetresFrontToRear) {
    const auto e = parse_lens_file("lens.dat", phos::testing::kDoubleGaussLens);
    ASSERT_EQ(e.size(), 11u);
    EXPECT_FLOAT_EQ(e[0].curvature_radius, 0.029475f);
    EXPECT_FLOAT_EQ(e[0].thickness, 0.00376f);
    EXPECT_FLOAT_EQ(e[0].eta, 1.67f);
    EXPECT_FLOAT_EQ(e[0].aperture_radius, 0.0126f);
    EXPECT_EQ(e[5].curvature_radius, 0.0f);  // the stop
    EXPECT_FLOAT_EQ(e[5].eta, 1.0f);         // eta 0: air
    EXPECT_FLOAT_EQ(e[10].thickness, 0.04f);
    // Elements may span lines; commas and '+' are accepted as pbrt-v4's float reader does.
    const auto two = parse_lens_file("lens.dat", "50 2\n1.5 20 # first\n-50, 40, +1, 20\n");
    ASSERT_EQ(two.size(), 2u);
    EXPECT_FLOAT_EQ(two[1].curvature_radius, -0.05f);
}

TEST(PbrtLensFile, BadFilesAreLocatedErrors) {
    expect_lens_error("# nothing\n", 2, 1, "no lens elements");
    expect_lens_error("50 2 1.5 20\n-50 40 x1 20\n", 2, 8, "'x1' is not a number");
    expect_lens_error("50 2 1.5 20\n-50 40 1\n", 2, 1, "3 number(s) left over");
    expect_lens_error("50 2 1.5 20\n-50 40 0.5 20\n", 2, 8, "0 (air) or at least 1");
    expect_lens_error("50 -2 1.5 20\n-50 40 1 20\n", 1, 4, "thickness must not be negative");
    expect_lens_error("50 2 1.5 20\n  -50 40 1 0\n", 2, 12, "aperture diameter must be positive");
    expect_lens_error("50 2 1.5 20\n-50 0 1 20\n", 2, 5, "distance to the film must be positive");
}

TEST(PbrtCamera, RealisticReadsItsLensFileApertureAndFocus) {
    QuietLog quiet;
    PbrtTempDir dir;
    dir.write("lenses/dgauss.dat", phos::testing::kDoubleGaussLens);
    const scene::Scene s = load_pbrt(dir.write(
        "scene.pbrt",
        "Film \"rgb\" \"float diagonal\" 24\n"
        "Camera \"realistic\" \"string lensfile\" \"lenses/dgauss.dat\" \"float aperturediameter\" 8\n"
        "  \"float focusdistance\" 2.5 \"float shutterclose\" 0.5\nWorldBegin\n"));
    ASSERT_TRUE(s.camera.has_value());
    EXPECT_EQ(s.camera->projection, scene::Camera::Projection::Realistic);
    ASSERT_EQ(s.camera->lens_elements.size(), 11u);
    EXPECT_FLOAT_EQ(s.camera->lens_elements[5].aperture_radius, 0.004f);  // 8 mm < the file's 17.1
    EXPECT_FLOAT_EQ(s.camera->lens_elements[0].aperture_radius, 0.0126f);
    EXPECT_FLOAT_EQ(s.camera->lens_focus_distance, 2.5f);
    EXPECT_FLOAT_EQ(s.camera->film_diagonal, 0.024f);
    EXPECT_FLOAT_EQ(s.film_response.exposure, 0.5f);
    // A larger diameter than the file's stop keeps the file's.
    const scene::Scene wide =
        load_pbrt(dir.write("wide.pbrt",
                            "Camera \"realistic\" \"string lensfile\" \"lenses/dgauss.dat\" "
                            "\"float aperturediameter\" 40\nWorldBegin\n"));
    EXPECT_FLOAT_EQ(wide.camera->lens_elements[5].aperture_radius, 0.00855f);
    EXPECT_FLOAT_EQ(wide.camera->lens_focus_distance, 10.0f);  // pbrt-v4's default
    EXPECT_FLOAT_EQ(wide.camera->film_diagonal, 0.035f);
}

TEST(PbrtLensAperture, NamedShapesPassACirclesLight) {
    for (const char* name : {"gaussian", "square", "pentagon", "star"}) {
        const auto a = named_aperture(name);
        ASSERT_TRUE(a.has_value()) << name;
        ASSERT_EQ(a->values.size(), size_t(a->width) * size_t(a->height));
        double sum = 0;
        for (const float v : a->values) sum += v;
        EXPECT_NEAR(sum / double(a->values.size()), kPi / 4, 1e-4) << name;
        EXPECT_GT(a->values[128 * 256 + 128], 0) << name;  // open in the middle
        EXPECT_EQ(a->values[0], 0) << name;                // closed in the corner
    }
    EXPECT_FALSE(named_aperture("hexagon").has_value());
    // The square's middle half: |x|, |y| < 1/2 of the stop's radius.
    const auto square = named_aperture("square");
    EXPECT_GT(square->values[128 * 256 + 190], 0);
    EXPECT_EQ(square->values[128 * 256 + 193], 0);
    // pbrt-v4 flips its rasterised shapes: the pentagon's vertex (at +y as drawn) lies along the
    // stop's -y (row 0), its flat side along +y.
    const auto pentagon = named_aperture("pentagon");
    EXPECT_GT(pentagon->values[size_t(30) * 256 + 128], 0);   // y = -0.76: inside, by the vertex
    EXPECT_EQ(pentagon->values[size_t(225) * 256 + 128], 0);  // y = +0.76: beyond the flat side
}

TEST(PbrtLensAperture, ImagesAreAveragedFlippedAndNormalised) {
    Image img(4, 2);
    img.at(1, 0) = Rgb(3, 0, 0);  // top row: lands on the stop's +y row
    const auto a = aperture_from_image(img);
    ASSERT_TRUE(a.has_value());
    EXPECT_FLOAT_EQ(a->values[4 + 1], float(kPi / 4 * 8));  // all the light in one of 8 pixels
    EXPECT_EQ(a->values[1], 0.0f);
    EXPECT_FALSE(aperture_from_image(Image(2, 2)).has_value());
}

TEST(PbrtCamera, RealisticApertureShapes) {
    QuietLog quiet;
    PbrtTempDir dir;
    dir.write("dgauss.dat", phos::testing::kDoubleGaussLens);
    const std::string cam = "Camera \"realistic\" \"string lensfile\" \"dgauss.dat\" \"string aperture\" ";
    scene::Scene s = load_pbrt(dir.write("a.pbrt", cam + "\"star\"\nWorldBegin\n"));
    EXPECT_EQ(s.camera->aperture.width, 256);
    Image img(2, 2);
    img.at(0, 0) = Rgb(1.0f);
    io::write_image(dir.file("stop.pfm"), img);
    s = load_pbrt(dir.write("b.pbrt", cam + "\"stop.pfm\"\nWorldBegin\n"));
    EXPECT_EQ(s.camera->aperture.width, 2);
    expect_pbrt_error(dir.write("c.pbrt", cam + "\"hexagon\"\nWorldBegin\n"), 1, 51, "is neither");
    io::write_image(dir.file("black.pfm"), Image(2, 2));
    expect_pbrt_error(dir.write("d.pbrt", cam + "\"black.pfm\"\nWorldBegin\n"), 1, 51, "is black");
}

TEST(PbrtCamera, RealisticErrorsAreLocated) {
    QuietLog quiet;
    PbrtTempDir dir;
    expect_pbrt_error(dir.write("a.pbrt", "Camera \"realistic\"\nWorldBegin\n"), 1, 1,
                      "needs a \"lensfile\"");
    expect_pbrt_error(
        dir.write("b.pbrt", "Camera \"realistic\" \"string lensfile\" \"none.dat\"\nWorldBegin\n"), 1, 20,
        "not found");
    // An error in the lens file is at its own line and column.
    const std::string bad = dir.write("bad.dat", "50 2 1.5 20\n-50 40 one 20\n");
    expect_pbrt_error(
        dir.write("c.pbrt", "Camera \"realistic\" \"string lensfile\" \"bad.dat\"\nWorldBegin\n"), 2, 8,
        "'one' is not a number", bad);
    dir.write("dgauss.dat", phos::testing::kDoubleGaussLens);
    expect_pbrt_error(dir.write("d.pbrt",
                                "Camera \"realistic\" \"string lensfile\" \"dgauss.dat\"\n"
                                "  \"float focusdistance\" -1\nWorldBegin\n"),
                      2, 3, "focusdistance must be positive");
    expect_pbrt_error(dir.write("e.pbrt", "Film \"rgb\" \"float diagonal\" 0\nWorldBegin\n"), 1, 12,
                      "diagonal must be positive");
}

}  // namespace
}  // namespace phos::io::pbrt
