// End-to-end tests of the `phos` command line: help, option validation, exit codes, error
// messages, no partial or clobbered output, and bit-identical images for any thread count.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "test_util.h"

namespace phos::testing {
namespace {

const std::string kTinyScene = R"(
camera 0 0.5 2   0 0 -1   0 1 0   0.4   0.001 100
material 0 0 0   0.7 0.7 0.7   0 0 0   0 0 0   0 0 0   10 1 0
material 0 0 0   0 0 0   0 0 0   1 1 1   0 0 0   1000000 1.5 0
tri 0   -1 0 -1   -1 0 1   1 0 1
tri 0   -1 0 -1   1 0 1   1 0 -1
sphere 1   0 0.3 0   0.3
rect_light 10 10 10   0 1.5 0   1 0 0   0 0 1   0.5 0.5   0 0 1
)";

TEST(Cli, HelpDocumentsEveryRenderOption) {
    const auto top = run_phos("--help");
    EXPECT_EQ(top.exit_code, 0);
    EXPECT_NE(top.output.find("render"), std::string::npos);
    const auto r = run_phos("render --help");
    EXPECT_EQ(r.exit_code, 0);
    for (const char* opt :
         {"--output", "--width", "--height", "--resolution", "--spp", "--aa", "--threads", "--seed",
          "--integrator", "--max-depth", "--verbose", "--exposure", "--schlick", "--dof"})
        EXPECT_NE(r.output.find(opt), std::string::npos) << opt;
}

TEST(Cli, NonsenseOptionsExitWith2) {
    TempDir dir;
    const std::string scene = dir.write("s.scn", kTinyScene);
    const std::string out = dir.file("o.png");
    const std::string with_out = "render " + scene + " -o " + out + " ";  // then the bad option
    const std::vector<std::string> bad_commands = {with_out + "--width 0",
                                                   with_out + "--height -5",
                                                   with_out + "--spp 0",
                                                   with_out + "--spp",
                                                   with_out + "--frobnicate",
                                                   with_out + "--spp abc",
                                                   with_out + "--integrator magic",
                                                   with_out + "--threads -1",
                                                   with_out + "-resolution 10",
                                                   with_out + "--dof 0 1 0.1",
                                                   with_out + "--dof 4 -1 0.1",
                                                   with_out + "--embree-config isa=fast",
                                                   with_out + "--embree-config threads=4",
                                                   "render " + scene + " -o " + dir.file("x.tiff"),
                                                   "render " + scene + " -o " + dir.file("nodir/x.png"),
                                                   "render",
                                                   "bogus-command"};
    for (const std::string& bad : bad_commands) {
        const auto r = run_phos(bad);
        EXPECT_EQ(r.exit_code, 2) << bad << "\n" << r.output;
        EXPECT_FALSE(r.output.empty()) << bad;
        EXPECT_EQ(r.output.find("terminate"), std::string::npos) << bad;
        EXPECT_FALSE(std::filesystem::exists(out)) << bad;
    }
}

TEST(Cli, MalformedSceneGivesLocatedErrorAndNoOutput) {
    TempDir dir;
    const std::string scene =
        dir.write("bad.scn", "material 0 0 0  1 1 1  0 0 0  0 0 0  0 0 0  10 1 0\nsphere 0 0 0 box\n");
    const std::string out = dir.file("o.png");
    const auto r = run_phos("render " + scene + " -o " + out);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("bad.scn:2:"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out));
}

