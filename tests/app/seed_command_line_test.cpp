// The seed renderer's habits that phos takes as they are: `phos in.scn out.png` and
// `phos render in.scn out.png` (positional output), and energy-creating `.scn` materials rendered
// sanely by default (scaled as the seed's -real did) with the raw behaviour behind --raw-materials.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/image/image_io.h"
#include "test_util.h"

namespace phos::testing {
namespace {

const std::string kScene = R"(
camera 0 0.5 2   0 0 -1   0 1 0   0.4   0.001 100
material 0 0 0   0.7 0.7 0.7   0 0 0   0 0 0   0 0 0   10 1 0
tri 0   -1 0 -1   -1 0 1   1 0 1
tri 0   -1 0 -1   1 0 1   1 0 -1
point_light 3 3 3   0 1.5 0   1 0 0
)";

// A closed box of a material with kd + ks = 1.6: without scaling, every bounce creates light.
const std::string kHotBox = R"(
camera 0 0 0   0 0 -1   0 1 0   0.5   0.001 100
material 0 0 0   0.8 0.8 0.8   0.8 0.8 0.8   0 0 0   0 0 0   20 1 0
box 0   -1 -1 -1   1 1 1
point_light 1 1 1   0 0.5 0   1 0 0
)";

double mean_of(const std::string& path) {
    const Image img = io::read_image(path);
    double sum = 0;
    for (const Rgb& p : img.pixels) sum += p.r + p.g + p.b;
    return sum / (3.0 * double(img.pixels.size()));
}

TEST(SeedCommandLine, PositionalOutput) {
    TempDir dir;
    const std::string scene = dir.write("s.scn", kScene);
    auto r = run_phos("render " + scene + " " + dir.file("a.pfm") + " --width 8 --spp 1 -q");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir.file("a.pfm")));
    r = run_phos(scene + " " + dir.file("b.pfm") + " -resolution 8 8 -aa 0 -q");  // no subcommand
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir.file("b.pfm")));
    EXPECT_EQ(read_bytes(dir.file("a.pfm")), read_bytes(dir.file("b.pfm")));
    r = run_phos("render " + scene + " " + dir.file("c.pfm") + " -o " + dir.file("d.pfm"));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_FALSE(std::filesystem::exists(dir.file("c.pfm")));
    EXPECT_FALSE(std::filesystem::exists(dir.file("d.pfm")));
}

TEST(SeedCommandLine, SeedSpellingsOfTheComponentSwitches) {
    TempDir dir;
    const std::string scene = dir.write("s.scn", kScene);
    const std::string common =
        " --integrator photonmap --global 2000 --caustic 2000 -resolution 8 8 -aa 0 -q ";
    for (const std::string seed : {"no_direct", "no_indirect", "photon_viz", "fast_global"}) {
        std::string phos = seed;
        std::replace(phos.begin(), phos.end(), '_', '-');
        ASSERT_EQ(run_phos(scene + " " + dir.file("a.pfm") + common + "-" + seed).exit_code, 0) << seed;
        ASSERT_EQ(run_phos(scene + " " + dir.file("b.pfm") + common + "--" + phos).exit_code, 0) << seed;
        EXPECT_EQ(read_bytes(dir.file("a.pfm")), read_bytes(dir.file("b.pfm"))) << seed;
    }
}

TEST(SeedCommandLine, EnergyCreatingMaterialsAreScaledByDefault) {
    TempDir dir;
    const std::string scene = dir.write("hot.scn", kHotBox);
    const std::string common = " --width 16 --spp 16 --integrator path --max-depth 60 --threads 2 -o ";
    auto r = run_phos("render " + scene + common + dir.file("sane.pfm"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("scaled by 0.625 0.625 0.625"), std::string::npos) << r.output;
    r = run_phos("render " + scene + common + dir.file("raw.pfm") + " --raw-materials");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("kept as written (--raw-materials)"), std::string::npos) << r.output;
    // Scaled: an albedo-1 box lit by a 1 W/sr point light stays bounded (radiance of order
    // I / (π r²) / (1 - ρ) with ρ < 1 after 60 bounces at most). Raw: ρ = 1.6 per bounce grows
    // without bound over the same 60 bounces (Russian roulette cannot remove the gain).
    const double sane = mean_of(dir.file("sane.pfm")), raw = mean_of(dir.file("raw.pfm"));
    EXPECT_TRUE(std::isfinite(sane));
    EXPECT_LT(sane, 10.0);
    EXPECT_GT(raw, 10.0 * sane);
}

// --quality presets set the budgets together; explicit options win.
TEST(SeedCommandLine, QualityPresetsSetBudgetsTogether) {
    TempDir dir;
    const std::string scene = dir.write("s.scn", kScene);
    const std::string common = " --width 16 --threads 2 -o ";
    auto r = run_phos("render " + scene + common + dir.file("draft.pfm") + " --quality draft");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("4 spp (--quality draft)"), std::string::npos) << r.output;
    ASSERT_EQ(run_phos("render " + scene + common + dir.file("explicit.pfm") +
                       " --spp 4 --global 50000 --caustic 25000 --indirect 50000 --gather-rays 4 -q")
                  .exit_code,
              0);
    EXPECT_EQ(read_bytes(dir.file("draft.pfm")), read_bytes(dir.file("explicit.pfm")));
    r = run_phos("render " + scene + common + dir.file("mixed.pfm") +
                 " --quality high --spp 2 --global 3000");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("2 spp (command line)"), std::string::npos) << r.output;
    ASSERT_EQ(run_phos("render " + scene + common + dir.file("mixed2.pfm") +
                       " --spp 2 --global 3000 --caustic 500000 --indirect 1000000 --gather-rays 16 -q")
                  .exit_code,
              0);
    EXPECT_EQ(read_bytes(dir.file("mixed.pfm")), read_bytes(dir.file("mixed2.pfm")));
    r = run_phos("render " + scene + common + dir.file("x.pfm") + " --quality ultra");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("--quality: 'ultra' is not one of draft|normal|high"), std::string::npos)
        << r.output;
}

