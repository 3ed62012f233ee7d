// Perlin noise, fbm and turbulence (scene/perlin_noise.h) against their defining properties: zero
// at lattice points, periodic in 256, bounded, deterministic, near-zero mean; fbm and turbulence
// as their octave sums, within bounds.
#include "scene/perlin_noise.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"

namespace phos::scene {
namespace {

TEST(PerlinNoise, ZeroAtEveryLatticePoint) {
    for (float x : {-300.0f, -1.0f, 0.0f, 1.0f, 7.0f, 255.0f, 1e6f})
        for (float y : {-2.0f, 0.0f, 3.0f, 128.0f})
            for (float z : {-5.0f, 0.0f, 11.0f})
                EXPECT_EQ(perlin_noise(x, y, z), 0.0f) << x << " " << y << " " << z;
}

TEST(PerlinNoise, DeterministicPeriodicAndNonTrivial) {
    const float a = perlin_noise(0.25f, 0.5f, 0.75f);
    EXPECT_EQ(a, perlin_noise(0.25f, 0.5f, 0.75f));
    EXPECT_NE(a, 0.0f);
    // The lattice hashes through a 256-entry permutation: the noise repeats every 256 units.
    EXPECT_EQ(perlin_noise(0.25f + 256, 0.5f, 0.75f), a);
    EXPECT_EQ(perlin_noise(0.25f, 0.5f - 512, 0.75f), a);
    EXPECT_NE(perlin_noise(1.25f, 0.5f, 0.75f), a);
    // Non-finite coordinates give 0 rather than undefined integer conversions.
    EXPECT_EQ(perlin_noise(NAN, 0.5f, 0.5f), 0.0f);
    EXPECT_EQ(perlin_noise(0.5f, INFINITY, 0.5f), 0.0f);
    // Huge coordinates stay finite.
    EXPECT_TRUE(std::isfinite(perlin_noise(3e20f, -7e12f, 1e9f)));
}

TEST(PerlinNoise, ContinuousAcrossCellFaces) {
    for (float y : {0.3f, 1.7f, -4.2f}) {
        const float below = perlin_noise(2.0f - 1e-4f, y, 0.6f), above = perlin_noise(2.0f + 1e-4f, y, 0.6f);
        EXPECT_NEAR(below, above, 2e-3f);
    }
}

TEST(PerlinNoise, BoundedWithNearZeroMean) {
    Sampler rng(7);
    double sum = 0, abs_sum = 0;
    float lo = 0, hi = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        const Vec3 p(rng.next() * 64 - 32, rng.next() * 64 - 32, rng.next() * 64 - 32);
        const float v = perlin_noise(p);
        sum += v;
        abs_sum += std::fabs(v);
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    EXPECT_LE(hi, 1.1f);
    EXPECT_GE(lo, -1.1f);
    EXPECT_GT(hi, 0.5f);  // it does swing both ways
    EXPECT_LT(lo, -0.5f);
    EXPECT_NEAR(sum / n, 0.0, 0.01);
    EXPECT_GT(abs_sum / n, 0.1);
    EXPECT_LT(abs_sum / n, 0.35);
}

TEST(PerlinNoise, FbmAndTurbulenceAreTheirOctaveSums) {
    const Vec3 p(0.3f, -1.4f, 2.25f);
    const float omega = 0.6f;
    EXPECT_EQ(fbm(p, omega, 0), 0.0f);
    EXPECT_FLOAT_EQ(fbm(p, omega, 1), perlin_noise(p));
    EXPECT_FLOAT_EQ(fbm(p, omega, 3), perlin_noise(p) + omega * perlin_noise(p * 1.99f) +
                                          omega * omega * perlin_noise(p * (1.99f * 1.99f)));
    // Turbulence: |noise| per octave plus pbrt's 0.2 omega^octaves for the octave past the last.
    EXPECT_FLOAT_EQ(turbulence(p, omega, 0), 0.2f);
    EXPECT_FLOAT_EQ(
        turbulence(p, omega, 2),
        std::fabs(perlin_noise(p)) + omega * std::fabs(perlin_noise(p * 1.99f)) + 0.2f * omega * omega);
}

TEST(PerlinNoise, FbmAndTurbulenceStatisticsWithinBounds) {
    Sampler rng(11);
    const int n = 20000, octaves = 8;
    const float omega = 0.5f;
    const float weight_sum = 2 * (1 - std::pow(omega, float(octaves)));  // sum of omega^i, i < 8
    double fbm_sum = 0, turb_sum = 0;
    for (int i = 0; i < n; ++i) {
        const Vec3 p(rng.next() * 40, rng.next() * 40 - 20, rng.next() * 40);
        const float f = fbm(p, omega, octaves), t = turbulence(p, omega, octaves);
        ASSERT_LE(std::fabs(f), 1.1f * weight_sum);
        ASSERT_GE(t, 0.2f * std::pow(omega, float(octaves)));
        ASSERT_LE(t, 1.1f * weight_sum + 0.2f);
        fbm_sum += f;
        turb_sum += t;
    }
    EXPECT_NEAR(fbm_sum / n, 0.0, 0.02);
    // Each octave's mean |noise| lies in (0.1, 0.35) (BoundedWithNearZeroMean).
    EXPECT_GT(turb_sum / n, 0.1 * weight_sum);
    EXPECT_LT(turb_sum / n, 0.35 * weight_sum + 0.01);
}

}  // namespace
}  // namespace phos::scene
