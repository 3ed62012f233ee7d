// Clean at the defaults: a room lit only through a frosted pane renders without isolated bright
// pixels at phos's defaults, and a scene lit mostly through glass gets the defaults chosen for it
// (app/lib/scene_defaults.h), which the start-up line names; an explicit --integrator wins.
#include <gtest/gtest.h>

#include <string>

#include "film/metrics.h"
#include "io/image/image_io.h"
#include "test_util.h"

namespace phos::testing {
namespace {

const std::string kPane = std::string(PHOS_SOURCE_DIR) + "/tests/agreement/scenes/frosted-pane-point.scn";

// A lantern: a point light inside a sphere of rough glass (alpha 0.02: a sharp lobe) hanging in
// a grey room; pbrt's default integrator would be path.
const char* kLantern = R"(Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]
LookAt 0 1 -1.8   0 0.9 0   0 1 0
Camera "perspective" "float fov" [ 60 ]
WorldBegin
Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
AttributeBegin
  ReverseOrientation
  Translate 0 1 0
  Shape "trianglemesh" "point3 P" [ -1 -1 -2  1 -1 -2  1 1 -2  -1 1 -2  -1 -1 2  1 -1 2  1 1 2  -1 1 2 ]
    "integer indices" [ 0 1 2 0 2 3  4 6 5 4 7 6  0 4 5 0 5 1  3 2 6 3 6 7  0 3 7 0 7 4  1 5 6 1 6 2 ]
AttributeEnd
LightSource "point" "point3 from" [ 0 1.2 0.5 ] "rgb I" [ 1 1 1 ]
AttributeBegin
  Material "dielectric" "float eta" 1.5 "float roughness" 0.02 "bool remaproughness" false
  Translate 0 1.2 0.5
  Shape "sphere" "float radius" 0.2
AttributeEnd
)";

TEST(SceneDefaults, ARoomLitThroughAFrostedPaneHasNoSpecklesAtTheDefaults) {
    // The room's light passes the pane's two glossy faces (exponent 300). Estimated there, as
    // every glossy lobe once was (--sharp-glossy above 300 restores it), the final gather picks up
    // the pane's few photons inside its sharp lobe: 0.7 % of the pixels are isolated bright dots
    // (luminance above 3 x their 5 x 5 median + 0.05, film::speckle_fraction on linear values).
    // Followed (the default), the light is a caustic read at the walls: at most 2 of 4096.
    TempDir dir;
    const auto r =
        run_phos("render " + kPane + " " + dir.file("pane.pfm") + " --width 64 --height 64 --quiet");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_LE(film::speckle_fraction(io::read_image(dir.file("pane.pfm"))), 2.0 / 4096) << r.output;

    const auto old = run_phos("render " + kPane + " " + dir.file("old.pfm") +
                              " --width 64 --height 64 --quiet --sharp-glossy 1000");
    ASSERT_EQ(old.exit_code, 0) << old.output;
    EXPECT_GT(film::speckle_fraction(io::read_image(dir.file("old.pfm"))), 0.002);
}

TEST(SceneDefaults, ALanternGetsThePhotonMapperAndSaysWhy) {
    TempDir dir;
    const std::string scene = dir.write("lantern.pbrt", kLantern);
    const auto r = run_phos("render " + scene + " " + dir.file("a.pfm") + " --spp 1");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("lantern.pbrt: photonmap (default: "), std::string::npos) << r.output;
    EXPECT_NE(
        r.output.find("% of the light reaches the surfaces through mirrors, glass or sharp glossy lobes; "
                      "path would find it only by chance; caustic map 1000000 photons)"),
        std::string::npos)
        << r.output;

    // An explicit choice wins, and an estimated lantern (its lobe below --sharp-glossy) is not
    // lit through interfaces.
    const auto path = run_phos("render " + scene + " " + dir.file("b.pfm") + " --spp 1 --integrator path");
    ASSERT_EQ(path.exit_code, 0) << path.output;
    EXPECT_NE(path.output.find("lantern.pbrt: path (command line)"), std::string::npos) << path.output;
    const auto wide = run_phos("render " + scene + " " + dir.file("c.pfm") + " --spp 1 --sharp-glossy 1e9");
    ASSERT_EQ(wide.exit_code, 0) << wide.output;
    EXPECT_NE(wide.output.find("lantern.pbrt: path (pbrt's default)"), std::string::npos) << wide.output;
}

TEST(SceneDefaults, ARoomLitDirectlyKeepsTheDefaults) {
    TempDir dir;
    const auto r = run_phos("render " + kPane + " " + dir.file("a.pfm") + " --width 16 --height 16 --spp 1");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // Most of the point light's power lands in its alcove, straight from the light.
    EXPECT_NE(r.output.find("frosted-pane-point.scn: photonmap (default), "), std::string::npos) << r.output;
}

}  // namespace
}  // namespace phos::testing
