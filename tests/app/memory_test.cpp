// End-to-end tests of phos render's memory check: the estimate against the peak the render then
// measures (within 25 %) for renders that each make one item dominate, and the refusals (exit 2,
// a message, no output) of a render that needs more than --max-memory or the memory available; and
// the photon tracer's -v figures printed beside the memory (pages faulted in, threads busy).
#include "core/memory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>

#include "support/mesh_writers.h"
#include "test_util.h"

namespace phos::testing {
namespace {

const std::string kCornell = std::string(PHOS_SOURCE_DIR) + "/scenes/cornell-diffuse.scn";

// The bytes of a -v statistics line "NAME: 61.2 MB ...".
double stat_bytes(const std::string& output, const std::string& name) {
    const std::regex re(name + ": ([0-9.]+) (bytes|kB|MB|GB|TB)");
    std::smatch m;
    if (!std::regex_search(output, m, re)) return -1;
    const std::string unit = m[2];
    const double scale = unit == "kB"   ? 1e3
                         : unit == "MB" ? 1e6
                         : unit == "GB" ? 1e9
                         : unit == "TB" ? 1e12
                                        : 1;
    return std::stod(m[1]) * scale;
}

// Renders with -v and checks the estimate against the measured peak (VmHWM); returns the output.
std::string expect_estimate_near_peak(const std::string& args, const std::string& dominant) {
    TempDir dir;
    const auto r = run_phos("render " + args + " -q -v -o " + dir.file("out.exr"));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const double estimate = stat_bytes(r.output, "memory estimate");
    const double peak = stat_bytes(r.output, "peak memory");
    EXPECT_GT(estimate, 0) << r.output;
    EXPECT_GT(peak, 0) << r.output;
    EXPECT_NEAR(estimate / peak, 1.0, 0.25) << args << "\n" << r.output;
    // The breakdown lists the largest item first.
    EXPECT_NE(r.output.find(": " + dominant + " "), std::string::npos) << r.output;
    return r.output;
}

TEST(Memory, PhotonMapEstimateMatchesPeak) {
    // 3 M global photons: ~250 MB, the photon maps at the k-d tree build.
    const std::string out = expect_estimate_near_peak(
        kCornell + " --resolution 16 16 --spp 1 --global 3000000 --no-irradiance-cache", "photon maps");
    EXPECT_NE(out.find("photon map build"), std::string::npos) << out;
    // The global map's array, reserved at its budget (plus one path's photons) and faulted in
    // before tracing: 24 bytes per photon.
    EXPECT_NEAR(stat_bytes(out, "photon map pages faulted in"), 3000018.0 * 24, 0.01e6) << out;
    // And how busy the tracing threads were: a share of their time, with the sums it comes from.
    std::smatch busy;
    ASSERT_TRUE(std::regex_search(
        out, busy,
        std::regex("photon tracing threads busy: ([0-9.]+) % \\(batches ([0-9.]+) s on [0-9]+ threads? in "
                   "([0-9.]+) s; commits ([0-9.]+) s, serial\\)")))
        << out;
    EXPECT_GT(std::stod(busy[1]), 0.0) << out;
    EXPECT_LE(std::stod(busy[1]), 100.0) << out;
    EXPECT_GT(std::stod(busy[2]), 0.0) << out;
}

TEST(Memory, SppmEstimateMatchesPeak) {
    // A 1000 x 1000 image: ~590 MB of visible points, statistics and the hit-point grid.
    expect_estimate_near_peak(
        kCornell + " --integrator sppm --resolution 1000 1000 --spp 1 --photons-per-iter 10000",
        "visible points");
}

TEST(Memory, MeshEstimateMatchesPeak) {
    // A 1 M triangle sheet: the Embree BVH build dominates.
    TempDir dir;
    scene::TriangleMesh mesh;
    const int n = 708;  // vertices per side: 2 x 707^2 = 1.0 M triangles
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float x = float(i) / float(n - 1) - 0.5f, z = float(j) / float(n - 1) - 0.5f;
            mesh.positions.push_back({x, 0.3f + 0.05f * std::sin(20 * x) * std::cos(20 * z), z});
        }
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const uint32_t a = uint32_t(j * n + i), b = a + 1, c = a + uint32_t(n), d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
        }
    write_ply(dir.file("sheet.ply"), mesh, true);
    const std::string scene = dir.write("mesh.pbrt", R"(
Film "rgb" "integer xresolution" [ 64 ] "integer yresolution" [ 64 ]
LookAt 0 1.5 1.5  0 0.3 0  0 1 0
Camera "perspective" "float fov" [ 45 ]
WorldBegin
LightSource "point" "point3 from" [ 0 2 0 ] "rgb I" [ 5 5 5 ]
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "plymesh" "string filename" "sheet.ply"
)");
    const std::string out = expect_estimate_near_peak(scene + " --integrator path --spp 1", "accelerator");
    EXPECT_NE(out.find("BVH build"), std::string::npos) << out;
}

TEST(Memory, MaxMemoryRefusesBeforeAnyWork) {
    TempDir dir;
    const std::string out = dir.file("out.png");
    const auto r = run_phos("render " + kCornell + " --resolution 16 16 --spp 1 --max-memory 0.01 -o " + out);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("phos: this render needs about"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("--max-memory allows only 10.0 MB"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out));
    // A limit above the estimate lets it run.
    EXPECT_EQ(run_phos("render " + kCornell +
                       " --integrator path --resolution 16 16 --spp 1 --max-memory 1 -q -o " + out)
                  .exit_code,
              0);
    EXPECT_TRUE(std::filesystem::exists(out));
}

TEST(Memory, HugePhotonBudgetRefusedWithTheAvailableMemory) {
    // 1.5 G global photons need ~86 GB (30 GB for the map alone, more to build its tree).
    const memory::Available a = memory::available();
    if (!a.bytes) GTEST_SKIP() << "the available memory is unknown here";
    if (*a.bytes > uint64_t(80e9)) GTEST_SKIP() << "this machine has enough memory for it";
    TempDir dir;
    const std::string out = dir.file("out.png");
    const auto r = run_phos("render " + kCornell + " --global 1500000000 -o " + out);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_TRUE(
        std::regex_search(r.output, std::regex("this render needs about [0-9.]+ GB \\(photon maps [0-9.]+ "
                                               "GB.*\\) but only [0-9.]+ [GM]B are available")))
        << r.output;
    EXPECT_NE(r.output.find("--max-memory"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace phos::testing
