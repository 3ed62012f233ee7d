// `phos agree` end to end: on a small diffuse scene path and bdpt agree (exit 0, the table and its
// header on stdout), whitted, which leaves the indirect light out, disagrees (exit 1, the blocks
// named), and bad input exits 2 with a located message.
#include <gtest/gtest.h>

#include <string>

#include "test_util.h"

namespace phos::testing {
namespace {

// A floor and a back wall under a square area light: light bounces from one to the other.
const std::string kDiffuseScene = R"(
camera 0 0.8 2.5   0 -0.2 -1   0 1 0   0.6   0.001 100
material 0 0 0   0.7 0.7 0.7   0 0 0   0 0 0   0 0 0   10 1 0
tri 0   -1 0 -1   -1 0 1   1 0 1
tri 0   -1 0 -1   1 0 1   1 0 -1
tri 0   -1 0 -1   1 0 -1   1 2 -1
tri 0   -1 0 -1   1 2 -1   -1 2 -1
rect_light 10 10 10   0 1.5 0   1 0 0   0 0 1   0.5 0.5   0 0 1
)";

// Half a second per integrator and seed: enough samples for the blocks' noise estimates on a
// loaded machine (ctest -j2), where 0.2 s of four-wavelength paths was not.
const std::string kSmall = " --time 0.5 --width 16 --height 16 --threads 2";

TEST(AgreeCommand, AgreeingIntegratorsExit0WithTheTable) {
    TempDir dir;
    const std::string scene = dir.write("diffuse.scn", kDiffuseScene);
    const auto r = run_phos("agree " + scene + " --integrators path,bdpt" + kSmall);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(
        r.output.find("| integrator | budget per seed | mean / reference mean | allowed | worst block | its "
                      "ratio | tolerances off | blocks beyond tolerance |"),
        std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("reference path at "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("| path | "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("| bdpt | "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(" of 12 | "), std::string::npos) << r.output;  // 2 x 2 blocks x 3 channels
    EXPECT_EQ(r.output.find("Blocks that disagree"), std::string::npos) << r.output;
}

TEST(AgreeCommand, WhittedDisagreesAndExits1) {
    TempDir dir;
    const std::string scene = dir.write("diffuse.scn", kDiffuseScene);
    const auto r = run_phos("agree " + scene + " --integrators whitted" + kSmall);
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("| whitted (does not claim the scene) | "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("Blocks that disagree"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("- whitted: block ("), std::string::npos) << r.output;
}

TEST(AgreeCommand, BadInputExits2) {
    TempDir dir;
    const std::string scene = dir.write("diffuse.scn", kDiffuseScene);
    const std::string broken = dir.write("broken.scn", "material 0 0 0\n");
    struct Case {
        std::string args, message;
    };
    for (const Case& c :
         {Case{"agree " + broken + kSmall, broken + ":2:1: material"},
          Case{"agree " + dir.file("missing.scn") + kSmall, "missing.scn"},
          Case{"agree " + scene + " --integrators path,magic" + kSmall,
               "--integrators: unknown integrator 'magic'"},
          Case{"agree " + scene + " --reference magic" + kSmall, "--reference: unknown integrator 'magic'"},
          Case{"agree " + scene + " --block 0" + kSmall, "--block"},
          Case{"agree " + scene + " --time 0", "--time"},
          Case{"agree " + scene + " --alpha 0" + kSmall, "--alpha"}, Case{"agree", "scene"}}) {
        const auto r = run_phos(c.args);
        EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << "\n" << r.output;
        EXPECT_EQ(r.output.find("| integrator |"), std::string::npos) << c.args;
    }
}

}  // namespace
}  // namespace phos::testing
