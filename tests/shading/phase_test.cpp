// The Henyey-Greenstein phase function (shading/phase.h): normalisation over the sphere, the
// direction convention (wo points back along the incoming path; g > 0 scatters forwards, towards
// -wo), exact importance sampling (chi-square over (cos theta, phi) bins, pdf = eval) and the mean
// cosine g. The expected bin probabilities come from the closed-form HG cdf in double precision and
// the reference frame around -wo is built here, independently of the implementation's Frame.
#include "shading/phase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "support/chi_square.h"

namespace phos::shading {
namespace {

// Closed-form HG in double: p(mu) = (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^(3/2)).
double hg(double mu, double g) { return (1 - g * g) / (4 * M_PI * std::pow(1 + g * g - 2 * g * mu, 1.5)); }

// P(cos theta <= mu) for HG (theta measured from the forward direction -wo):
// (1 - g^2) / (2 g) * (1 / sqrt(1 + g^2 - 2 g mu) - 1 / (1 + g)), or (mu + 1) / 2 for g = 0.
double hg_cdf(double mu, double g) {
    if (g == 0) return 0.5 * (mu + 1);
    return (1 - g * g) / (2 * g) * (1 / std::sqrt(1 + g * g - 2 * g * mu) - 1 / (1 + g));
}

// mu with hg_cdf(mu) = p, by bisection (independent of the sampler's own inversion).
double hg_cdf_inverse(double p, double g) {
    double lo = -1, hi = 1;
    for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (hg_cdf(mid, g) < p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// An orthonormal basis (b1, b2, n) around unit n, by Gram-Schmidt against a fixed axis.
void basis(Vec3 n, Vec3& b1, Vec3& b2) {
    const Vec3 a = std::fabs(n.x) < 0.6f ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    b1 = normalize(a - n * dot(a, n));
    b2 = cross(n, b1);
}

const Vec3 kWo = normalize(Vec3(0.3f, -0.5f, 0.8f));  // a direction off every axis

TEST(Phase, MatchesTheClosedForm) {
    for (float g : {-0.7f, 0.0f, 0.3f, 0.9f})
        for (float mu : {-1.0f, -0.5f, 0.0f, 0.4f, 0.95f, 1.0f})
            EXPECT_NEAR(henyey_greenstein(mu, g), hg(mu, g), 1e-5 * hg(mu, g))
                << "g = " << g << ", mu = " << mu;
}

TEST(Phase, ForwardScatteringIsTowardsMinusWo) {
    // wo points back along the incoming path, so "straight on" is wi = -wo.
    const PhaseFunction forward{0.6f}, backward{-0.6f};
    EXPECT_GT(forward.eval(kWo, -kWo), forward.eval(kWo, kWo));
    EXPECT_LT(backward.eval(kWo, -kWo), backward.eval(kWo, kWo));
    EXPECT_NEAR(forward.eval(kWo, -kWo), hg(1.0, 0.6), 1e-4 * hg(1.0, 0.6));
    EXPECT_NEAR(forward.eval(kWo, kWo), hg(-1.0, 0.6), 1e-4 * hg(-1.0, 0.6));
    // Reciprocity: swapping (and reversing) the directions leaves the value unchanged.
    const Vec3 wi = normalize(Vec3(-0.2f, 0.9f, 0.1f));
    EXPECT_FLOAT_EQ(forward.eval(kWo, wi), forward.eval(-wi, -kWo));
}

TEST(Phase, IntegratesToOneOverTheSphere) {
    for (float g : {-0.9f, -0.5f, 0.0f, 0.3f, 0.7f, 0.9f}) {
        const PhaseFunction phase{g};
        // 2D quadrature of eval(wo, w) over the whole sphere around +z while the lobe points along
        // -wo (off-axis), so the test sees the convention and the frame, not only the 1D profile.
        // Simpson with 2048 x 1024 nodes resolves the g = 0.9 peak (width ~ 1 - g = 0.1 rad) to
        // well under 1e-4 (a 1024 x 512 grid already agrees to 1e-5).
        const double integral =
            test::integrate_sphere([&](Vec3 w) { return phase.eval(kWo, w); }, M_PI, 2048, 1024);
        EXPECT_NEAR(integral, 1.0, 1e-4) << "g = " << g;
        // And the 1D profile in cos theta (midpoint rule, 1e5 cells: error ~ 1e-7 even at 0.9).
        const int n = 100000;
        double sum = 0;
        for (int i = 0; i < n; ++i) sum += henyey_greenstein(float(-1 + 2 * (i + 0.5) / n), g) * (2.0 / n);
        EXPECT_NEAR(sum * 2 * M_PI, 1.0, 1e-4) << "g = " << g;
    }
}

TEST(Phase, SamplingMatchesThePdfInCosThetaAndPhi) {
    Vec3 b1, b2;
    basis(-kWo, b1, b2);
    for (float g : {-0.7f, 0.0f, 0.3f, 0.9f}) {
        const PhaseFunction phase{g};
        Sampler s(17, uint64_t(int64_t(g * 1000) + 5000));
        // 16 cos-theta bins of equal HG probability (edges from the closed-form cdf) x 16 phi bins:
        // every bin expects n / 256 ~ 780 samples.
        const int n_mu = 16, n_phi = 16, n = 200000;
        std::vector<double> edges(n_mu + 1);
        for (int i = 0; i <= n_mu; ++i)
            edges[size_t(i)] = i == 0 ? -1.0 : i == n_mu ? 1.0 : hg_cdf_inverse(double(i) / n_mu, g);
        std::vector<double> observed(size_t(n_mu * n_phi), 0.0), expected(observed.size(), 0.0);
        for (int i = 0; i < n_mu; ++i)
            for (int j = 0; j < n_phi; ++j)
                expected[size_t(i * n_phi + j)] =
                    n * (hg_cdf(edges[size_t(i) + 1], g) - hg_cdf(edges[size_t(i)], g)) / n_phi;
        double sum_cos = 0, sum_cos2 = 0, worst_pdf = 0;
        for (int k = 0; k < n; ++k) {
            Vec3 wi;
            const float pdf = phase.sample(kWo, s.next2(), wi);
            ASSERT_NEAR(length(wi), 1.0f, 1e-4f);
            ASSERT_GT(pdf, 0.0f);
            // The returned pdf is the value for the pair (float rounding of the cosine only).
            worst_pdf = std::max(worst_pdf, std::fabs(double(pdf) / phase.eval(kWo, wi) - 1));
            const double mu = std::clamp(double(dot(-kWo, wi)), -1.0, 1.0);
            double phi = std::atan2(double(dot(wi, b2)), double(dot(wi, b1)));
            if (phi < 0) phi += 2 * M_PI;
            sum_cos += mu;
            sum_cos2 += mu * mu;
            const int i = int(std::upper_bound(edges.begin() + 1, edges.end() - 1, mu) - edges.begin()) - 1;
            const int j = std::min(n_phi - 1, int(phi / (2 * M_PI) * n_phi));
            observed[size_t(i * n_phi + j)] += 1;
        }
        EXPECT_LT(worst_pdf, 1e-3) << "sample() returns eval(wo, wi), g = " << g;
        // Significance 1e-4 per g (4 values): a correct sampler fails with probability < 4e-4.
        const test::ChiSquareResult chi = test::chi_square(observed, expected, 1e-4);
        EXPECT_TRUE(chi.passed) << "g = " << g << ": " << chi.detail;
        // The mean cosine of HG is g; 5 standard errors of the sample mean.
        const double mean = sum_cos / n, se = std::sqrt((sum_cos2 / n - mean * mean) / n);
        EXPECT_NEAR(mean, g, 5 * se) << "g = " << g;
    }
}

TEST(Phase, SamplingIsFiniteAtTheEndsOfTheUnitSquare) {
    for (float g : {-0.99f, -0.7f, -0.0005f, 0.0f, 0.0005f, 0.3f, 0.9f, 0.99f}) {
        const PhaseFunction phase{g};
        for (float ux : {0.0f, 0.5f, 0.99999994f})
            for (float uy : {0.0f, 0.99999994f}) {
                Vec3 wi;
                const float pdf = phase.sample(kWo, Vec2(ux, uy), wi);
                EXPECT_TRUE(std::isfinite(pdf) && pdf > 0) << "g = " << g << " u = " << ux << "," << uy;
                EXPECT_NEAR(length(wi), 1.0f, 1e-4f);
            }
        // u.x = 0 and u.x -> 1 are the two ends of the cdf's inversion: straight on (mu = 1) and
        // straight back (mu = -1), in whichever order the inversion takes them.
        Vec3 end0, end1;
        phase.sample(kWo, Vec2(0.0f, 0.3f), end0);
        phase.sample(kWo, Vec2(0.99999994f, 0.3f), end1);
        EXPECT_NEAR(std::fabs(dot(-kWo, end0)), 1.0f, 2e-3f) << "g = " << g;
        EXPECT_NEAR(dot(-kWo, end0) * dot(-kWo, end1), -1.0f, 4e-3f) << "g = " << g;
    }
}

}  // namespace
}  // namespace phos::shading
