// pbrt "alpha" cut-outs rendered by `phos render`: a leaf quad between a distant light and a floor
// casts a shadow with holes where its alpha texture is 0 (a checkerboard: half the shadow lit) and,
// with a constant alpha of 0.3, lets 70 % of the shadow rays through.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/image/image_io.h"
#include "test_util.h"

namespace phos {
namespace {

using testing::run_phos;
using testing::TempDir;

// An orthographic camera looking straight down at exactly the square x in [-3, -2], z in
// [-0.5, 0.5] of a diffuse floor at y = 0, lit by a distant light along (-1, -1, 0). The leaf,
// the square x in [-2, -1], z in [-0.5, 0.5] at y = 1 (uv over it), casts its shadow exactly onto
// that square and lies outside the camera's view. Box pixel filter: each pixel averages only its
// own area. `leaf` is the leaf's alpha parameter, or empty for no leaf at all.
std::string scene_text(const std::string& leaf) {
    std::string s = R"(LookAt -2.5 5 0  -2.5 0 0  0 0 1
Camera "orthographic" "float screenwindow" [ -0.5 0.5 -0.5 0.5 ]
PixelFilter "box"
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
WorldBegin
LightSource "distant" "point3 from" [ 1 1 0 ] "point3 to" [ 0 0 0 ] "rgb L" [ 2 2 2 ]
Texture "checks" "float" "checkerboard" "float uscale" 4 "float vscale" 4 "float tex1" 1 "float tex2" 0
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "trianglemesh" "point3 P" [ -10 0 -10  10 0 -10  10 0 10  -10 0 10 ] "integer indices" [ 0 2 1 0 3 2 ]
Material "diffuse" "rgb reflectance" [ 0 0 0 ]
)";
    if (!leaf.empty())
        s += "Shape \"trianglemesh\" \"point3 P\" [ -2 1 -0.5  -1 1 -0.5  -1 1 0.5  -2 1 0.5 ] "
             "\"point2 uv\" [ 0 0 1 0 1 1 0 1 ] \"integer indices\" [ 0 1 2 0 2 3 ] " +
             leaf + "\n";
    return s;
}

struct Rendered {
    double mean = 0;           // over the image, channel average
    int dark = 0, bright = 0;  // pixels below 5 % / above 95 % of `lit`
};

Rendered render(TempDir& dir, const std::string& name, const std::string& leaf, double lit, int spp) {
    const std::string scene = dir.write(name + ".pbrt", scene_text(leaf));
    const std::string out = dir.file(name + ".pfm");
    const auto r = run_phos("render " + scene + " --spp " + std::to_string(spp) +
                            " --integrator path --seed 3 --quiet -o " + out);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const Image img = io::read_image(out, false);
    Rendered res;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const Rgb& p = img.at(x, y);
            const double v = (double(p.r) + p.g + p.b) / 3;
            res.mean += v;
            res.dark += v < 0.05 * lit;
            res.bright += v > 0.95 * lit;
        }
    res.mean /= double(img.width) * img.height;
    return res;
}

TEST(PbrtAlphaRender, CutOutLeafShadowHasHoles) {
    TempDir dir;
    // Without the leaf the floor is lit evenly: the reference.
    const Rendered open = render(dir, "open", "", 0, 1);
    ASSERT_GT(open.mean, 0.1);
    // An opaque leaf (alpha 1) shadows the whole square.
    EXPECT_EQ(render(dir, "opaque", "\"float alpha\" 1", open.mean, 1).mean, 0.0);
    // Alpha 0: the leaf is absent for shadow rays too.
    EXPECT_NEAR(render(dir, "absent", "\"float alpha\" 0", open.mean, 1).mean, open.mean, 1e-6 * open.mean);
    // The checkerboard (4 x 4 checks over the leaf, 4 x 4 pixels each in the shadow): the shadow
    // is half holes. Each pixel lies within one check, so every pixel is either lit or dark; the
    // tolerance allows a sample or two of the 16 x 16 x 4 that land across a check's edge through
    // rounding.
    const Rendered checks = render(dir, "checks", "\"texture alpha\" \"checks\"", open.mean, 4);
    EXPECT_NEAR(checks.mean / open.mean, 0.5, 0.01);
    EXPECT_GE(checks.dark, 120);
    EXPECT_GE(checks.bright, 120);
    // Constant alpha 0.3: each of the 16 x 16 x 16 shadow rays (distinct rays) passes with
    // probability 0.7, so the mean ratio is 0.7 within 4 binomial sigmas, sqrt(0.21 / 4096).
    const Rendered partial = render(dir, "partial", "\"float alpha\" 0.3", open.mean, 16);
    EXPECT_NEAR(partial.mean / open.mean, 0.7, 4 * std::sqrt(0.21 / 4096));
}

}  // namespace
}  // namespace phos
