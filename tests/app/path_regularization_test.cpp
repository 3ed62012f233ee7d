// Path regularisation (--regularize, integrators/path.cpp): plain path tracing cannot find a point
// light's caustic through smooth glass (no vertex can sample it); regularised, the glass seen after
// a diffuse bounce is widened just enough for next-event estimation to find it, and the image
// converges to bdpt's. Widening never touches what the camera sees directly.
#include <gtest/gtest.h>

#include <string>

#include "film/metrics.h"
#include "io/image/image_io.h"
#include "test_util.h"

namespace phos::testing {
namespace {

const std::string kCaustic = std::string(PHOS_SOURCE_DIR) + "/tests/agreement/scenes/a-caustic-point.scn";

double mean_of(const TempDir& dir, const std::string& name, const std::string& options) {
    const auto r =
        run_phos("render " + kCaustic + " " + dir.file(name) + " --width 32 --height 32 --quiet " + options);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return film::mean_value(io::read_image(dir.file(name)));
}

TEST(PathRegularization, FindsThePointLightsCausticAndConvergesToBdpt) {
    // 256 samples or iterations at 32 x 32 (seed 0): the image means are then within 0.3 % of
    // each other's noise; the caustic is about 10 % of the image. Measured: bdpt 0.4686, path
    // regularised 0.4660 (-0.5 %: noise plus the widening's remaining blur at the caustic's
    // edge), plain path 0.4228 (-10 %: no caustic).
    TempDir dir;
    const double bdpt = mean_of(dir, "bdpt.pfm", "--integrator bdpt --spp 256");
    const double regularized = mean_of(dir, "reg.pfm", "--integrator path --spp 256");
    const double plain = mean_of(dir, "plain.pfm", "--integrator path --spp 256 --regularize 0");
    EXPECT_NEAR(regularized / bdpt, 1.0, 0.02);
    EXPECT_LT(plain / bdpt, 0.93);
}

TEST(PathRegularization, LeavesWhatTheCameraSeesDirectlyAlone) {
    // The camera's first vertex is never widened (the path has had no rough bounce yet), and the
    // widening draws no random numbers: the direct layer (emission seen, and the first vertex's
    // light, sampled or found by its BSDF sample) is the same to the bit with and without it.
    TempDir dir;
    for (const char* r : {"0", "30"}) {
        const auto out =
            run_phos("render " + kCaustic + " " + dir.file(std::string("r") + r + ".pfm") +
                     " --integrator path --spp 4 --width 32 --height 32 --layers --quiet --regularize " + r);
        ASSERT_EQ(out.exit_code, 0) << out.output;
    }
    const Image a = io::read_image(dir.file("r0.direct.pfm")), b = io::read_image(dir.file("r30.direct.pfm"));
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    for (size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) ASSERT_EQ(a.pixels[i][c], b.pixels[i][c]) << "pixel " << i;
}

}  // namespace
}  // namespace phos::testing
