// Tests of the piecewise-bilinear warp behind the measured BRDF (scene/piecewise_linear_2d.h,
// Dupuy & Jakob 2018 sec. 5): sample() and invert() are inverses, their densities equal eval(),
// eval() interpolates bilinearly (raw tables) and across parameter slices linearly, the sampled
// points follow the density (chi-square on a grid), and a slice of tiny values (the fuzzer's
// finding: 1 / its integral overflowed a float) still samples finite points and densities.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "scene/piecewise_linear_2d.h"
#include "support/chi_square.h"

namespace phos::scene {
namespace {

// Two slices (a parameter axis {0, 2}) of a 4 x 3 grid.
const std::vector<float> kValues = {1, 2, 3, 4, 0.5f, 1, 0, 2, 3, 1, 1, 1,  //
                                    2, 2, 2, 2, 0,    5, 1, 1, 1, 1, 4, 0.1f};

TEST(MeasuredWarp, SampleAndInvertAreInversesWithTheEvalDensity) {
    const PiecewiseLinear2D w(kValues.data(), 4, 3, {{0.0f, 2.0f}}, true);
    Sampler rng(1);
    for (float param : {0.0f, 0.5f, 2.0f}) {
        for (int i = 0; i < 2000; ++i) {
            const Vec2 u = rng.next2();
            const auto s = w.sample(u, &param);
            ASSERT_GE(s.p.x, 0.0f);
            ASSERT_LE(s.p.x, 1.0f);
            ASSERT_GE(s.p.y, 0.0f);
            ASSERT_LE(s.p.y, 1.0f);
            EXPECT_NEAR(s.pdf, w.eval(s.p, &param), 1e-4f * (1 + s.pdf));
            const auto back = w.invert(s.p, &param);
            EXPECT_NEAR(back.p.x, u.x, 2e-4f);
            EXPECT_NEAR(back.p.y, u.y, 2e-4f);
            EXPECT_NEAR(back.pdf, s.pdf, 1e-4f * (1 + s.pdf));
        }
    }
}

TEST(MeasuredWarp, EvalInterpolatesValuesAndSlices) {
    const PiecewiseLinear2D raw(kValues.data(), 4, 3, {{0.0f, 2.0f}}, false);
    const float p0 = 0, p1 = 2, mid = 0.5f;
    // Grid points: the values; between them bilinear; between slices linear in the parameter.
    EXPECT_FLOAT_EQ(raw.eval(Vec2(1.0f / 3, 0.5f), &p0), 1.0f);
    EXPECT_FLOAT_EQ(raw.eval(Vec2(1.0f / 3, 0.5f), &p1), 5.0f);
    EXPECT_FLOAT_EQ(raw.eval(Vec2(0.5f, 0.25f), &p0), 0.25f * (2 + 3 + 1 + 0));
    EXPECT_FLOAT_EQ(raw.eval(Vec2(1.0f / 3, 0.5f), &mid), 0.75f * 1 + 0.25f * 5);
    // Sampling tables integrate to 1 over the square (trapezoidal rule of the bilinear function).
    const PiecewiseLinear2D w(kValues.data(), 4, 3, {{0.0f, 2.0f}}, true);
    double sum = 0;
    const int n = 600;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) sum += w.eval(Vec2((a + 0.5f) / n, (b + 0.5f) / n), &mid);
    EXPECT_NEAR(sum / (double(n) * n), 1.0, 1e-4);
}

TEST(MeasuredWarp, SamplesFollowTheDensity) {
    const PiecewiseLinear2D w(kValues.data(), 4, 3, {{0.0f, 2.0f}}, true);
    const float param = 1.3f;
    const int bins = 24, n = 100000;
    std::vector<double> observed(size_t(bins * bins), 0), expected(size_t(bins * bins), 0);
    Sampler rng(2);
    for (int i = 0; i < n; ++i) {
        const Vec2 p = w.sample(rng.next2(), &param).p;
        observed[size_t(std::min(bins - 1, int(p.y * bins)) * bins + std::min(bins - 1, int(p.x * bins)))] +=
            1;
    }
    const int q = 8;  // quadrature points per bin and axis
    for (int by = 0; by < bins; ++by)
        for (int bx = 0; bx < bins; ++bx) {
            double s = 0;
            for (int a = 0; a < q; ++a)
                for (int b = 0; b < q; ++b)
                    s += w.eval(Vec2((bx + (a + 0.5f) / q) / bins, (by + (b + 0.5f) / q) / bins), &param);
            expected[size_t(by * bins + bx)] = n * s / (q * q) / (bins * bins);
        }
    const auto r = test::chi_square(observed, expected);
    EXPECT_TRUE(r.passed) << r.detail;
}

TEST(MeasuredWarp, TinyValuesStillSampleFinitely) {
    std::vector<float> tiny(9, 1e-44f);
    const PiecewiseLinear2D w(tiny.data(), 3, 3, {}, true);
    for (float a : {0.0f, 0.3f, 0.999f}) {
        const auto s = w.sample(Vec2(a, 0.61f));
        EXPECT_TRUE(std::isfinite(s.pdf));
        EXPECT_NEAR(s.pdf, 1.0f, 1e-3f);
        EXPECT_GE(s.p.x, 0.0f);
        EXPECT_LE(s.p.x, 1.0f);
    }
}

}  // namespace
}  // namespace phos::scene