// An error in a mesh or an included file names its own place and every line that included it
// (exit 2, nothing written), for each format that includes files.
TEST(Cli, ErrorInAnIncludedFileNamesTheIncludingLine) {
    TempDir dir;
    dir.write("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n");
    dir.write("parts/walls.scn", "mesh -1 ../bad.off\n");
    dir.write("w.mat", "diffuse 0.5 0.5 0.5\n");
    dir.write("bad.mesh", "ply bad.off\nmaterial w.mat\n");
    dir.write("bad.ply",
              "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
              "property float z\nend_header\n0 0 zero\n");
    dir.write("parts/mesh.pbrt", "Shape \"plymesh\" \"string filename\" \"../bad.ply\"\n");
    struct Case {
        std::string scene, text, mesh, chain;
    };
    const std::vector<Case> cases = {
        {"scene.scn", "# walls\n  include parts/walls.scn\n", "bad.off:4:",
         "included from " + dir.file("parts/walls.scn") + ":1:9\n  included from " + dir.file("scene.scn") +
             ":2:11"},
        {"scene.scene", "\nmesh bad.mesh\n", "bad.off:4:",
         "included from " + dir.file("bad.mesh") + ":1:5\n" + "  included from " + dir.file("scene.scene") +
             ":2:6"},
        {"scene.pbrt", "WorldBegin\nInclude \"parts/mesh.pbrt\"\n", "bad.ply:8:",
         "included from " + dir.file("parts/mesh.pbrt") + ":1:17\n  included from " + dir.file("scene.pbrt") +
             ":2:1"},
    };
    for (const Case& c : cases) {
        const std::string scene = dir.write(c.scene, c.text);
        const std::string out = dir.file("o.png");
        const auto r = run_phos("render " + scene + " -o " + out);
        EXPECT_EQ(r.exit_code, 2) << r.output;
        EXPECT_NE(r.output.find(c.mesh), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("\n  " + c.chain + "\n"), std::string::npos) << r.output;
        EXPECT_FALSE(std::filesystem::exists(out));
        EXPECT_FALSE(std::filesystem::exists(dir.file("scene.png")));
    }
}

// Without -o a .scn or .scene scene is written beside itself as NAME.png, and the start-up line
// says so; a pbrt file names its own (Film "filename") or gets pbrt's default, pbrt.exr, in the
// current directory.
TEST(Cli, DefaultOutputIsBesideTheScene) {
    TempDir dir;
    const std::string scene = dir.write("sub/room.scn", kTinyScene);
    auto r = run_phos("render " + scene + " --resolution 8 8 --spp 1 --integrator path");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir.file("sub/room.png")));
    EXPECT_NE(r.output.find("output " + dir.file("sub/room.png") + " (default: beside the scene"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(read_bytes(scene), kTinyScene);  // the scene itself is untouched
    // The seed's positional output and -o still choose it, and the line says so.
    r = run_phos("render " + scene + " " + dir.file("given.png") + " --resolution 8 8 --spp 1");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("output " + dir.file("given.png") + " (command line)"), std::string::npos)
        << r.output;

    dir.write("w.mat", "diffuse 0.5 0.5 0.5\n");
    const std::string dissertation =
        dir.write("d/one.scene",
                  "camera 0 0 3  0 0 0  0 1 0  2\nsphere 0.5 0 0 0 ../w.mat\nlight point 0 2 2  10 10 10\n");
    r = run_phos("render " + dissertation + " --resolution 8 8 --spp 1 --integrator path");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir.file("d/one.png")));

    const std::string pbrt_scene =
        "Camera \"perspective\"\nWorldBegin\nLightSource \"point\"\n"
        "Shape \"sphere\"\n";
    dir.write("p/none.pbrt", pbrt_scene);
    dir.write("p/named.pbrt", "Film \"rgb\" \"string filename\" \"named.pfm\"\n" + pbrt_scene);
    // Run from the pbrt files' directory (env's -C), where they write.
    for (const auto& [name, written] :
         {std::pair<std::string, std::string>{"none.pbrt", "pbrt.exr"}, {"named.pbrt", "named.pfm"}}) {
        r = run_phos_env("-C " + dir.file("p"), "render " + name + " --resolution 8 8 --spp 1");
        EXPECT_EQ(r.exit_code, 0) << r.output;
        EXPECT_TRUE(std::filesystem::exists(dir.file("p/" + written))) << r.output;
        EXPECT_NE(r.output.find("output " + written + " ("), std::string::npos) << r.output;
    }
}