// The photon mapper is the default where the scene names no integrator: a point-lit glass
// sphere's caustic (which plain path tracing cannot find from a point light) is there by default.
TEST(SeedCommandLine, PhotonMapperIsTheDefaultForScnScenes) {
    TempDir dir;
    const std::string scene = source_path("scenes/caustic-point.scn");
    const std::string common = " --width 64 --spp 4 --threads 2 --global 20000 --caustic 20000 -o ";
    auto r = run_phos("render " + scene + common + dir.file("default.exr"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("photonmap (default)"), std::string::npos) << r.output;
    r = run_phos("render " + scene + common + dir.file("path.exr") + " --integrator path --regularize 0");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // The caustic under the sphere: the bench window (104..128, 132..156 at 256 pixels) at 64.
    auto window = [](const std::string& path) {
        const Image img = io::read_image(path);
        double sum = 0;
        for (int y = 33; y < 39; ++y)
            for (int x = 26; x < 32; ++x) sum += img.at(x, y).g;
        return sum / 36.0;
    };
    const double pm = window(dir.file("default.exr")), path = window(dir.file("path.exr"));
    EXPECT_GT(pm, 1.0) << "reference window mean 4.58";
    EXPECT_GT(pm, 10 * path);
}

// The seed's Makefile command lines run unchanged (output last, after the flags): the flags with a
// phos equivalent take effect, the others are accepted with one warning each.
TEST(SeedCommandLine, SeedMakefileCommandLinesRun) {
    TempDir dir;
    const std::string scene = source_path("scenes/cornell-diffuse.scn");
    const std::string small = " --global 5000 --caustic 5000 ";
    struct Line {
        std::string flags;
        size_t warnings;  // flags without effect
    };
    const Line lines[] = {
        {"-resolution 32 32 -aa 2 -v -lt 64 -ss 0 -tt 64 -st 128 -md 128 -threads 8 -no_caustic -no_indirect "
         "-no_transmissive -no_specular",
         4},
        {"-resolution 32 32 -aa 0 -v -lt 128 -no_rs -no_ss -no_fresnel -no_dt -no_ds -tt 32 -st 32 -md 8 "
         "-threads 8",
         8},
        {"-resolution 32 32 -aa 1 -v -real -lt 64 -ss 64 -tt 128 -st 128 -md 64 -threads 8 -it 4", 4},
        {"-resolution 32 32 -aa 0 -no_ambient -no-monte -absorb 0.01 -pd 8 -gs 40 -gd 0.2 -gf cone 1.1 -cs "
         "30 "
         "-cd 0.05 -cf gauss -cache -no_shadow -s 4",
         4},
    };
    for (const Line& l : lines) {
        const std::string out = dir.file("seed.png");
        std::filesystem::remove(out);
        const auto r = run_phos(scene + " " + l.flags + small + out);
        ASSERT_EQ(r.exit_code, 0) << l.flags << "\n" << r.output;
        EXPECT_TRUE(std::filesystem::exists(out)) << l.flags;
        size_t warnings = 0;
        for (size_t p = r.output.find("has no effect"); p != std::string::npos;
             p = r.output.find("has no effect", p + 1))
            ++warnings;
        EXPECT_EQ(warnings, l.warnings) << l.flags << "\n" << r.output;
    }
}

// The seed flags with a phos equivalent give the same image as the phos options themselves.
TEST(SeedCommandLine, SeedFlagsMapToPhosOptions) {
    TempDir dir;
    const std::string scene = source_path("scenes/cornell-diffuse.scn");
    const std::string common = " --resolution 24 24 --spp 2 --global 5000 --caustic 5000 -o ";
    const auto a =
        run_phos("render " + scene +
                 " -md 3 -it 2 -gs 30 -gd 0.2 -gf cone 1.5 -cs 20 -cd 0.05 -cf gauss -pd 4 -cache" + common +
                 dir.file("seed.pfm"));
    ASSERT_EQ(a.exit_code, 0) << a.output;
    const auto b = run_phos(
        "render " + scene +
        " --max-depth 3 --gather-rays 2 --global-samples 30 --global-radius 0.2 --global-filter cone "
        "--global-cone-k 1.5 --caustic-samples 20 --caustic-radius 0.05 --caustic-filter gauss "
        "--max-photon-depth 4 --irradiance-cache" +
        common + dir.file("phos.pfm"));
    ASSERT_EQ(b.exit_code, 0) << b.output;
    EXPECT_EQ(read_bytes(dir.file("seed.pfm")), read_bytes(dir.file("phos.pfm")));
    // and they change the image (the test would pass trivially if the flags were ignored)
    const auto c = run_phos("render " + scene + common + dir.file("default.pfm"));
    ASSERT_EQ(c.exit_code, 0) << c.output;
    EXPECT_NE(read_bytes(dir.file("seed.pfm")), read_bytes(dir.file("default.pfm")));
}

}  // namespace
}  // namespace phos::testing
