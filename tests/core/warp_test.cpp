// Tests of the sampling warps (core/warp.h): samples stay in their domain, each pdf integrates to 1,
// and chi-square tests that sample histograms match the pdfs.
#include "core/warp.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <functional>

#include "core/rng.h"
#include "support/chi_square.h"

namespace phos {
namespace {

constexpr int kSamples = 200000;

// Direction warps: (sampler, pdf, support half-angle). The histogram covers the support.
struct DirectionWarp {
    std::string name;
    std::function<Vec3(Vec2)> sample;
    std::function<double(Vec3)> pdf;
    double theta_max;
};

std::vector<DirectionWarp> direction_warps() {
    std::vector<DirectionWarp> w;
    w.push_back({"cosine_hemisphere", [](Vec2 u) { return warp::cosine_hemisphere(u); },
                 [](Vec3 v) { return double(warp::cosine_hemisphere_pdf(v.z)); }, M_PI / 2});
    w.push_back({"uniform_sphere", [](Vec2 u) { return warp::uniform_sphere(u); },
                 [](Vec3) { return double(warp::uniform_sphere_pdf()); }, M_PI});
    for (float cmax : {0.9f, 0.2f}) {  // truncated_power_cosine with n = 0: uniform over the cone
        w.push_back({"truncated_power_cosine(0," + std::to_string(cmax) + ")",
                     [cmax](Vec2 u) { return warp::truncated_power_cosine(u, 0.0f, cmax); },
                     [cmax](Vec3 v) { return v.z >= cmax ? double(warp::uniform_cone_pdf(cmax)) : 0.0; },
                     std::acos(double(cmax))});
    }
    for (float n : {1.0f, 10.0f, 100.0f}) {
        // The histogram covers the cone holding all but ~1e-6 of the lobe (cos^(n+1) = 1e-6).
        const double tmax = n > 50 ? std::acos(std::pow(1e-6, 1.0 / (n + 1))) : M_PI / 2;
        w.push_back({"power_cosine(" + std::to_string(n) + ")",
                     [n](Vec2 u) { return warp::power_cosine(u, n); },
                     [n](Vec3 v) { return double(warp::power_cosine_pdf(v.z, n)); }, tmax});
    }
    for (auto [n, cmax] : {std::pair{5.0f, 0.7f}, std::pair{30.0f, 0.95f}, std::pair{2.0f, -0.3f}}) {
        w.push_back({"truncated_power_cosine(" + std::to_string(n) + "," + std::to_string(cmax) + ")",
                     [n, cmax](Vec2 u) { return warp::truncated_power_cosine(u, n, cmax); },
                     [n, cmax](Vec3 v) { return double(warp::truncated_power_cosine_pdf(v.z, n, cmax)); },
                     std::acos(std::max(0.0, double(cmax)))});
    }
    return w;
}

TEST(Warp, DirectionSamplesStayInDomain) {
    for (const auto& w : direction_warps()) {
        Sampler rng(7);
        for (int i = 0; i < 20000; ++i) {
            const Vec3 d = w.sample(rng.next2());
            ASSERT_NEAR(length(d), 1.0f, 1e-5f) << w.name;
            ASSERT_LE(std::acos(std::clamp(double(d.z), -1.0, 1.0)), w.theta_max + 1e-3) << w.name;
            ASSERT_GT(w.pdf(d), 0) << w.name << " sampled a direction of zero density";
        }
        // The corners of the unit square too.
        for (Vec2 u :
             {Vec2(0, 0), Vec2(0.99999994f, 0), Vec2(0, 0.99999994f), Vec2(0.99999994f, 0.99999994f)})
            ASSERT_TRUE(is_finite(w.sample(u))) << w.name;
    }
}

TEST(Warp, DirectionPdfsIntegrateToOne) {
    for (const auto& w : direction_warps()) {
        // Over the whole sphere: pdfs must vanish outside their support and integrate to 1.
        const double all = test::integrate_sphere(w.pdf, M_PI, 4096, 16);
        // Over the support only (the support edge is a grid line: no discontinuity inside).
        const double support = test::integrate_sphere(w.pdf, w.theta_max, 1024, 16);
        EXPECT_NEAR(all, 1.0, 2e-3) << w.name;
        if (w.theta_max < M_PI / 2 + 1e-9 && w.name.find("power_cosine(100") == std::string::npos) {
            EXPECT_NEAR(support, 1.0, 1e-4) << w.name;
        }
    }
}

TEST(Warp, DirectionHistogramsMatchPdf) {
    for (const auto& w : direction_warps()) {
        test::DirectionHistogram h(24, 48, w.theta_max);
        Sampler rng(11);
        for (int i = 0; i < kSamples; ++i) h.add(w.sample(rng.next2()));
        h.total = kSamples;
        const auto r = test::chi_square(h.counts, h.expected(w.pdf));
        EXPECT_TRUE(r.passed) << w.name << ": " << r.detail;
        if (getenv("PHOS_TEST_VERBOSE")) printf("%s: %s\n", w.name.c_str(), r.detail.c_str());
    }
}

// A wrong pdf must be caught: the test is only honest if it can fail.
TEST(Warp, ChiSquareRejectsWrongPdf) {
    test::DirectionHistogram h(24, 48, M_PI / 2);
    Sampler rng(11);
    for (int i = 0; i < kSamples; ++i) h.add(warp::power_cosine(rng.next2(), 1.0f));
    h.total = kSamples;
    const auto wrong = [](Vec3 v) { return double(warp::power_cosine_pdf(v.z, 1.1f)); };
    EXPECT_FALSE(test::chi_square(h.counts, h.expected(wrong)).passed);
}

TEST(Warp, ConcentricDiskUniform) {
    // In polar coordinates (r^2, phi) a uniform disk density is uniform, so each of the
    // nr x nphi cells expects exactly N / (nr nphi) samples.
    constexpr int nr = 20, nphi = 40;
    std::vector<double> obs(nr * nphi, 0.0), exp(nr * nphi, double(kSamples) / (nr * nphi));
    Sampler rng(3);
    for (int i = 0; i < kSamples; ++i) {
        const Vec2 d = warp::concentric_disk(rng.next2());
        const double r2 = double(d.x) * d.x + double(d.y) * d.y;
        ASSERT_LE(r2, 1.0 + 1e-6);
        double phi = std::atan2(d.y, d.x);
        if (phi < 0) phi += 2 * M_PI;
        const int ir = std::min(nr - 1, int(r2 * nr)), ip = std::min(nphi - 1, int(phi / (2 * M_PI) * nphi));
        obs[size_t(ir * nphi + ip)] += 1;
    }
    const auto r = test::chi_square(obs, exp);
    EXPECT_TRUE(r.passed) << r.detail;
    // pdf = 1/pi integrates to 1 over the disk of area pi.
    EXPECT_NEAR(warp::concentric_disk_pdf() * kPi, 1.0f, 1e-6f);
    EXPECT_EQ(warp::concentric_disk(Vec2(0.5f, 0.5f)), Vec2(0, 0));
}

TEST(Warp, UniformTriangle) {
    // Barycentrics (b0, b1) uniform on the triangle b0, b1 >= 0, b0 + b1 <= 1 (area 1/2, so the
    // density is 2). On an n x n grid, cells below the diagonal hold h^2 of area, cells it crosses
    // through their corners h^2/2, cells above it none: expected counts are exact.
    constexpr int n = 30;
    const double h = 1.0 / n;
    std::vector<double> obs(n * n, 0.0), exp(n * n, 0.0);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double area = i + j < n - 1 ? h * h : (i + j == n - 1 ? h * h / 2 : 0);
            exp[size_t(i * n + j)] = 2 * area * kSamples;
        }
    Sampler rng(5);
    for (int k = 0; k < kSamples; ++k) {
        const Vec2 b = warp::uniform_triangle(rng.next2());
        ASSERT_GE(b.x, 0);
        ASSERT_GE(b.y, 0);
        ASSERT_LE(b.x + b.y, 1 + 1e-6f);
        const int i = std::min(n - 1, int(b.x * n)), j = std::min(n - 1, int(b.y * n));
        obs[size_t(i * n + j)] += 1;
    }
    const auto r = test::chi_square(obs, exp);
    EXPECT_TRUE(r.passed) << r.detail;
}

TEST(Warp, HelpersAgreeWithDefinitions) {
    EXPECT_FLOAT_EQ(warp::power_heuristic(1.0f, 1.0f), 0.5f);
    EXPECT_FLOAT_EQ(warp::power_heuristic(3.0f, 1.0f), 0.9f);
    EXPECT_EQ(warp::power_heuristic(0.0f, 0.0f), 0.0f);
    // The truncated lobe with the cone opened to the hemisphere is the plain power cosine.
    EXPECT_NEAR(warp::truncated_power_cosine_pdf(0.6f, 7.0f, 0.0f), warp::power_cosine_pdf(0.6f, 7.0f),
                1e-6f);
    EXPECT_EQ(warp::truncated_power_cosine_pdf(0.5f, 7.0f, 0.6f), 0.0f);
}

}  // namespace
}  // namespace phos
