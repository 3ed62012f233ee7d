// Interrupts, budgets and resume for every integrator, through the phos binary: a render killed
// with SIGKILL and resumed from its checkpoint, or stopped with SIGINT / SIGTERM (exit 130 / 143,
// the image so far written and correctly normalised, the checkpoint kept) and resumed, is
// byte-identical to an uninterrupted render of the same total; an interrupt while photons are
// traced writes nothing and leaves the previous image; a second interrupt exits at once; --time
// bounds path; failed writes (file size limit, unwritable directory) keep the previous files.
#include "core/interrupt.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "io/image/image_io.h"
#include "render/progressive_checkpoint.h"
#include "test_util.h"

namespace phos::testing {
namespace {

using Clock = std::chrono::steady_clock;

// A phos process in the background, its output in a file.
class Background {
public:
    Background(const std::string& args, const std::string& log) {
        const std::string cmd = "exec " + std::string(PHOS_BINARY) + " " + args + " >" + log + " 2>&1";
        pid_ = fork();
        if (pid_ == 0) {
            execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
            _exit(127);
        }
    }
    ~Background() {
        if (pid_ > 0 && !waited_) {
            kill(pid_, SIGKILL);
            wait();
        }
    }
    bool started() const { return pid_ > 0; }
    void signal(int sig) const { kill(pid_, sig); }
    // Waits for the process; returns its wait status (-1 if it is still running after `limit`).
    int wait(std::chrono::seconds limit = std::chrono::seconds(120)) {
        const auto deadline = Clock::now() + limit;
        int status = 0;
        while (Clock::now() < deadline) {
            if (waitpid(pid_, &status, WNOHANG) == pid_) {
                waited_ = true;
                return status;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        return -1;
    }

private:
    pid_t pid_ = -1;
    bool waited_ = false;
};

// Waits until `path` exists (a checkpoint, a progress line); false after two minutes.
bool wait_for_file(const std::string& path) {
    const auto deadline = Clock::now() + std::chrono::seconds(120);
    while (!std::filesystem::exists(path) && Clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    return std::filesystem::exists(path);
}

double image_mean(const std::string& path) {
    const Image img = io::read_image(path, false);
    double sum = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const Rgb c = img.at(x, y);
            sum += double(c.r) + double(c.g) + double(c.b);
        }
    return sum / (3.0 * double(img.width) * double(img.height));
}

const std::string kCornell = shared_path("bench/scn/cornell-glass-mirror.scn");

struct Case {
    const char* integrator;
    std::string args;  // budget and options, long enough to be killed mid-way
};

class KilledRender : public ::testing::TestWithParam<Case> {};

TEST_P(KilledRender, ResumesToTheSameBytes) {
    const Case& c = GetParam();
    TempDir dir;
    const std::string ckpt = dir.file("r.ckpt");
    const std::string args = "render " + kCornell + " --integrator " + c.integrator +
                             " --width 64 --height 64 --seed 3 --threads 2 -q " + c.args;
    const auto full = run_phos(args + " -o " + dir.file("full.pfm"));
    ASSERT_EQ(full.exit_code, 0) << full.output;

    Background render(args + " --checkpoint " + ckpt + " --checkpoint-every 1 -o " + dir.file("killed.pfm"),
                      dir.file("log"));
    ASSERT_TRUE(render.started());
    ASSERT_TRUE(wait_for_file(ckpt));
    render.signal(SIGKILL);
    const int status = render.wait();
    ASSERT_TRUE(WIFSIGNALED(status)) << "the render finished before it could be killed";
    EXPECT_FALSE(std::filesystem::exists(dir.file("killed.pfm")));
    const render::ProgressiveState saved = render::load_checkpoint(ckpt);
    EXPECT_EQ(saved.integrator, c.integrator);
    EXPECT_GT(saved.iterations, 0u);
    EXPECT_LT(saved.iterations, saved.target_iterations);
    std::printf("%s killed after a checkpoint at %llu samples per pixel\n", c.integrator,
                static_cast<unsigned long long>(saved.iterations));

    // The bare form: the checkpoint's own arguments.
    const auto resumed = run_phos("render --resume " + ckpt + " -q -o " + dir.file("resumed.pfm"));
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    const std::string a = read_bytes(dir.file("full.pfm")), b = read_bytes(dir.file("resumed.pfm"));
    EXPECT_GT(a.size(), 64u * 64u * 12u);
    EXPECT_TRUE(a == b) << c.integrator << ": the resumed image differs from the uninterrupted render";
}

INSTANTIATE_TEST_SUITE_P(
    EveryIntegrator, KilledRender,
    ::testing::Values(Case{"path", "--spp 96"}, Case{"whitted", "--spp 512"},
                      Case{"photonmap", "--spp 24 --global 20000 --caustic 20000 --gather-rays 16"},
                      Case{"bdpt", "--spp 100"}, Case{"vcm", "--spp 60 --layers"}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.integrator); });

// A finished render extended through its checkpoint equals the longer render made at once; for
// the photon mapper the checkpoint holds the maps, which are read instead of traced again. Below 9
// samples per pixel its caustic kernel depends on the count, so that extension is refused.
TEST(Resume, ExtendingARenderEqualsRenderingItWhole) {
    TempDir dir;
    for (const char* integrator : {"path", "photonmap"}) {
        const std::string ckpt = dir.file(std::string(integrator) + ".ckpt");
        const std::string args = "render " + kCornell + " --integrator " + integrator +
                                 " --width 32 --height 32 --global 20000 --caustic 20000 --gather-rays 8 -q";
        ASSERT_EQ(run_phos(args + " --spp 12 --checkpoint " + ckpt + " -o " + dir.file("a.pfm")).exit_code,
                  0);
        const auto more = run_phos(args + " --spp 20 --resume " + ckpt + " -v -o " + dir.file("b.pfm"));
        ASSERT_EQ(more.exit_code, 0) << more.output;
        ASSERT_EQ(run_phos(args + " --spp 20 -o " + dir.file("c.pfm")).exit_code, 0);
        EXPECT_TRUE(read_bytes(dir.file("b.pfm")) == read_bytes(dir.file("c.pfm"))) << integrator;
        if (std::string(integrator) == "photonmap") {
            EXPECT_NE(more.output.find("photon maps read from the checkpoint"), std::string::npos)
                << more.output;
            EXPECT_EQ(more.output.find("time photon trace"), std::string::npos) << more.output;
            ASSERT_EQ(run_phos(args + " --spp 4 --checkpoint " + ckpt + " -o " + dir.file("d.pfm")).exit_code,
                      0);
            const auto low = run_phos(args + " --spp 8 --resume " + ckpt + " -o " + dir.file("e.pfm"));
            EXPECT_EQ(low.exit_code, 2) << low.output;
            EXPECT_NE(low.output.find("depends on it below 9 samples) differs: checkpoint 4, now 8"),
                      std::string::npos)
                << low.output;
        }
    }
}

// SIGINT mid-render: exit 130, the image so far (each pixel normalised by its own samples, so its
// mean matches a finished render's), the checkpoint (tiles part-way through a pass included); the
// resumed render equals an uninterrupted one of the same total.
TEST(Interrupt, SigintWritesTheImageSoFarAndResumesExactly) {
    TempDir dir;
    const std::string ckpt = dir.file("i.ckpt"), out = dir.file("i.pfm");
    const std::string args =
        "render " + kCornell + " --integrator path --width 64 --height 64 --seed 9 --threads 2";
    const auto ref = run_phos(args + " --spp 16 -q -o " + dir.file("ref.pfm"));
    ASSERT_EQ(ref.exit_code, 0) << ref.output;

    Background render(args + " --spp 1000000 --checkpoint " + ckpt + " --checkpoint-every 4 -o " + out,
                      dir.file("log"));
    ASSERT_TRUE(wait_for_file(ckpt));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    render.signal(SIGINT);
    const int status = render.wait();
    ASSERT_TRUE(WIFEXITED(status)) << "status " << status;
    EXPECT_EQ(WEXITSTATUS(status), 130);
    const std::string log = read_bytes(dir.file("log"));
    EXPECT_NE(log.find("warning: interrupted: the image holds the work done so far ("), std::string::npos)
        << log;
    EXPECT_NE(log.find("continue it with phos render --resume " + ckpt), std::string::npos) << log;
    ASSERT_TRUE(std::filesystem::exists(out)) << log;
    const double mean = image_mean(out), ref_mean = image_mean(dir.file("ref.pfm"));
    EXPECT_NEAR(mean, ref_mean, 0.03 * ref_mean) << "the interrupted image is not normalised by its samples";

    const render::ProgressiveState saved = render::load_checkpoint(ckpt);
    uint32_t most = 0;
    for (uint32_t s : saved.tile_samples) most = std::max(most, s);
    const std::string total = std::to_string(most + 3);
    const auto resumed =
        run_phos(args + " --spp " + total + " -q --resume " + ckpt + " -o " + dir.file("res.pfm"));
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    const auto straight = run_phos(args + " --spp " + total + " -q -o " + dir.file("straight.pfm"));
    ASSERT_EQ(straight.exit_code, 0) << straight.output;
    EXPECT_TRUE(read_bytes(dir.file("res.pfm")) == read_bytes(dir.file("straight.pfm")));
}

// SIGTERM (a batch system's stop) on a progressive render: exit 143, image and checkpoint written.
TEST(Interrupt, SigtermOnSppmExits143WithImageAndCheckpoint) {
    TempDir dir;
    const std::string ckpt = dir.file("s.ckpt"), out = dir.file("s.pfm");
    Background render(
        "render " + shared_path("bench/scn/caustic-point.scn") +
            " --integrator sppm --width 64 --height 64 --photons-per-iter 30000 --iterations 100000 "
            "--checkpoint " +
            ckpt + " --checkpoint-every 2 -o " + out,
        dir.file("log"));
    ASSERT_TRUE(wait_for_file(ckpt));
    render.signal(SIGTERM);
    const int status = render.wait();
    ASSERT_TRUE(WIFEXITED(status)) << "status " << status;
    EXPECT_EQ(WEXITSTATUS(status), 143);
    EXPECT_TRUE(std::filesystem::exists(out)) << read_bytes(dir.file("log"));
    const render::ProgressiveState saved = render::load_checkpoint(ckpt);
    EXPECT_GE(saved.iterations, 2u);
    EXPECT_NE(read_bytes(dir.file("log")).find("of 100000 iterations"), std::string::npos);
}

// An interrupt while the photon maps are traced: nothing to show, so nothing is written and the
// previous image stays as it was.
TEST(Interrupt, DuringPhotonTracingWritesNothing) {
    TempDir dir;
    const std::string out = dir.write("old.pfm", "previous bytes");
    const std::string log = dir.file("log");
    Background render(
        "render " + kCornell + " --integrator photonmap --width 64 --height 64 --global 30000000 -o " + out,
        log);
    // The start-up line is printed once tracing is about to begin.
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    while (read_bytes(log).find("seed") == std::string::npos && Clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    render.signal(SIGINT);
    const int status = render.wait(std::chrono::seconds(30));
    ASSERT_NE(status, -1) << "no exit within 30 s of the interrupt";
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);
    EXPECT_EQ(read_bytes(out), "previous bytes");
    EXPECT_NE(read_bytes(log).find("no image written"), std::string::npos) << read_bytes(log);
}

// The second interrupt ends the process at once with 130 (the first only asks to stop).
TEST(Interrupt, SecondSignalExitsAtOnce) {
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        interrupt::install_handlers();
        raise(SIGINT);
        if (!interrupt::requested() || interrupt::signal_number() != SIGINT) _exit(1);
        raise(SIGINT);
        _exit(0);  // not reached
    }
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);
    EXPECT_EQ(interrupt::exit_status(SIGTERM), 143);
}

TEST(Budget, TimeBoundsEveryIntegrator) {
    TempDir dir;
    for (const char* integrator : {"path", "whitted", "photonmap"}) {
        const std::string out = dir.file(std::string(integrator) + ".pfm");
        const auto r = run_phos("render " + kCornell + " --integrator " + integrator +
                                " --width 32 --height 32 --global 20000 --time 0.5 -v -o " + out);
        if (std::string(integrator) != "photonmap") {
            // --global is a photonmap option: a warning elsewhere, not an error.
            EXPECT_NE(r.output.find("--global has no effect"), std::string::npos) << r.output;
        }
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_NE(r.output.find("samples until 0.5 s"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("samples per pixel, integrator " + std::string(integrator)),
                  std::string::npos)
            << r.output;
        EXPECT_TRUE(std::filesystem::exists(out));
    }
    // Iterations remain the progressive integrators' count.
    const auto bad =
        run_phos("render " + kCornell + " --integrator path --iterations 4 -o " + dir.file("x.pfm"));
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_NE(bad.output.find("--iterations is for the ppm/sppm/bdpt/vcm integrators"), std::string::npos)
        << bad.output;
}

// A file-size limit (as a full disk) while writing the image: the previous image is intact, the
// error says so, and the image is saved to the temporary directory instead.
TEST(FailedWrites, FileSizeLimitKeepsThePreviousImage) {
    TempDir dir;
    const std::string out = dir.write("big.pfm", "previous image");
    const std::string cmd = "ulimit -f 8; TMPDIR=" + dir.path().string() + " " + std::string(PHOS_BINARY) +
                            " render " + kCornell +
                            " --integrator whitted --width 128 --height 128 --spp 1 -o " + out + " 2>&1";
    FILE* pipe = popen(("sh -c '" + cmd + "'").c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string output;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) output.append(buf, n);
    const int status = pclose(pipe);
    ASSERT_TRUE(WIFEXITED(status)) << output;
    EXPECT_EQ(WEXITSTATUS(status), 2) << output;
    EXPECT_EQ(read_bytes(out), "previous image");
    EXPECT_NE(output.find("cannot write '" + out + "'"), std::string::npos) << output;
    EXPECT_NE(output.find("a previous file there is intact"), std::string::npos) << output;
    // 128 x 128 float RGB is 196 kB, over the 8 kB limit: the rescue copy fails too, and says so.
    EXPECT_NE(output.find("could not be saved elsewhere either"), std::string::npos) << output;
}

// A failing checkpoint write does not stop the render; an unwritable output directory is refused
// before any work.
TEST(FailedWrites, UnwritableDirectoriesAreRefusedBeforeRendering) {
    TempDir dir;
    const std::string args = "render " + kCornell + " --integrator whitted --width 16 --height 16 --spp 1";
    // /proc accepts no new files, even from root.
    const auto out = run_phos(args + " -o /proc/phos-out.pfm");
    EXPECT_EQ(out.exit_code, 2) << out.output;
    EXPECT_NE(out.output.find("output '/proc/phos-out.pfm': cannot create files in '/proc'"),
              std::string::npos)
        << out.output;
    const auto ck = run_phos(args + " --checkpoint /proc/phos.ckpt -o " + dir.file("a.pfm"));
    EXPECT_EQ(ck.exit_code, 2) << ck.output;
    EXPECT_NE(ck.output.find("checkpoint '/proc/phos.ckpt': cannot create files"), std::string::npos)
        << ck.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("a.pfm")));
}

}  // namespace
}  // namespace phos::testing
