// Glowing .scn surfaces (material emission `e`) are two-sided area lights by default, in every
// integrator: a Cornell box lit only by a glowing ceiling panel (as the seed renderer's distributed
// scenes are) renders lit whichever way the panel is wound, and --no-emission-lights gives the seed's
// reading back (the glow is seen, the room stays dark).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/image/image_io.h"
#include "test_util.h"

namespace phos::testing {
namespace {

// A Cornell box whose only light is a glowing panel just below the ceiling (PANEL is replaced by
// its two triangles); the black point light keeps the seed's default lights away, as such files do.
const std::string kRoom = R"(
camera 0 0.5 1.9   0 0 -1   0 1 0   0.34   0.001 100
material 0 0 0   0.75 0.75 0.75   0 0 0   0 0 0   0 0 0      1 1 0   # white
material 0 0 0   0.6 0.06 0.05    0 0 0   0 0 0   0 0 0      1 1 0   # red
material 0 0 0   0.12 0.45 0.09   0 0 0   0 0 0   0 0 0      1 1 0   # green
material 0 0 0   0 0 0            0 0 0   0 0 0   20 20 20   1 1 0   # the glow
tri 0   -0.5 0 -0.5   -0.5 0 0.5   0.5 0 0.5
tri 0   -0.5 0 -0.5   0.5 0 0.5   0.5 0 -0.5
tri 0   -0.5 1 -0.5   0.5 1 -0.5   0.5 1 0.5
tri 0   -0.5 1 -0.5   0.5 1 0.5   -0.5 1 0.5
tri 0   -0.5 0 -0.5   0.5 0 -0.5   0.5 1 -0.5
tri 0   -0.5 0 -0.5   0.5 1 -0.5   -0.5 1 -0.5
tri 1   -0.5 0 -0.5   -0.5 1 -0.5   -0.5 1 0.5
tri 1   -0.5 0 -0.5   -0.5 1 0.5   -0.5 0 0.5
tri 2   0.5 0 -0.5   0.5 0 0.5   0.5 1 0.5
tri 2   0.5 0 -0.5   0.5 1 0.5   0.5 1 -0.5
box 0   -0.3 0 -0.3   -0.05 0.5 -0.05
sphere 0   0.2 0.15 0.15   0.15
PANEL
point_light 0 0 0   0 0.5 0   0 0 1
)";

// The panel wound to face the ceiling (normal +y, as in the seed's scenes) or the room (-y).
const std::string kPanelUp =
    "tri 3   -0.15 0.98 -0.15   -0.15 0.98 0.15   0.15 0.98 0.15\n"
    "tri 3   -0.15 0.98 -0.15   0.15 0.98 0.15   0.15 0.98 -0.15";
const std::string kPanelDown =
    "tri 3   -0.15 0.98 -0.15   0.15 0.98 0.15   -0.15 0.98 0.15\n"
    "tri 3   -0.15 0.98 -0.15   0.15 0.98 -0.15   0.15 0.98 0.15";

std::string room(const std::string& panel) {
    std::string s = kRoom;
    s.replace(s.find("PANEL"), 5, panel);
    return s;
}

struct Stats {
    double mean = 0;        // over all pixels and channels
    double black = 0;       // fraction of pixels that are exactly black
    double lower_half = 0;  // mean of the image's lower half (floor, boxes: lit only by light)
};

Stats stats_of(const std::string& path) {
    const Image img = io::read_image(path);
    Stats s;
    size_t black = 0;
    double lower = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const Rgb& p = img.at(x, y);
            const double v = (double(p.r) + p.g + p.b) / 3;
            s.mean += v;
            if (v == 0) ++black;
            if (y >= img.height / 2) lower += v;
        }
    const double n = double(img.pixels.size());
    s.mean /= n;
    s.black = double(black) / n;
    s.lower_half = lower / (n / 2);
    return s;
}

class ScnEmission : public ::testing::Test {
protected:
    // Renders `scene` at 32x32 with `args` (fixed seed) and returns its statistics.
    Stats render(const std::string& scene, const std::string& args) {
        const std::string img = dir.file("x.pfm");
        std::filesystem::remove(img);
        const auto r =
            run_phos("render " + scene + " --resolution 32 32 --seed 3 --quiet " + args + " -o " + img);
        EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.output;
        return stats_of(img);
    }
    TempDir dir;
};