TEST(Cli, HelpNamesEverySceneFormat) {
    for (const char* command : {"help render", "render --help"}) {
        const auto r = run_phos(command);
        EXPECT_EQ(r.exit_code, 0) << r.output;
        for (const char* format : {".scn", ".pbrt", ".scene"})
            EXPECT_NE(r.output.find(format), std::string::npos) << command << ": " << format;
        EXPECT_NE(r.output.find(".scn, .pbrt, .scene"), std::string::npos) << r.output;
    }
}

TEST(Cli, FailedRenderLeavesExistingOutputUntouched) {
    TempDir dir;
    const std::string scene = dir.write("bad.scn", "sphere 7 0 0 0 1\n");
    const std::string out = dir.write("o.png", "previous contents");
    EXPECT_EQ(run_phos("render " + scene + " -o " + out).exit_code, 2);
    EXPECT_EQ(read_bytes(out), "previous contents");
    EXPECT_EQ(run_phos("render " + dir.file("missing.scn") + " -o " + out).exit_code, 2);
    EXPECT_EQ(read_bytes(out), "previous contents");
}

TEST(Cli, SameSeedIsBitIdenticalForAnyThreadCount) {
    TempDir dir;
    const std::string scene = dir.write("s.scn", kTinyScene);
    for (const std::string integrator : {"path", "whitted"}) {
        const std::string a = dir.file("a-" + integrator + ".pfm"), b = dir.file("b-" + integrator + ".pfm");
        const std::string common = "render " + scene +
                                   " --width 48 --height 32 --spp 4 --seed 7 --integrator " + integrator +
                                   " -q -o ";
        ASSERT_EQ(run_phos(common + a + " --threads 1").exit_code, 0);
        ASSERT_EQ(run_phos(common + b + " --threads 2").exit_code, 0);
        const std::string ba = read_bytes(a), bb = read_bytes(b);
        ASSERT_GT(ba.size(), 48u * 32u * 12u);
        EXPECT_EQ(ba, bb) << integrator;
    }
    // A different seed gives a different image (the seed is really used).
    const std::string c = dir.file("c.pfm");
    ASSERT_EQ(
        run_phos("render " + scene + " --width 48 --height 32 --spp 4 --seed 8 --integrator path -q -o " + c)
            .exit_code,
        0);
    EXPECT_NE(read_bytes(c), read_bytes(dir.file("a-path.pfm")));
}

// --embree-config reaches Embree's device (its verbose=1 banner appears), and with the kernels
// pinned the image is still the same at any thread count.
TEST(Cli, EmbreeConfigReachesTheDevice) {
    TempDir dir;
    const std::string scene = dir.write("s.scn", kTinyScene);
    const std::string common =
        "render " + scene + " --width 32 --height 24 --spp 2 --global 20000 --gather-rays 2 ";
    const auto plain = run_phos(common + "-o " + dir.file("p.pfm"));
    ASSERT_EQ(plain.exit_code, 0) << plain.output;
    EXPECT_EQ(plain.output.find("Embree Ray Tracing Kernels"), std::string::npos) << plain.output;
    const auto banner = run_phos(common + "--embree-config isa=sse4.2,verbose=1 -o " + dir.file("v.pfm"));
    ASSERT_EQ(banner.exit_code, 0) << banner.output;
    EXPECT_NE(banner.output.find("Embree Ray Tracing Kernels"), std::string::npos) << banner.output;
    const std::string a = dir.file("a.pfm"), b = dir.file("b.pfm");
    ASSERT_EQ(run_phos(common + "--embree-config isa=sse4.2 --threads 1 -q -o " + a).exit_code, 0);
    ASSERT_EQ(run_phos(common + "--embree-config isa=sse4.2 --threads 2 -q -o " + b).exit_code, 0);
    ASSERT_GT(read_bytes(a).size(), 32u * 24u * 12u);
    EXPECT_EQ(read_bytes(a), read_bytes(b));
    EXPECT_EQ(read_bytes(a), read_bytes(dir.file("v.pfm")));  // verbose changes nothing else
}

