// Filter importance sampling against the filters' integrals: for every pbrt-v4 filter, the sample
// weights have mean 1 and the weighted samples reproduce ∫ f g / ∫ f for test functions g (computed
// here by quadrature of the filter's own formula); splat weights integrate to 1; the default box
// leaves the sample position and weight exactly as given.
#include "render/pixel_filter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/low_discrepancy.h"

namespace phos::render {
namespace {

using Kind = scene::PixelFilter::Kind;

scene::PixelFilter make(Kind kind) {
    scene::PixelFilter f;
    f.kind = kind;
    f.radius = scene::PixelFilter::default_radius(kind);
    return f;
}

// ∫∫ f g over the support by the midpoint rule on a fine grid.
double quadrature(const PixelFilterSampler& s, const std::function<double(double, double)>& g) {
    const Vec2 r = s.radius();
    const int n = 800;
    const double hx = 2.0 * r.x / n, hy = 2.0 * r.y / n;
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double x = -r.x + (i + 0.5) * hx, y = -r.y + (j + 0.5) * hy;
            sum += double(s.evaluate(Vec2(float(x), float(y)))) * g(x, y);
        }
    return sum * hx * hy;
}

// The mean of weight × g(offset from the pixel centre) over 2^16 (0,2)-sequence samples.
double estimate(const PixelFilterSampler& s, const std::function<double(double, double)>& g) {
    const uint32_t n = 1u << 16;
    double sum = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const PixelFilterSampler::FilmSample fs = s.sample(sobol02_point(i, 0x1234567u));
        sum += double(fs.weight) * g(double(fs.position.x) - 0.5, double(fs.position.y) - 0.5);
    }
    return sum / n;
}

class EveryFilter : public ::testing::TestWithParam<Kind> {};

TEST_P(EveryFilter, WeightsHaveMeanOneAndReproduceTheFilteredIntegral) {
    const PixelFilterSampler s(make(GetParam()));
    const double integral = quadrature(s, [](double, double) { return 1.0; });
    EXPECT_NEAR(s.integral(), integral, 1e-3 * integral);
    EXPECT_NEAR(estimate(s, [](double, double) { return 1.0; }), 1.0, 2e-3);
    // Smooth test functions, one odd in x, one even, one mixed.
    const std::function<double(double, double)> tests[] = {
        [](double x, double y) { return 1 + 0.4 * x + 0.1 * y; },
        [](double x, double y) { return x * x + 0.5 * y * y; },
        [](double x, double y) { return std::cos(1.3 * x) * std::exp(0.2 * y); },
    };
    for (const auto& g : tests) {
        const double expected = quadrature(s, g) / integral;
        EXPECT_NEAR(estimate(s, g), expected, 3e-3 * std::max(1.0, std::fabs(expected)));
    }
}

TEST_P(EveryFilter, SamplesStayInsideTheRadiusAndSplatWeightsIntegrateToOne) {
    const PixelFilterSampler s(make(GetParam()));
    const Vec2 r = s.radius();
    for (uint32_t i = 0; i < 4096; ++i) {
        const PixelFilterSampler::FilmSample fs = s.sample(sobol02_point(i, 99));
        EXPECT_LE(std::fabs(fs.position.x - 0.5f), r.x + 1e-5f);
        EXPECT_LE(std::fabs(fs.position.y - 0.5f), r.y + 1e-5f);
    }
    // A light path's splat weighs f(p - c) / ∫ f at each pixel centre c around it: as a function of
    // the offset it integrates to 1 (so each pixel's mean over splats is its filtered value).
    const int n = 400;
    const double hx = 2.0 * r.x / n, hy = 2.0 * r.y / n;
    double integral = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            integral +=
                s.splat_weight(Vec2(float(-r.x + (i + 0.5) * hx), float(-r.y + (j + 0.5) * hy))) * hx * hy;
    EXPECT_NEAR(integral, 1.0, 2e-3);
}

INSTANTIATE_TEST_SUITE_P(PixelFilter, EveryFilter,
                         ::testing::Values(Kind::Box, Kind::Gaussian, Kind::Mitchell, Kind::Lanczos,
                                           Kind::Triangle));

TEST(PixelFilter, TheDefaultBoxKeepsTheSampleAsGiven) {
    const PixelFilterSampler s;
    EXPECT_TRUE(s.is_pixel_box());
    for (const Vec2 u : {Vec2(0.0f, 0.0f), Vec2(0.3f, 0.9999f), Vec2(0.123456f, 0.5f)}) {
        const PixelFilterSampler::FilmSample fs = s.sample(u);
        EXPECT_EQ(fs.position.x, u.x);
        EXPECT_EQ(fs.position.y, u.y);
        EXPECT_EQ(fs.weight, 1.0f);
    }
}

TEST(PixelFilter, MitchellAndLanczosHaveNegativeLobesAndNegativeWeights) {
    for (const Kind k : {Kind::Mitchell, Kind::Lanczos}) {
        const PixelFilterSampler s(make(k));
        int negative = 0;
        for (uint32_t i = 0; i < 4096; ++i) negative += s.sample(sobol02_point(i, 7)).weight < 0;
        EXPECT_GT(negative, 0);
        EXPECT_LT(s.evaluate(Vec2(1.5f, 0.0f)), 0.0f);  // Mitchell's lobe at 1.5 of radius 2; sinc's at 1.5
    }
}

TEST(PixelFilter, PositiveFiltersWeighAlmostOne) {
    // The tables bound |f| per cell finely enough that a positive filter's weights stay near 1 (no
    // extra variance): below 1 only in the cells where f falls to 0; the triangle's inverse CDF is
    // exact.
    for (const Kind k : {Kind::Gaussian, Kind::Triangle}) {
        const PixelFilterSampler s(make(k));
        double deviation = 0;
        float most = 0;
        const uint32_t n = 4096;
        for (uint32_t i = 0; i < n; ++i) {
            const float w = s.sample(sobol02_point(i, 3)).weight;
            deviation += std::fabs(double(w) - 1);
            most = std::max(most, w);
        }
        EXPECT_LT(deviation / n, k == Kind::Triangle ? 1e-6 : 0.01);
        EXPECT_LT(most, 1.01f);
    }
}

TEST(PixelFilter, BadParametersAreRefused) {
    scene::PixelFilter f = make(Kind::Gaussian);
    f.sigma = 0;
    EXPECT_ANY_THROW(PixelFilterSampler{f});
    f = make(Kind::Box);
    f.radius = {0.0f, 1.0f};
    EXPECT_ANY_THROW(PixelFilterSampler{f});
}

}  // namespace
}  // namespace phos::render
