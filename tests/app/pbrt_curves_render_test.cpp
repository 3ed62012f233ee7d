// pbrt curves rendered by `phos render`: three horizontal curves (flat, cylinder, ribbon, one of
// them in an instanced object) lit by a distant light over a black background show as lit bands
// where they are and black rows between them.
#include <gtest/gtest.h>

#include <string>

#include "io/image/image_io.h"
#include "test_util.h"

namespace phos {
namespace {

using testing::run_phos;
using testing::TempDir;

// The camera sees about y in [-1.34, 1.34] at z = 0 over 32 rows: a curve at height y covers the
// rows around 16 - 12 y, 0.3 wide (about 3.6 rows).
const std::string kScene = R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [ 30 ]
WorldBegin
LightSource "distant" "point3 from" [ 0 0 5 ] "point3 to" [ 0 0 0 ] "rgb L" [ 3 3 3 ]
Material "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]
Shape "curve" "string type" "flat" "point3 P" [ -3 0.8 0  -1 0.8 0  1 0.8 0  3 0.8 0 ] "float width" 0.3
ObjectBegin "hair"
Shape "curve" "string type" "cylinder" "point3 P" [ -3 0 0  -1 0 0  1 0 0  3 0 0 ] "float width" 0.3
ObjectEnd
ObjectInstance "hair"
Shape "curve" "string type" "ribbon" "string basis" "bspline" "point3 P" [ -4 -0.8 0  -3 -0.8 0  -1 -0.8 0  1 -0.8 0  3 -0.8 0  4 -0.8 0 ]
  "normal N" [ 0 0 1  0 0.2 1  0 0 1  0 -0.2 1 ] "float width" 0.3
)";

double row_mean(const Image& img, int y) {
    double s = 0;
    for (int x = 4; x < img.width - 4; ++x) {
        const Rgb& p = img.at(x, y);
        s += (double(p.r) + p.g + p.b) / 3;
    }
    return s / double(img.width - 8);
}

TEST(PbrtCurvesRender, CurvesAreLitBandsOverTheBackground) {
    TempDir dir;
    const std::string scene = dir.write("curves.pbrt", kScene);
    const std::string out = dir.file("curves.pfm");
    const auto r = run_phos("render " + scene +
                            " --resolution 32 32 --spp 4 --integrator path --seed 1 --quiet -o " + out);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const Image img = io::read_image(out, false);
    ASSERT_EQ(img.height, 32);
    // The three curves' rows (y = 0.8, 0, -0.8: rows 6, 16 and 25 from the top) are lit ...
    for (int y : {6, 16, 25}) EXPECT_GT(row_mean(img, y), 0.2) << "row " << y;
    // ... and the rows between and beyond them are the black background.
    for (int y : {0, 1, 11, 21, 30, 31}) EXPECT_EQ(row_mean(img, y), 0.0) << "row " << y;
}

}  // namespace
}  // namespace phos
