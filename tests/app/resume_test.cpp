// Checkpoint and resume of progressive renders through the phos binary: a render killed with
// SIGKILL mid-way and resumed from its last checkpoint writes exactly the bytes of an uninterrupted
// render with the same total iterations; corrupt, truncated or foreign checkpoints exit 2; a
// resume says what it continues, and warns when the checkpoint already holds more iterations than
// asked; --embree-config is not part of the identity.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "render/progressive_checkpoint.h"
#include "test_util.h"

namespace phos::testing {
namespace {

const std::string kScene = shared_path("bench/scn/caustic-point.scn");
const std::string kArgs =
    " --integrator sppm --width 64 --height 64 --photons-per-iter 30000 --seed 5 --threads 2 -q";

TEST(Resume, KilledRenderResumesToTheSameImage) {
    TempDir dir;
    const std::string ckpt = dir.file("r.ckpt");
    const auto full = run_phos("render " + kScene + kArgs + " --iterations 40 -o " + dir.file("full.pfm"));
    ASSERT_EQ(full.exit_code, 0) << full.output;

    const std::string cmd = "exec " + std::string(PHOS_BINARY) + " render " + kScene + kArgs +
                            " --iterations 40 --checkpoint " + ckpt + " --checkpoint-every 2 -o " +
                            dir.file("killed.pfm") + " >/dev/null 2>&1";
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!std::filesystem::exists(ckpt) && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the render finished before it could be killed";
    EXPECT_FALSE(std::filesystem::exists(dir.file("killed.pfm")));
    const render::ProgressiveState saved = render::load_checkpoint(ckpt);
    EXPECT_GT(saved.iterations, 0u);
    EXPECT_LT(saved.iterations, 40u);
    std::printf("killed after checkpoint of iteration %llu\n",
                static_cast<unsigned long long>(saved.iterations));

    const auto resumed = run_phos("render " + kScene + kArgs + " --iterations 40 --resume " + ckpt + " -o " +
                                  dir.file("resumed.pfm"));
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    const std::string a = read_bytes(dir.file("full.pfm")), b = read_bytes(dir.file("resumed.pfm"));
    EXPECT_GT(a.size(), 64u * 64u * 12u);
    EXPECT_TRUE(a == b) << "resumed image differs from the uninterrupted render";
}

// Embree's kernels already follow the machine, so --embree-config is not part of a checkpoint's
// identity: a render checkpointed with one configuration goes on under another (or none).
TEST(Resume, EmbreeConfigIsNotPartOfTheIdentity) {
    TempDir dir;
    const std::string ckpt = dir.file("e.ckpt");
    const auto first =
        run_phos("render " + kScene + kArgs + " --iterations 3 --embree-config isa=sse4.2 --checkpoint " +
                 ckpt + " -o " + dir.file("first.pfm"));
    ASSERT_EQ(first.exit_code, 0) << first.output;
    const render::ProgressiveState saved = render::load_checkpoint(ckpt);
    ASSERT_FALSE(saved.options.empty());
    for (const auto& [flag, value] : saved.options) EXPECT_EQ(flag.find("embree"), std::string::npos) << flag;
    const auto resumed = run_phos("render " + kScene + kArgs + " --iterations 5 --resume " + ckpt + " -o " +
                                  dir.file("more.pfm"));
    EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
}

TEST(Resume, BadCheckpointsAreRefusedWithExit2) {
    TempDir dir;
    const std::string ckpt = dir.file("c.ckpt");
    ASSERT_EQ(run_phos("render " + kScene + kArgs + " --iterations 2 --checkpoint " + ckpt + " -o " +
                       dir.file("a.pfm"))
                  .exit_code,
              0);
    const std::string good = read_bytes(ckpt);
    std::string corrupt = good;
    corrupt[corrupt.size() / 2] = char(corrupt[corrupt.size() / 2] ^ 0x55);
    const std::string truncated = dir.write("t.ckpt", good.substr(0, good.size() - 100));
    const std::string corrupted = dir.write("x.ckpt", corrupt);
    const std::string other_scene = dir.write("other.scn", read_bytes(kScene) + "\n# changed\n");
    const std::string out = dir.file("o.pfm");
    struct Case {
        std::string args, expect;
    };
    for (const Case& c : std::vector<Case>{
             {kScene + kArgs + " --resume " + truncated, "checksum"},
             {kScene + kArgs + " --resume " + corrupted, "checksum"},
             {kScene + kArgs + " --resume " + dir.file("missing.ckpt"), "cannot open"},
             {kScene + kArgs + " --resume " + kScene, "not a phos checkpoint"},
             {other_scene + kArgs + " --resume " + ckpt, "scene file contents"},
             {kScene + kArgs + " --alpha 0.5 --resume " + ckpt,
              "option --alpha differs: checkpoint 0.7, now 0.5"},
             {kScene +
                  " --integrator sppm --width 32 --height 64 --photons-per-iter 30000 --seed 5 --resume " +
                  ckpt,
              "image size"},
             {kScene +
                  " --integrator ppm --width 64 --height 64 --photons-per-iter 30000 --seed 5 --resume " +
                  ckpt,
              "integrator"},
         }) {
        const auto r = run_phos("render " + c.args + " -o " + out);
        EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
        EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
    }
    // The intact checkpoint resumes.
    const auto ok = run_phos("render " + kScene + kArgs + " --iterations 3 --resume " + ckpt + " -o " + out);
    EXPECT_EQ(ok.exit_code, 0) << ok.output;
}

TEST(Resume, BidirectionalResumeToTheSameImage) {
    // bdpt and vcm keep their image as fixed-point sums (light tracing included) in the checkpoint:
    // 3 iterations, then resumed to 7, give the bytes of 7 straight; a checkpoint of one cannot
    // resume the other.
    TempDir dir;
    for (const std::string integrator : {"bdpt", "vcm"}) {
        const std::string args = " --integrator " + integrator + " --width 40 --height 32 --seed 5 -q";
        const std::string whole = dir.file(integrator + "-whole.pfm"), ck = dir.file(integrator + ".ckpt");
        ASSERT_EQ(run_phos("render " + kScene + args + " --spp 7 -o " + whole).exit_code, 0);
        ASSERT_EQ(
            run_phos("render " + kScene + args + " --spp 3 --checkpoint " + ck + " -o " + dir.file("a.pfm"))
                .exit_code,
            0);
        const auto r =
            run_phos("render " + kScene + args + " --spp 7 --resume " + ck + " -o " + dir.file("b.pfm"));
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_EQ(read_bytes(whole), read_bytes(dir.file("b.pfm"))) << integrator;
        const std::string other = integrator == "bdpt" ? "vcm" : "bdpt";
        const auto refused =
            run_phos("render " + kScene + " --integrator " + other +
                     " --width 40 --height 32 --seed 5 --spp 7 --resume " + ck + " -o " + dir.file("c.pfm"));
        EXPECT_EQ(refused.exit_code, 2) << refused.output;
    }
}

TEST(Resume, TimeBudgetAndPreviews) {
    TempDir dir;
    const std::string out = dir.file("p.pfm");
    const auto r = run_phos("render " + kScene + kArgs + " --time 1.5 --write-every 0.2 -o " + out + " -v");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(out));
    EXPECT_NE(r.output.find("iterations"), std::string::npos) << r.output;
    // Every integrator has a time budget (tests/app/interrupt_test.cpp).
    const auto path =
        run_phos("render " + kScene + " --integrator path --width 16 --height 16 --time 0.3 -o " + out);
    EXPECT_EQ(path.exit_code, 0) << path.output;
}

TEST(Resume, SaysWhatIsResumedAndWarnsWhenAskedForFewer) {
    TempDir dir;
    const std::string ckpt = dir.file("c.ckpt");
    const std::string args = " --integrator sppm --width 32 --height 32 --photons-per-iter 30000 --seed 5";
    ASSERT_EQ(run_phos("render " + kScene + args + " --iterations 4 -q --checkpoint " + ckpt + " -o " +
                       dir.file("four.pfm"))
                  .exit_code,
              0);
    // More iterations: it says where it starts from (sppm's first iteration is the pilot, whose
    // photons are not counted: 3 x 30000 photons).
    const auto more = run_phos("render " + kScene + args + " --iterations 6 --resume " + ckpt + " -o " +
                               dir.file("six.pfm"));
    ASSERT_EQ(more.exit_code, 0) << more.output;
    EXPECT_NE(
        more.output.find("resuming sppm render from " + ckpt + ": 4 of 6 iterations done, 9.00e4 photons"),
        std::string::npos)
        << more.output;
    const auto quiet = run_phos("render " + kScene + args + " --iterations 6 -q --resume " + ckpt + " -o " +
                                dir.file("six.pfm"));
    EXPECT_EQ(quiet.exit_code, 0);
    EXPECT_EQ(quiet.output, "");
    // Fewer: a clear warning, and the image is the checkpoint's 4-iteration one.
    const auto fewer = run_phos("render " + kScene + args + " --iterations 2 --resume " + ckpt + " -o " +
                                dir.file("two.pfm"));
    ASSERT_EQ(fewer.exit_code, 0) << fewer.output;
    EXPECT_NE(fewer.output.find("warning: checkpoint " + ckpt +
                                " already holds 4 iterations, more than the 2 asked: the image is the "
                                "4-iteration one (no further iterations run)"),
              std::string::npos)
        << fewer.output;
    EXPECT_EQ(read_bytes(dir.file("two.pfm")), read_bytes(dir.file("four.pfm")));
}

}  // namespace
}  // namespace phos::testing
