// What ppm / sppm write besides the image, through the phos binary: progress in a log is plain
// lines (by time for a --time budget, never a sentinel count), none with -q or --no-progress; and
// --layers writes direct and indirect layers that sum to the unchanged image.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "io/image/image_io.h"
#include "test_util.h"

namespace phos::testing {
namespace {

const std::string kScene = shared_path("bench/scn/caustic-point.scn");

TEST(ProgressiveOutput, ProgressInALogIsPlainLinesByTime) {
    TempDir dir;
    const std::string args = " --integrator sppm --width 32 --height 32 --photons-per-iter 30000 --seed 5";
    const auto timed = run_phos("render " + kScene + args + " --time 1 -o " + dir.file("t.pfm"));
    ASSERT_EQ(timed.exit_code, 0) << timed.output;
    EXPECT_NE(timed.output.find("sppm: "), std::string::npos) << timed.output;
    EXPECT_NE(timed.output.find(" s / 1 s, "), std::string::npos) << timed.output;
    EXPECT_NE(timed.output.find(" iterations, done\n"), std::string::npos) << timed.output;
    EXPECT_EQ(timed.output.find("ETA"), std::string::npos) << timed.output;
    EXPECT_EQ(timed.output.find('\r'), std::string::npos) << timed.output;
    EXPECT_EQ(timed.output.find("1073741824"), std::string::npos) << timed.output;
    const auto counted = run_phos("render " + kScene + args + " --iterations 20 -o " + dir.file("c.pfm"));
    ASSERT_EQ(counted.exit_code, 0) << counted.output;
    EXPECT_NE(counted.output.find("sppm:  50 % (10 of 20)"), std::string::npos) << counted.output;
    EXPECT_NE(counted.output.find("sppm: 100 % (20 of 20), took "), std::string::npos) << counted.output;
    // -q and --no-progress: none.
    for (const char* off : {" -q", " --no-progress"}) {
        const auto r =
            run_phos("render " + kScene + args + " --iterations 20" + off + " -o " + dir.file("c.pfm"));
        EXPECT_EQ(r.output.find("sppm: "), std::string::npos) << off << "\n" << r.output;
    }
}

TEST(ProgressiveOutput, LayersSumToTheUnchangedImage) {
    TempDir dir;
    for (const char* integrator : {"sppm", "ppm"}) {
        const std::string args = std::string(" --integrator ") + integrator +
                                 " --width 24 --height 20 --photons-per-iter 20000 --iterations 5 -q";
        const std::string plain = dir.file(std::string(integrator) + "-plain.pfm");
        const std::string layered = dir.file(std::string(integrator) + ".pfm");
        ASSERT_EQ(run_phos("render " + kScene + args + " -o " + plain).exit_code, 0);
        const auto r = run_phos("render " + kScene + args + " --layers -o " + layered);
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_EQ(read_bytes(plain), read_bytes(layered)) << integrator;
        const Image image = io::read_image(layered, false);
        const Image direct = io::read_image(dir.file(std::string(integrator) + ".direct.pfm"), false);
        const Image indirect = io::read_image(dir.file(std::string(integrator) + ".indirect.pfm"), false);
        ASSERT_EQ(direct.pixels.size(), image.pixels.size());
        ASSERT_EQ(indirect.pixels.size(), image.pixels.size());
        double sum_direct = 0, sum_indirect = 0;
        for (size_t i = 0; i < image.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                const float v = image.pixels[i][c], d = direct.pixels[i][c], l = indirect.pixels[i][c];
                EXPECT_NEAR(d + l, v, 2 * std::numeric_limits<float>::epsilon() * std::abs(v))
                    << integrator << i;
                sum_direct += d;
                sum_indirect += l;
            }
        EXPECT_GT(sum_direct, 0) << integrator;
        EXPECT_GT(sum_indirect, 0) << integrator;  // the caustic comes from photons
    }
}

}  // namespace
}  // namespace phos::testing
