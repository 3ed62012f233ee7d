// The option tables as a user meets them: every table option in --help with its default and in
// docs/options.md; pbrt Integrator parameters mapped onto the same options (and changing the
// image); located errors and warnings for scene-file parameters; the start-up line; commands, help
// and version; a single --width keeping the aspect ratio; warnings once and naming the cause.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/lib/render_options.h"
#include "test_util.h"

namespace phos::testing {
namespace {

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// A small pbrt scene: a point-lit floor and back wall (light bounces between them) seen from above.
std::string pbrt_scene(const std::string& integrator_line) {
    return "LookAt 0 3 3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
           "Film \"rgb\" \"integer xresolution\" 24 \"integer yresolution\" 16\n" +
           integrator_line +
           "\nWorldBegin\nLightSource \"point\" \"rgb I\" [5 5 5] \"point3 from\" [0 2 0]\n"
           "Material \"diffuse\"\nShape \"trianglemesh\" \"point3 P\" [-2 0 -2  2 0 -2  2 0 2  -2 0 2] "
           "\"integer indices\" [0 1 2 0 2 3]\n"
           "Shape \"trianglemesh\" \"point3 P\" [-2 0 -2  2 0 -2  2 3 -2  -2 3 -2] \"integer indices\" [0 1 "
           "2 0 2 3]\n";
}

TEST(Options, EveryTableOptionIsInHelpWithItsDefault) {
    const auto r = run_phos("render --help");
    ASSERT_EQ(r.exit_code, 0);
    for (const options::Table* t : app::all_tables())
        for (const options::Option& o : t->options) {
            EXPECT_NE(r.output.find("--" + o.name), std::string::npos) << o.name;
            std::string def = t->default_text(o);
            if (def.empty()) def = "none";
            EXPECT_NE(r.output.find("(default: " + def + ")"), std::string::npos) << o.name << ": " << def;
        }
    // The defaults a new user looks for first.
    for (const char* s : {"--spp N", "--integrator NAME", "--width W", "--max-depth N", "--seed S"})
        EXPECT_NE(r.output.find(s), std::string::npos) << s;
    EXPECT_NE(r.output.find("(default: 16)"), std::string::npos);  // --max-depth
    EXPECT_NE(r.output.find("the scene file's (pbrt: path unless it names one), else photonmap"),
              std::string::npos);
}

TEST(Options, DocsReferenceIsGeneratedFromTheTables) {
    const auto r = run_phos("options --markdown");
    ASSERT_EQ(r.exit_code, 0);
    std::ifstream f(std::string(PHOS_SOURCE_DIR) + "/docs/options.md");
    std::stringstream docs;
    docs << f.rdbuf();
    EXPECT_EQ(docs.str(), r.output) << "docs/options.md is stale: regenerate it with "
                                       "`build/phos options --markdown > docs/options.md`";
    for (const options::Table* t : app::all_tables())
        for (const options::Option& o : t->options)
            EXPECT_NE(r.output.find("`--" + o.name), std::string::npos);
}

TEST(Options, PbrtSppmParametersChangeTheImageAndTheCommandLineWins) {
    TempDir dir;
    const std::string plain = dir.write("plain.pbrt", pbrt_scene("Integrator \"sppm\""));
    const std::string with = dir.write(
        "with.pbrt",
        pbrt_scene("Integrator \"sppm\" \"float radius\" 0.3 \"integer photonsperiteration\" 3000"));
    const std::string common = " --spp 3 -q --threads 2 -o ";
    ASSERT_EQ(run_phos("render " + plain + common + dir.file("plain.pfm")).exit_code, 0);
    ASSERT_EQ(run_phos("render " + with + common + dir.file("with.pfm")).exit_code, 0);
    ASSERT_EQ(
        run_phos("render " + plain + common + dir.file("cli.pfm") + " --radius 0.3 --photons-per-iter 3000")
            .exit_code,
        0);
    EXPECT_TRUE(read_bytes(dir.file("plain.pfm")) != read_bytes(dir.file("with.pfm")));
    EXPECT_TRUE(read_bytes(dir.file("with.pfm")) == read_bytes(dir.file("cli.pfm")));
    // The command line overrides the file's parameters.
    ASSERT_EQ(
        run_phos("render " + with + common + dir.file("over.pfm") + " --radius 0 --photons-per-iter 200000")
            .exit_code,
        0);
    EXPECT_TRUE(read_bytes(dir.file("plain.pfm")) == read_bytes(dir.file("over.pfm")));
}

TEST(Options, PbrtParameterErrorsAndWarningsAreLocated) {
    TempDir dir;
    const std::string bad = dir.write("bad.pbrt", pbrt_scene("Integrator \"sppm\" \"float radius\" -1"));
    auto r = run_phos("render " + bad + " -o " + dir.file("bad.png"));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(
                  "bad.pbrt:4:19: Integrator parameter \"float radius\" (--radius): -1 is not in [0, inf)"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("bad.png")));

