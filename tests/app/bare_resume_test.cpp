// `phos render --resume FILE` without a scene replays the checkpointed render's own arguments
// (options given now override them) and continues it bit for bit.
#include <gtest/gtest.h>

#include <filesystem>

#include "test_util.h"

namespace phos::testing {
namespace {

TEST(BareResume, ReplaysTheCheckpointedArgumentsAndExtendsTheRender) {
    TempDir dir;
    const std::string scene = shared_path("bench/scn/cornell-diffuse.scn");
    const std::string common =
        " --integrator sppm --width 48 --height 40 --photons-per-iter 5000 --seed 3 -q";
    const std::string ck = dir.file("run.ckpt");
    ASSERT_EQ(run_phos("render " + scene + common + " --iterations 3 --checkpoint " + ck + " -o " +
                       dir.file("first.pfm"))
                  .exit_code,
              0);
    ASSERT_TRUE(std::filesystem::exists(ck));
    // No scene, no options: only the checkpoint, a longer budget and a new output name.
    const auto resumed = run_phos("render --resume " + ck + " --iterations 5 -o " + dir.file("resumed.pfm"));
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    ASSERT_EQ(
        run_phos("render " + scene + common + " --iterations 5 -o " + dir.file("straight.pfm")).exit_code, 0);
    EXPECT_EQ(read_bytes(dir.file("resumed.pfm")), read_bytes(dir.file("straight.pfm")));
    // The first output is untouched by the resumed run.
    EXPECT_NE(read_bytes(dir.file("first.pfm")), read_bytes(dir.file("resumed.pfm")));
}

TEST(BareResume, NeedsASceneOrACheckpoint) {
    TempDir dir;
    EXPECT_EQ(run_phos("render -o " + dir.file("x.png")).exit_code, 2);
    const auto r = run_phos("render --resume " + dir.file("missing.ckpt") + " -o " + dir.file("x.png"));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("missing.ckpt"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("x.png")));
}

}  // namespace
}  // namespace phos::testing
