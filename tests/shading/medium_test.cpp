// Participating media numerics: the Henyey-Greenstein phase function (normalisation, sampling),
// Beer-Lambert transmittance, and delta / ratio tracking against the homogeneous closed form.
#include "shading/medium.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "shading/medium_tracking.h"
#include "shading/phase.h"

namespace phos::shading {
namespace {

scene::Medium homogeneous(Rgb sigma_a, Rgb sigma_s, float g = 0) {
    scene::Medium m;
    m.sigma_a = sigma_a;
    m.sigma_s = sigma_s;
    m.g = g;
    return m;
}

TEST(Phase, HenyeyGreensteinIntegratesToOne) {
    for (float g : {-0.8f, -0.3f, 0.0f, 0.3f, 0.9f}) {
        // Midpoint rule in cos theta (the pdf is smooth; 2e5 cells give ~1e-6 accuracy even at 0.9).
        const int n = 200000;
        double sum = 0;
        for (int i = 0; i < n; ++i) sum += henyey_greenstein(-1 + 2 * (i + 0.5f) / n, g) * (2.0 / n);
        EXPECT_NEAR(sum * 2 * M_PI, 1.0, 1e-4) << "g = " << g;
    }
}

TEST(Phase, SamplingMatchesThePdfAndItsMeanCosine) {
    const Vec3 wo = normalize(Vec3(0.3f, -0.5f, 0.8f));
    for (float g : {-0.7f, 0.0f, 0.3f, 0.9f}) {
        const PhaseFunction phase{g};
        Sampler s(7, uint64_t(g * 1000 + 5000));
        const int n = 200000;
        double sum_cos = 0, sum_cos2 = 0;
        // Chi-square over 20 equal-width bins of cos theta against the exact bin probabilities.
        const int bins = 20;
        std::vector<double> count(bins, 0.0);
        for (int i = 0; i < n; ++i) {
            Vec3 wi;
            const float pdf = phase.sample(wo, s.next2(), wi);
            ASSERT_NEAR(length(wi), 1.0f, 1e-4f);
            ASSERT_NEAR(pdf, phase.eval(wo, wi), 1e-3f * pdf);
            const double c = dot(-wo, wi);
            sum_cos += c;
            sum_cos2 += c * c;
            count[size_t(std::min(bins - 1, int((c + 1) / 2 * bins)))] += 1;
        }
        const double mean = sum_cos / n, se = std::sqrt((sum_cos2 / n - mean * mean) / n);
        EXPECT_NEAR(mean, g, 5 * se) << "the mean cosine of HG is g";
        double chi2 = 0;
        for (int b = 0; b < bins; ++b) {
            double p = 0;  // exact probability of the bin by fine quadrature
            const int m = 2000;
            for (int k = 0; k < m; ++k) {
                const float c = -1 + 2 * (b + (k + 0.5f) / m) / bins;
                p += henyey_greenstein(c, g) * 2 * M_PI * (2.0 / bins / m);
            }
            const double e = p * n;
            chi2 += (count[size_t(b)] - e) * (count[size_t(b)] - e) / e;
        }
        // 19 degrees of freedom: P(chi2 > 43.8) = 0.001.
        EXPECT_LT(chi2, 43.8) << "g = " << g;
    }
}

TEST(Tracking, HomogeneousTransmittanceIsBeerLambert) {
    const Medium m(homogeneous(Rgb(0.1f, 0.2f, 0.4f), Rgb(0.5f, 0.3f, 0.1f)));
    Sampler s(1);
    for (float d : {0.0f, 0.3f, 1.0f, 4.0f}) {
        const Rgb T = transmittance(m, Vec3(0.0f), Vec3(0, 0, 1), d, s);
        EXPECT_FLOAT_EQ(T.r, std::exp(-0.6f * d));
        EXPECT_FLOAT_EQ(T.g, std::exp(-0.5f * d));
        EXPECT_FLOAT_EQ(T.b, std::exp(-0.5f * d));
    }
}

// Mean over n free flights of the pass-through weight (0 when the flight scattered) per channel,
// with its standard error: an unbiased estimate of the transmittance over distance d.
void pass_through(const Medium& m, float d, int n, Rgb& mean, Rgb& se, double* scatter_albedo_error = nullptr,
                  Rgb albedo = Rgb(0.0f)) {
    Sampler s(11, 3);
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0}, worst = 0;
    for (int i = 0; i < n; ++i) {
        const FreeFlight f = sample_free_flight(m, Vec3(0.0f), Vec3(0, 1, 0), d, s);
        if (f.scattered) {
            ASSERT_GE(f.t, 0.0f);
            ASSERT_LT(f.t, d);
            if (scatter_albedo_error)
                for (int c = 0; c < 3; ++c)
                    worst = std::max(worst, double(std::fabs(f.weight[c] - albedo[c])));
            continue;
        }
        for (int c = 0; c < 3; ++c) sum[c] += f.weight[c], sum2[c] += double(f.weight[c]) * f.weight[c];
    }
    for (int c = 0; c < 3; ++c) {
        mean[c] = float(sum[c] / n);
        se[c] = float(std::sqrt(std::max(0.0, sum2[c] / n - mean[c] * double(mean[c])) / n));
    }
    if (scatter_albedo_error) *scatter_albedo_error = worst;
}

TEST(Tracking, GreyFreeFlightsPassWithBeerLambertProbabilityAndScatterWithTheAlbedo) {
    const Medium m(homogeneous(Rgb(0.2f), Rgb(0.6f)));
    Rgb mean, se;
    double albedo_error = 1;
    pass_through(m, 1.5f, 100000, mean, se, &albedo_error, Rgb(0.75f));
    const double T = std::exp(-0.8 * 1.5);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], T, 5 * se[c] + 1e-6);
    EXPECT_LT(albedo_error, 1e-5)
        << "a grey medium scatters at its first collision with weight sigma_s/sigma_t";
}

