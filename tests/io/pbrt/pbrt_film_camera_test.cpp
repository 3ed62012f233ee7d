// The pbrt loader's film, filter, camera and graphics-state directives: PixelFilter (every pbrt-v4
// filter and pbrt-v4's Gaussian default), Film cropwindow/pixelbounds, Camera "spherical",
// ColorSpace, Attribute and Option, with their located errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pbrt_test_util.h"
#include "scene/scene.h"
#include "spectrum/color.h"

namespace phos::io::pbrt {
namespace {

using test::expect_pbrt_error;
using test::PbrtTempDir;
using test::QuietLog;
using Kind = scene::PixelFilter::Kind;

scene::Scene load(const std::string& text) {
    QuietLog quiet;
    PbrtTempDir dir;
    return load_pbrt(dir.write("scene.pbrt", text));
}

void expect_error(const std::string& text, int line, int col, const std::string& message) {
    QuietLog quiet;
    PbrtTempDir dir;
    expect_pbrt_error(dir.write("scene.pbrt", text), line, col, message);
}

TEST(PbrtFilter, EveryPbrtV4FilterWithItsParameters) {
    scene::Scene s = load("PixelFilter \"gaussian\" \"float sigma\" 0.7 \"float xradius\" 2\nWorldBegin\n");
    EXPECT_EQ(s.pixel_filter.kind, Kind::Gaussian);
    EXPECT_FLOAT_EQ(s.pixel_filter.sigma, 0.7f);
    EXPECT_FLOAT_EQ(s.pixel_filter.radius.x, 2.0f);
    EXPECT_FLOAT_EQ(s.pixel_filter.radius.y, 1.5f);
    s = load("PixelFilter \"mitchell\" \"float B\" 0.5 \"float C\" 0.25\nWorldBegin\n");
    EXPECT_EQ(s.pixel_filter.kind, Kind::Mitchell);
    EXPECT_FLOAT_EQ(s.pixel_filter.b, 0.5f);
    EXPECT_FLOAT_EQ(s.pixel_filter.c, 0.25f);
    EXPECT_FLOAT_EQ(s.pixel_filter.radius.x, 2.0f);
    s = load("PixelFilter \"sinc\" \"float tau\" 2\nWorldBegin\n");
    EXPECT_EQ(s.pixel_filter.kind, Kind::Lanczos);
    EXPECT_FLOAT_EQ(s.pixel_filter.tau, 2.0f);
    EXPECT_FLOAT_EQ(s.pixel_filter.radius.x, 4.0f);
    s = load("PixelFilter \"triangle\"\nWorldBegin\n");
    EXPECT_EQ(s.pixel_filter.kind, Kind::Triangle);
    s = load("PixelFilter \"box\"\nWorldBegin\n");
    EXPECT_TRUE(s.pixel_filter.is_pixel_box());
}

TEST(PbrtFilter, WithoutADirectiveItIsPbrtV4sGaussian) {
    const scene::Scene s = load("WorldBegin\n");
    EXPECT_EQ(s.pixel_filter.kind, Kind::Gaussian);
    EXPECT_FLOAT_EQ(s.pixel_filter.radius.x, 1.5f);
    EXPECT_FLOAT_EQ(s.pixel_filter.sigma, 0.5f);
}

TEST(PbrtFilter, PbrtV3WidthsAndAlphaBecomeRadiiAndSigma) {
    const scene::Scene s = load(
        "PixelFilter \"gaussian\" \"float xwidth\" 2 \"float ywidth\" 2 \"float alpha\" 2\nWorldBegin\n");
    EXPECT_FLOAT_EQ(s.pixel_filter.radius.x, 2.0f);
    EXPECT_NEAR(s.pixel_filter.sigma, 0.5f, 1e-6f);  // 1 / sqrt(2 alpha)
}

TEST(PbrtFilter, BadFiltersAreLocatedErrors) {
    expect_error("PixelFilter \"blackman\"\nWorldBegin\n", 1, 1, "unknown filter");
    expect_error("PixelFilter \"gaussian\" \"float xradius\" -1\nWorldBegin\n", 1, 24, "must be in (0, 64]");
    expect_error("PixelFilter \"gaussian\" \"float sigma\" 0\nWorldBegin\n", 1, 24, "sigma must be positive");
}

TEST(PbrtFilm, CropWindowAndPixelBounds) {
    scene::Scene s = load(
        "Film \"rgb\" \"integer xresolution\" 100 \"integer yresolution\" 50 \"float cropwindow\" [0.25 "
        "0.75 0 0.5]\nWorldBegin\n");
    ASSERT_TRUE(s.settings.crop_window.has_value());
    EXPECT_FLOAT_EQ((*s.settings.crop_window)[0], 0.25f);
    EXPECT_FLOAT_EQ((*s.settings.crop_window)[3], 0.5f);
    s = load(
        "Film \"rgb\" \"integer xresolution\" 100 \"integer yresolution\" 50 \"integer pixelbounds\" [10 20 "
        "5 "
        "15]\nWorldBegin\n");
    ASSERT_TRUE(s.settings.pixel_bounds.has_value());
    EXPECT_EQ((*s.settings.pixel_bounds)[1], 20);
    expect_error("Film \"rgb\" \"float cropwindow\" [0.5 0.25 0 1]\nWorldBegin\n", 1, 12,
                 "cropwindow needs 4 values");
    expect_error("Film \"rgb\" \"integer xresolution\" 10 \"integer pixelbounds\" [0 20 0 5]\nWorldBegin\n",
                 1, 37, "pixelbounds needs 4 values");
}

TEST(PbrtCamera, SphericalWithEitherMapping) {
    scene::Scene s = load("Camera \"spherical\"\nWorldBegin\n");
    ASSERT_TRUE(s.camera.has_value());
    EXPECT_EQ(s.camera->projection, scene::Camera::Projection::Spherical);
    EXPECT_EQ(s.camera->spherical_mapping, scene::Camera::SphericalMapping::EqualArea);
    s = load("Camera \"spherical\" \"string mapping\" \"equirectangular\"\nWorldBegin\n");
    EXPECT_EQ(s.camera->spherical_mapping, scene::Camera::SphericalMapping::Equirectangular);
    expect_error("Camera \"spherical\" \"string mapping\" \"cube\"\nWorldBegin\n", 1, 20, "mapping must be");
}

TEST(PbrtColorSpace, RgbValuesAreReadInTheCurrentSpace) {
    const std::string lights = "LightSource \"point\" \"rgb I\" [0.2 0.5 0.3]\n";
    const scene::Scene srgb = load("WorldBegin\n" + lights);
    const scene::Scene rec = load("WorldBegin\nColorSpace \"rec2020\"\n" + lights +
                                  "AttributeBegin\nColorSpace \"srgb\"\nAttributeEnd\n" + lights);
    ASSERT_EQ(rec.lights.size(), 2u);
    // The same XYZ: rec2020's primaries are wider, so its (0.2, 0.5, 0.3) is a purer green in sRGB.
    const Vec3 v = spectrum::apply(*spectrum::rgb_space_to_srgb("rec2020", false), Vec3(0.2f, 0.5f, 0.3f));
    EXPECT_NEAR(rec.lights[0].color.g, v.y, 1e-5f);
    EXPECT_GT(rec.lights[0].color.g, srgb.lights[0].color.g);
    EXPECT_EQ(rec.lights[1].color, rec.lights[0].color);  // the block's own space ended with it
    // The spaces' whites: rec2020's is D65 (white stays white), ACES's is adapted for reflectances.
    for (const char* space : {"rec2020", "dci-p3", "aces2065-1"}) {
        const Vec3 w = spectrum::apply(*spectrum::rgb_space_to_srgb(space, true), Vec3(1, 1, 1));
        EXPECT_NEAR(w.x, 1, 1e-4);
        EXPECT_NEAR(w.y, 1, 1e-4);
        EXPECT_NEAR(w.z, 1, 1e-4);
    }
    expect_error("WorldBegin\nColorSpace \"adobe\"\n", 2, 1, "unknown");
}

TEST(PbrtAttribute, DefaultsApplyWithinTheirBlock) {
    const scene::Scene s = load(
        "WorldBegin\n"
        "AttributeBegin\n"
        "Attribute \"shape\" \"float radius\" 2\n"
        "Shape \"sphere\"\n"
        "Shape \"sphere\" \"float radius\" 3\n"
        "AttributeEnd\n"
        "Shape \"sphere\"\n");
    ASSERT_EQ(s.shapes.size(), 3u);
    EXPECT_FLOAT_EQ(s.shapes[0].radius, 2.0f);
    EXPECT_FLOAT_EQ(s.shapes[1].radius, 3.0f);  // the directive's own value wins
    EXPECT_FLOAT_EQ(s.shapes[2].radius, 1.0f);  // the block ended
    const scene::Scene l =
        load("WorldBegin\nAttribute \"light\" \"float scale\" 4\nLightSource \"point\" \"rgb I\" [1 1 1]\n");
    ASSERT_EQ(l.lights.size(), 1u);
    EXPECT_NEAR(l.lights[0].color.r, 4.0f, 1e-5f);
    expect_error("WorldBegin\nAttribute \"camera\" \"float fov\" 30\n", 2, 1, "unknown target");
}

TEST(PbrtOption, SeedBecomesTheRendersSeed) {
    const scene::Scene s = load("Option \"integer seed\" 42\nWorldBegin\n");
    bool found = false;
    for (const scene::IntegratorParameter& p : s.settings.integrator_parameters)
        if (p.name == "seed") found = p.values == std::vector<std::string>{"42"};
    EXPECT_TRUE(found);
    EXPECT_NO_THROW(load(
        "Option \"string rendercoordsys\" \"world\"\nOption \"bool disablepixeljitter\" true\nWorldBegin\n"));
}

}  // namespace
}  // namespace phos::io::pbrt