    const std::string unused = dir.write(
        "unused.pbrt", pbrt_scene("Integrator \"sppm\" \"float radiuss\" 1 \"integer maxdepth\" 3"));
    r = run_phos("render " + unused + " --spp 1 -o " + dir.file("u.png"));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(count(r.output, "warning"), 1u) << r.output;
    EXPECT_NE(r.output.find("unused.pbrt:4:19: Integrator parameter \"float radiuss\" is not used by phos"),
              std::string::npos)
        << r.output;
    r = run_phos("render " + unused + " --spp 1 --strict -o " + dir.file("s.png"));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("unused.pbrt:4:19:"), std::string::npos) << r.output;
}

TEST(Options, SubstitutedIntegratorWarnsOnlyWhenNotChosen) {
    TempDir dir;
    const std::string scene = dir.write("b.pbrt", pbrt_scene("Integrator \"mlt\" \"integer maxdepth\" 4"));
    auto r = run_phos("render " + scene + " --spp 1 -o " + dir.file("a.png"));
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(count(r.output, "warning"), 1u) << r.output;
    EXPECT_NE(r.output.find("b.pbrt:4:1: Integrator \"mlt\" is not available in phos; using bdpt"),
              std::string::npos)
        << r.output;
    r = run_phos("render " + scene + " --spp 1 --integrator path -o " + dir.file("b.png"));
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(count(r.output, "warning"), 0u) << r.output;
}

