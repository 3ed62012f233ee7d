// phos under OpenMPI's mpirun (docs/distributed.md): two or three ranks give byte for byte the
// image one process gives, for every integrator (threads 1 per rank against one process with two
// threads); checkpoints move between rank counts; a bad input fails once and cleanly; a killed
// rank ends the job without writing; an interrupt writes the image so far. Skipped when phos was
// built without MPI or mpirun is missing (scripts/setup.sh installs both).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "dist/ranks.h"
#include "test_util.h"

namespace phos::testing {
namespace {

const std::string kScene = shared_path("bench/scn/cornell-glass-mirror.scn");
const std::string kSmall = " --width 48 --height 36 ";

bool have_mpi() { return dist::built_with_mpi() && std::system("command -v mpirun >/dev/null 2>&1") == 0; }

// Runs `mpirun -np N phos ARGS`, capturing its output.
CommandResult run_mpi(int ranks, const std::string& args) {
    const std::string cmd = "mpirun --allow-run-as-root --oversubscribe -np " + std::to_string(ranks) + " " +
                            std::string(PHOS_BINARY) + " " + args + " 2>&1";
    CommandResult r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.output.append(buf, n);
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

#define REQUIRE_MPI() \
    if (!have_mpi()) GTEST_SKIP() << "built without MPI or no mpirun (scripts/setup.sh installs OpenMPI)"

struct Case {
    const char* integrator;
    const char* budget;
};

TEST(Mpi, RanksGiveTheSingleProcessImageByteForByte) {
    REQUIRE_MPI();
    const Case cases[] = {{"path", "--spp 6"},
                          {"whitted", "--spp 2"},
                          {"photonmap", "--spp 2 --global 20000 --caustic 20000 --layers"},
                          {"ppm", "--iterations 3 --photons-per-iter 20000"},
                          {"sppm", "--iterations 4 --photons-per-iter 20000"},
                          {"bdpt", "--spp 3"},
                          {"vcm", "--spp 3"},
                          {"vcm", "--spp 2 --vcm-light-paths 2 --layers"}};
    TempDir dir;
    for (const Case& c : cases) {
        const std::string opts =
            "render " + kScene + kSmall + "--integrator " + c.integrator + " " + c.budget;
        const std::string one = dir.file(std::string(c.integrator) + "-1.exr"),
                          two = dir.file(std::string(c.integrator) + "-2.exr");
        const auto a = run_phos(opts + " --threads 2 -q -o " + one);
        ASSERT_EQ(a.exit_code, 0) << a.output;
        const auto b = run_mpi(2, opts + " --threads 1 -v -o " + two);
        ASSERT_EQ(b.exit_code, 0) << b.output;
        EXPECT_EQ(read_bytes(one), read_bytes(two)) << c.integrator << ": 2 ranks differ from one process";
        // Rank 0 alone speaks: one start-up line, and -v lists both ranks.
        EXPECT_EQ(b.output.find("phos: cornell-glass-mirror.scn"),
                  b.output.rfind("phos: cornell-glass-mirror.scn"))
            << b.output;
        EXPECT_NE(b.output.find("rank 1 of 2"), std::string::npos) << b.output;
        if (std::string(c.integrator) == "photonmap") {
            for (const char* layer : {"direct", "caustic", "indirect", "specular"})
                EXPECT_EQ(read_bytes(dir.file(std::string("photonmap-1.") + layer + ".exr")),
                          read_bytes(dir.file(std::string("photonmap-2.") + layer + ".exr")))
                    << layer;
        }
    }
    // Three ranks (tiles not a multiple of the rank count), with the photon maps split three ways.
    const std::string opts = "render " + kScene + kSmall + "--integrator photonmap --spp 3 --global 30000";
    const auto a = run_phos(opts + " -q -o " + dir.file("p3-1.pfm"));
    const auto b = run_mpi(3, opts + " --threads 1 -q -o " + dir.file("p3-3.pfm"));
    ASSERT_EQ(a.exit_code, 0) << a.output;
    ASSERT_EQ(b.exit_code, 0) << b.output;
    EXPECT_EQ(read_bytes(dir.file("p3-1.pfm")), read_bytes(dir.file("p3-3.pfm")));
}

TEST(Mpi, CheckpointsMoveBetweenRankCounts) {
    REQUIRE_MPI();
    TempDir dir;
    for (const Case& c : {Case{"path", "--spp"}, Case{"sppm", "--photons-per-iter 20000 --iterations"},
                          Case{"vcm", "--spp"}}) {
        const std::string base =
            "render " + kScene + kSmall + "--integrator " + c.integrator + " " + c.budget;
        const std::string whole = dir.file(std::string(c.integrator) + "-whole.pfm");
        ASSERT_EQ(run_phos(base + " 8 -q -o " + whole).exit_code, 0);
        // 2 ranks to 4, then one process on to 8.
        const std::string ck = dir.file(std::string(c.integrator) + ".ckpt");
        const auto first =
            run_mpi(2, base + " 4 --threads 1 --checkpoint " + ck + " -q -o " + dir.file("a.pfm"));
        ASSERT_EQ(first.exit_code, 0) << first.output;
        const std::string resumed = dir.file(std::string(c.integrator) + "-resumed.pfm");
        const auto second = run_phos(base + " 8 --resume " + ck + " -q -o " + resumed);
        ASSERT_EQ(second.exit_code, 0) << second.output;
        EXPECT_EQ(read_bytes(whole), read_bytes(resumed)) << c.integrator << ": 2 ranks, then one process";
        // One process to 4, then 3 ranks on to 8.
        const std::string ck1 = dir.file(std::string(c.integrator) + "-1.ckpt");
        ASSERT_EQ(run_phos(base + " 4 --checkpoint " + ck1 + " -q -o " + dir.file("b.pfm")).exit_code, 0);
        const std::string resumed3 = dir.file(std::string(c.integrator) + "-resumed3.pfm");
        const auto third = run_mpi(3, base + " 8 --threads 1 --resume " + ck1 + " -q -o " + resumed3);
        ASSERT_EQ(third.exit_code, 0) << third.output;
        EXPECT_EQ(read_bytes(whole), read_bytes(resumed3)) << c.integrator << ": one process, then 3 ranks";
    }
}

TEST(Mpi, PixelTracesAreTheSingleProcessOnes) {
    // --trace-pixel under MPI: rank 0 reports every photon the pixel gathered, whichever rank
    // traced it, and the same paths as one process.
    REQUIRE_MPI();
    TempDir dir;
    for (const char* integrator : {"path", "photonmap", "sppm"}) {
        const std::string opts = "render " + kScene + kSmall + "--integrator " + integrator +
                                 " --spp 2 --photons-per-iter 20000 --global 20000 --trace-pixel 30 20 -q";
        const std::string one = dir.file(std::string(integrator) + "-1.json"),
                          two = dir.file(std::string(integrator) + "-2.json");
        ASSERT_EQ(run_phos(opts + " --trace-json " + one + " -o " + dir.file("a.pfm")).exit_code, 0);
        const auto r = run_mpi(2, opts + " --threads 1 --trace-json " + two + " -o " + dir.file("b.pfm"));
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_EQ(read_bytes(one), read_bytes(two)) << integrator;
    }
}

TEST(Mpi, OtherCommandsRunOnRankZeroAlone) {
    // phos photons (which traces photon maps, as render does) and phos info under mpirun: rank 0
    // does the work by itself, once; the other ranks end at once.
    REQUIRE_MPI();
    TempDir dir;
    const auto r = run_mpi(2, "photons " + kScene + " --global 5000 --caustic 5000 -o " + dir.file("p.ply"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("phos: wrote"), r.output.rfind("phos: wrote")) << r.output;
    const auto one =
        run_phos("photons " + kScene + " --global 5000 --caustic 5000 -q -o " + dir.file("q.ply"));
    ASSERT_EQ(one.exit_code, 0) << one.output;
    EXPECT_EQ(read_bytes(dir.file("p.ply")), read_bytes(dir.file("q.ply")));
}

TEST(Mpi, BadInputFailsOnceWithExit2) {
    REQUIRE_MPI();
    TempDir dir;
    const std::string bad = dir.write("bad.scn", "sphere 0 0 0\n");
    const auto r = run_mpi(2, "render " + bad + " -o " + dir.file("out.png"));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("bad.scn:2:1:"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("bad.scn:2:1:"), r.output.rfind("bad.scn:2:1:")) << "printed by every rank:\n"
                                                                             << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out.png")));
}

// The pid of the phos process of rank `rank` whose command line holds `marker`, or -1.
pid_t rank_pid(int rank, const std::string& marker) {
    for (const auto& e : std::filesystem::directory_iterator("/proc")) {
        const std::string name = e.path().filename().string();
        if (name.find_first_not_of("0123456789") != std::string::npos) continue;
        std::ifstream cmdline(e.path() / "cmdline", std::ios::binary),
            environ(e.path() / "environ", std::ios::binary);
        const std::string cmd((std::istreambuf_iterator<char>(cmdline)), std::istreambuf_iterator<char>());
        const std::string env((std::istreambuf_iterator<char>(environ)), std::istreambuf_iterator<char>());
        if (cmd.find(marker) == std::string::npos || cmd.rfind(PHOS_BINARY, 0) != 0) continue;
        if (env.find(std::string("OMPI_COMM_WORLD_RANK=") + std::to_string(rank) + '\0') != std::string::npos)
            return pid_t(std::stol(name));
    }
    return -1;
}

// Starts `mpirun -np 2 phos ARGS` in the background (output to `log`), waits until rank `rank`
// runs, and returns its pid (-1 after 30 s).
pid_t start_job(const std::string& args, const std::string& log, int rank, const std::string& marker) {
    const std::string cmd = "(mpirun --allow-run-as-root --oversubscribe -np 2 " + std::string(PHOS_BINARY) +
                            " " + args + " >" + log + " 2>&1; echo \"job-exit $?\" >>" + log + ") &";
    std::system(cmd.c_str());
    for (int i = 0; i < 300; ++i) {
        if (const pid_t p = rank_pid(rank, marker); p > 0) return p;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return -1;
}

// Ends a background job left running by a failed test (its command line holds `marker`).
struct KillJob {
    std::string marker;
    ~KillJob() { std::system(("pkill -KILL -f '^mpirun.*" + marker + "' 2>/dev/null").c_str()); }
};

// Waits (up to `seconds`) for the job's "exit N" line in `log`; returns the text.
std::string wait_exit(const std::string& log, double seconds, double& waited) {
    const auto t0 = std::chrono::steady_clock::now();
    for (;;) {
        const std::string text = read_bytes(log);
        waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (text.find("job-exit ") != std::string::npos || waited > seconds) return text;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
}

TEST(Mpi, AKilledRankEndsTheJobWithinSecondsAndOverwritesNothing) {
    REQUIRE_MPI();
    TempDir dir;
    const std::string out = dir.file("killed.pfm");
    std::ofstream(out) << "previous";
    const std::string args =
        "render " + kScene + kSmall + "--integrator path --spp 1000000 --threads 1 -o " + out;
    const KillJob cleanup{out};
    const pid_t victim = start_job(args, dir.file("log"), 1, "killed.pfm");
    ASSERT_GT(victim, 0) << read_bytes(dir.file("log"));
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // rendering
    ASSERT_EQ(::kill(victim, SIGKILL), 0);
    double waited = 0;
    const std::string log = wait_exit(dir.file("log"), 30, waited);
    std::printf("the job ended %.1f s after rank 1 was killed\n", waited);
    EXPECT_LT(waited, 10) << log;
    EXPECT_NE(log.find("job-exit "), std::string::npos) << log;
    EXPECT_EQ(log.find("job-exit 0"), std::string::npos) << log;
    EXPECT_NE(log.find("rank 1"), std::string::npos) << "mpirun names the dead rank:\n" << log;
    // So does rank 0 (rank 1 ran on its machine), instead of promising the image so far.
    EXPECT_NE(log.find("phos: rank 1 has stopped running"), std::string::npos) << log;
    EXPECT_EQ(log.find("writing the image so far"), std::string::npos) << log;
    EXPECT_EQ(read_bytes(out), "previous") << "the output was overwritten";
}

TEST(Mpi, InterruptingTheJobWritesTheImageSoFar) {
    REQUIRE_MPI();
    TempDir dir;
    const std::string out = dir.file("stopped.pfm");
    const std::string args =
        "render " + kScene + kSmall + "--integrator path --spp 1000000 --threads 1 -o " + out;
    const KillJob cleanup{out};
    const pid_t rank0 = start_job(args, dir.file("log"), 0, "stopped.pfm");
    ASSERT_GT(rank0, 0) << read_bytes(dir.file("log"));
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    // Ctrl-C on mpirun: it passes the signal on to the ranks as SIGTERM.
    ASSERT_EQ(std::system(("pkill -INT -f '^mpirun.*" + out + "'").c_str()), 0);
    double waited = 0;
    const std::string log = wait_exit(dir.file("log"), 30, waited);
    EXPECT_NE(log.find("warning: interrupted: the image holds the work done so far"), std::string::npos)
        << log;
    EXPECT_NE(log.find("phos: wrote " + out), std::string::npos) << log;
    EXPECT_EQ(log.find("phos: wrote " + out), log.rfind("phos: wrote ")) << "written more than once:\n"
                                                                         << log;
    ASSERT_TRUE(std::filesystem::exists(out));
    EXPECT_GT(std::filesystem::file_size(out), 48u * 36u * 12u);
}

}  // namespace
}  // namespace phos::testing