TEST(Cli, VerbosePrintsStatistics) {
    TempDir dir;
    const std::string scene = dir.write("s.scn", kTinyScene);
    const auto r = run_phos("render " + scene + " -resolution 16 16 -aa 1 -v -o " + dir.file("o.exr"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("camera"), std::string::npos);
    EXPECT_NE(r.output.find("shadow"), std::string::npos);
    EXPECT_NE(r.output.find("time render"), std::string::npos);
    EXPECT_NE(r.output.find("4 spp"), std::string::npos) << r.output;  // -aa 1 = 4 samples
    EXPECT_TRUE(std::filesystem::exists(dir.file("o.exr")));
}

// A camera beyond what Embree traces (coordinates over 1.8e18) must not stop phos on Embree's
// assertion (exit 134): its rays hit nothing, and phos says why, once.
TEST(Cli, CameraBeyondEmbreesRangeRendersAndSaysSo) {
    TempDir dir;
    ASSERT_TRUE(dir.ok());
    const std::string scene = (dir.path() / "far.scn").string();
    {
        std::ofstream f(scene);
        f << "camera 0 0.5 1e20   0 0 -1   0 1 0   0.33 0.001 1e30\n"
             "material 0 0 0   0.8 0.8 0.8   0 0 0   0 0 0   0 0 0   10 1 0\n"
             "tri 0   -0.5 0 -0.5   -0.5 0 0.5   0.5 0 0.5\n"
             "point_light 1 1 1   0 0.9 0   0 0 1\n";
    }
    const std::string out = (dir.path() / "far.pfm").string();
    const CommandResult r =
        run_phos("render " + scene + " --integrator path --resolution 8 8 --spp 1 -o " + out);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(out));
    const std::string says = "beyond +-1.8e18";
    const size_t at = r.output.find(says);
    EXPECT_NE(at, std::string::npos) << r.output;
    EXPECT_EQ(r.output.find(says, at + 1), std::string::npos) << r.output;
}

TEST(Cli, DefaultSceneRenders) {
    TempDir dir;
    const auto r = run_phos("render " + source_path("scenes/default.scn") +
                            " --width 32 --height 32 --spp 2 -o " + dir.file("d.png"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir.file("d.png")));
}

// `phos upgrade IN OUT` writes the pbrt-v4 form (which phos renders); it refuses to overwrite its
// input, and a malformed input is a located error with nothing written.
TEST(Cli, UpgradeWritesThePbrtV4FormAndNothingOnError) {
    TempDir dir;
    const std::string v3 = dir.write(
        "v3.pbrt",
        "Film \"image\" \"integer xresolution\" 8 \"integer yresolution\" 8\nWorldBegin\n"
        "AttributeBegin\nAreaLightSource \"area\" \"color L\" [1 1 1]\nShape \"sphere\"\nAttributeEnd\n"
        "Material \"matte\"\nShape \"disk\"\nWorldEnd\n");
    const CommandResult r = run_phos("upgrade " + v3 + " " + dir.file("v4.pbrt"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string text = read_bytes(dir.file("v4.pbrt"));
    EXPECT_NE(text.find("AreaLightSource \"diffuse\""), std::string::npos) << text;
    EXPECT_NE(text.find("Material \"diffuse\""), std::string::npos) << text;
    const CommandResult rendered =
        run_phos("render " + dir.file("v4.pbrt") + " --spp 1 -o " + dir.file("v4.pfm"));
    EXPECT_EQ(rendered.exit_code, 0) << rendered.output;

    const CommandResult same = run_phos("upgrade " + v3 + " " + v3);
    EXPECT_EQ(same.exit_code, 2) << same.output;
    EXPECT_NE(same.output.find("is the input"), std::string::npos) << same.output;
    EXPECT_EQ(read_bytes(v3).find("Film \"image\""), 0u);  // untouched

    const std::string bad = dir.write("bad.pbrt", "WorldBegin\nShape \"sphere\" \"float radius\" [ 1\n");
    const CommandResult failed = run_phos("upgrade " + bad + " " + dir.file("bad-v4.pbrt"));
    EXPECT_EQ(failed.exit_code, 2) << failed.output;
    EXPECT_NE(failed.output.find("bad.pbrt:"), std::string::npos) << failed.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("bad-v4.pbrt")));
}

}  // namespace
}  // namespace phos::testing