TEST(Tracking, ChromaticFreeFlightsAreUnbiasedPerChannel) {
    // One scalar majorant (the largest channel) with spectral-tracking probabilities.
    const Medium m(homogeneous(Rgb(0.05f, 0.3f, 1.0f), Rgb(0.9f, 0.4f, 0.2f)));
    Rgb mean, se;
    pass_through(m, 1.0f, 200000, mean, se);
    const float st[3] = {0.95f, 0.7f, 1.2f};
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], std::exp(-st[c]), 5 * se[c] + 1e-6) << "channel " << c;
}

scene::Medium constant_grid(float density) {
    scene::Medium g = homogeneous(Rgb(0.1f, 0.2f, 0.3f), Rgb(0.4f, 0.2f, 0.1f));
    g.kind = scene::Medium::Kind::UniformGrid;
    g.nx = 3, g.ny = 2, g.nz = 4;
    g.density.assign(24, density);
    g.p0 = Vec3(-2, -1, -3);
    g.p1 = Vec3(2, 5, 3);
    g.to_world = Transform::translate(Vec3(0.5f, 0, 0)) * Transform::scale(Vec3(1, 2, 1));
    return g;
}

TEST(Tracking, ConstantGridMatchesTheHomogeneousClosedForm) {
    // Trilinear interpolation between cell centres falls off towards the box faces, so stay in the
    // region where every sample is interior: the ray runs along y through the grid's middle.
    const Medium grid(constant_grid(1.5f));
    const Vec3 o(0.5f, 1.0f, 0.0f), d(0, 1, 0);
    const float len = 3.0f;  // world y 1..4 = medium y 0.5..2, inside the interior cells
    const Rgb st = (Rgb(0.1f, 0.2f, 0.3f) + Rgb(0.4f, 0.2f, 0.1f)) * 1.5f;
    Sampler s(5);
    const int n = 40000;
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        const Rgb T = transmittance(grid, o, d, len, s);
        for (int c = 0; c < 3; ++c) sum[c] += T[c], sum2[c] += double(T[c]) * T[c];
    }
    for (int c = 0; c < 3; ++c) {
        const double mean = sum[c] / n, se = std::sqrt(std::max(0.0, sum2[c] / n - mean * mean) / n);
        EXPECT_NEAR(mean, std::exp(-st[c] * len), 5 * se + 1e-6) << "ratio tracking, channel " << c;
    }
    double pass[3] = {0, 0, 0}, pass2[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        const FreeFlight f = sample_free_flight(grid, o, d, len, s);
        if (f.scattered) continue;
        for (int c = 0; c < 3; ++c) pass[c] += f.weight[c], pass2[c] += double(f.weight[c]) * f.weight[c];
    }
    for (int c = 0; c < 3; ++c) {
        const double mean = pass[c] / n, se = std::sqrt(std::max(0.0, pass2[c] / n - mean * mean) / n);
        EXPECT_NEAR(mean, std::exp(-st[c] * len), 5 * se + 1e-6) << "delta tracking, channel " << c;
    }
}

}  // namespace
}  // namespace phos::shading