TEST(Options, StartupLineSaysWhereSettingsCameFrom) {
    TempDir dir;
    const std::string scene = dir.write("s.pbrt", pbrt_scene("Integrator \"path\"") + "");
    auto r = run_phos("render " + scene + " --width 48 -o " + dir.file("a.pfm"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // 24x16 in the file: --width 48 alone keeps 3:2.
    EXPECT_NE(
        r.output.find("path (scene file), 48x32 (command line; height keeps the scene file's aspect ratio), "
                      "16 spp (default), seed 0"),
        std::string::npos)
        << r.output;
    r = run_phos("render " + scene + " --height 8 --integrator whitted --spp 2 -o " + dir.file("b.pfm"));
    EXPECT_NE(r.output.find("whitted (command line), 12x8 (command line; width keeps"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("2 spp (command line)"), std::string::npos) << r.output;
    // A .scn scene has no size: --width alone gives a square image, not W x 512.
    const std::string scn = dir.write("t.scn",
                                      "camera 0 0 3  0 0 -1  0 1 0  0.5  0.01 100\n"
                                      "material 0 0 0  .5 .5 .5  0 0 0  0 0 0  0 0 0  1 1 0\n"
                                      "sphere 0  0 0 0  1\npoint_light 1 1 1  0 2 2  1 0 0\n");
    r = run_phos("render " + scn + " --width 20 --spp 1 -o " + dir.file("c.pfm"));
    EXPECT_NE(r.output.find("20x20 (command line; height keeps the default square aspect)"),
              std::string::npos)
        << r.output;
}

TEST(Options, SceneSampleCountIsABudgetForItsOwnIntegrator) {
    TempDir dir;
    const std::string scene =
        dir.write("s.pbrt", pbrt_scene("Integrator \"path\"\nSampler \"halton\" \"integer pixelsamples\" 3"));
    auto r = run_phos("render " + scene + " -o " + dir.file("a.pfm"));
    EXPECT_NE(r.output.find("3 spp (scene file)"), std::string::npos) << r.output;
    r = run_phos("render " + scene + " --integrator whitted -o " + dir.file("b.pfm"));
    EXPECT_NE(r.output.find("16 spp (default; the scene file's 3 are for its path integrator)"),
              std::string::npos)
        << r.output;
}

TEST(Options, OptionsForAnotherIntegratorWarnOrAreRefused) {
    TempDir dir;
    const std::string scene = dir.write("s.pbrt", pbrt_scene("Integrator \"path\""));
    auto r = run_phos("render " + scene + " --spp 1 --alpha 0.5 -o " + dir.file("a.pfm"));
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.output.find("warning: --alpha has no effect on the path integrator (ppm/sppm/vcm only)"),
              std::string::npos)
        << r.output;
    // Budgets that do not apply would silently not bound the work: refused.
    r = run_phos("render " + scene + " --iterations 4 -o " + dir.file("b.pfm"));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find(
                  "--iterations is for the ppm/sppm/bdpt/vcm integrators (this render uses path; --spp and "
                  "--time bound any render)"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("b.pfm")));
}

TEST(Options, CommandsHelpAndVersion) {
    auto r = run_phos("rendr x.scn");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("unknown command 'rendr'; did you mean 'phos render'?"), std::string::npos)
        << r.output;
    r = run_phos("missing-scene.scn");  // the seed's form: renders (here: the file is missing)
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("missing-scene.scn: cannot open scene file"), std::string::npos) << r.output;
    r = run_phos("help");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.output.find("render"), std::string::npos);
    EXPECT_NE(r.output.find("diff"), std::string::npos);
    r = run_phos("help render");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.output.find("--photons-per-iter"), std::string::npos);
    for (const char* v : {"--version", "-V"}) {
        r = run_phos(v);
        EXPECT_EQ(r.exit_code, 0) << v;
        EXPECT_NE(r.output.find("phos 0."), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("Embree 3."), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("oneTBB"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("GCC"), std::string::npos) << r.output;
    }
    r = run_phos("render x.scn --photons-per-itr 5");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("did you mean --photons-per-iter?"), std::string::npos) << r.output;
}

TEST(Options, NoLightsWarnsOnceNamingTheCause) {
    TempDir dir;
    const std::string scn = dir.write("dark.scn",
                                      "camera 0 0 3  0 0 -1  0 1 0  0.5  0.01 100\n"
                                      "material 0 0 0  .5 .5 .5  0 0 0  0 0 0  1 1 1  1 1 0\n"
                                      "sphere 0  0 0 0  1\n");
    for (const char* integrator : {"path", "photonmap", "sppm"}) {
        const auto r =
            run_phos("render " + scn + " --width 8 --spp 1 --no-default-lights --no-emission-lights" +
                     " --integrator " + std::string(integrator) + " -o " + dir.file("d.pfm"));
        EXPECT_EQ(r.exit_code, 0) << r.output;
        EXPECT_EQ(count(r.output, "warning"), 1u) << integrator << ": " << r.output;
        EXPECT_NE(r.output.find("no lights"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("--no-emission-lights"), std::string::npos) << r.output;  // it glows
        EXPECT_EQ(r.output.find("max-emitted"), std::string::npos) << r.output;
        // By default its glow is a light: no warning.
        const auto lit = run_phos("render " + scn + " --width 8 --spp 1 --no-default-lights --integrator " +
                                  std::string(integrator) + " -o " + dir.file("d.pfm"));
        EXPECT_EQ(lit.exit_code, 0) << lit.output;
        EXPECT_EQ(count(lit.output, "warning"), 0u) << integrator << ": " << lit.output;
    }
}

}  // namespace
}  // namespace phos::testing