// The seed's distributed scenes rendered 98 % black: the panel faces the ceiling and a glow lit
// nothing. By default the room is lit, with the default integrator and with path tracing.
TEST_F(ScnEmission, GlowingPanelLightsTheRoomByDefault) {
    const std::string scene = dir.write("distributed.scn", room(kPanelUp));
    for (const std::string args : {"", "--integrator path --spp 16"}) {
        const Stats lit = render(scene, args);
        EXPECT_GT(lit.mean, 0.05) << args;
        EXPECT_LT(lit.black, 0.02) << args;
        EXPECT_GT(lit.lower_half, 0.05) << args;
        // --no-emission-lights: the seed's reading; only the glow itself is seen.
        const Stats dark = render(scene, args + " --no-emission-lights");
        EXPECT_GT(dark.black, 0.9) << args;
        EXPECT_EQ(dark.lower_half, 0.0) << args;
        // --emission-lights (the default) is still accepted and changes nothing.
        const Stats same = render(scene, args + " --emission-lights");
        EXPECT_EQ(same.mean, lit.mean) << args;
    }
}

// A glow is seen from both sides, so it lights from both sides: the panel wound either way lights
// the room alike in every integrator, and the integrators agree with each other as they do for any
// light: photonmap and sppm with path, whitted with path limited to direct light. They are compared
// on the image's lower half (floor and boxes, lit from a distance): the upper half holds the ceiling
// 2 cm above the panel, whose estimates are heavy-tailed in every integrator but path.
TEST_F(ScnEmission, BothSidesOfAGlowLightInEveryIntegrator) {
    const std::string up = dir.write("up.scn", room(kPanelUp));
    const std::string down = dir.write("down.scn", room(kPanelDown));
    const Stats path_up = render(up, "--integrator path --spp 64");
    const Stats path_down = render(down, "--integrator path --spp 64");
    EXPECT_GT(path_up.lower_half, 0.1);
    // 32x32 means: path's noise is ~0.5 %, photonmap's and sppm's bias (kernel estimates) ~1-2 %.
    EXPECT_NEAR(path_down.mean / path_up.mean, 1.0, 0.02) << path_down.mean << " vs " << path_up.mean;
    EXPECT_NEAR(path_down.lower_half / path_up.lower_half, 1.0, 0.02);
    for (const std::string& scene : {up, down}) {
        const double path = (scene == up ? path_up : path_down).lower_half;
        const double photonmap = render(scene, "--integrator photonmap --spp 16").lower_half;
        EXPECT_NEAR(photonmap / path, 1.0, 0.05) << scene << ": " << photonmap << " vs " << path;
        const double sppm = render(scene, "--integrator sppm --iterations 8").lower_half;
        EXPECT_NEAR(sppm / path, 1.0, 0.08) << scene << ": " << sppm << " vs " << path;
        const double whitted = render(scene, "--integrator whitted --spp 16").lower_half;
        const double direct = render(scene, "--integrator path --spp 64 --max-depth 1").lower_half;
        EXPECT_NEAR(whitted / direct, 1.0, 0.03) << scene << ": " << whitted << " vs " << direct;
    }
}

// Light commands keep their own side: a one-sided rect_light above the ceiling, facing away from
// the room, leaves it black in every integrator (the glow's two sides are the .scn glow's alone).
TEST_F(ScnEmission, OneSidedLightsStillEmitOnTheirSideOnly) {
    const std::string scene =
        dir.write("away.scn", room("rect_light 15 15 15   0 1.001 0   0 0 1   1 0 0   0.3 0.3   0 0 1"));
    // (Every photon escapes: small photon budgets keep the photon mappers quick.)
    for (const std::string integrator : {"path", "photonmap --max-emitted 100000", "whitted",
                                         "sppm --iterations 4 --photons-per-iter 20000"})
        EXPECT_EQ(render(scene, "--integrator " + integrator).mean, 0.0) << integrator;
}

}  // namespace
}  // namespace phos::testing
