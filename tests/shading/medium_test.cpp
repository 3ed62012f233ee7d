// Participating media numerics (shading/medium.h, shading/medium_tracking.h): Beer-Lambert
// transmittance, delta / spectral tracking free flights (pass-through probability and weight, the
// scattering weight, unbiasedness per channel, emission), ratio tracking and free flights in
// uniform grids against closed forms and quadrature, the grid's lookup convention and the majorant
// segments. (The phase function is tested in phase_test.cpp.)
//
// Coefficients are spectral: a medium's RGB sigma_a and sigma_s are read as unbounded spectra and
// its emission as an illuminant (spectrum/rgb_spectrum.h). The per-channel checks of the RGB
// renderer are made at every wavelength sample of a fixed set, against the closed forms of those
// spectra's values there (computed here from the RGB, independently of the medium).
//
// Statistical tolerances are 5 standard errors of the estimated mean, measured from the same
// samples (a correct implementation fails one check with probability ~6e-7), plus 1e-6 so that a
// zero-variance estimate is not compared at float rounding.
#include "shading/medium.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "shading/medium_tracking.h"
#include "spectral_test_util.h"
#include "support/chi_square.h"

namespace phos::shading {
namespace {

scene::Medium homogeneous(Rgb sigma_a, Rgb sigma_s, float g = 0) {
    scene::Medium m;
    m.sigma_a = sigma_a;
    m.sigma_s = sigma_s;
    m.g = g;
    return m;
}

using spectral::kSpectrumSamples;

const Wavelengths& kLambda = spectral::fixed_lambda();

// An RGB coefficient at kLambda (an unbounded spectrum).
Spectrum coef(Rgb c) { return spectral::unbounded(c, kLambda); }

// Per-wavelength-sample running mean and standard error of the mean.
struct MeanS {
    double sum[kSpectrumSamples] = {}, sum2[kSpectrumSamples] = {};
    long n = 0;
    void add(const Spectrum& v) {
        for (int c = 0; c < kSpectrumSamples; ++c) sum[c] += v[c], sum2[c] += double(v[c]) * v[c];
        ++n;
    }
    double mean(int c) const { return sum[c] / double(n); }
    double se(int c) const {
        const double m = mean(c);
        return std::sqrt(std::max(0.0, sum2[c] / double(n) - m * m) / double(n));
    }
};

// ---------------------------------------------------------------------------------------------
// Homogeneous media

TEST(Tracking, HomogeneousTransmittanceIsBeerLambert) {
    scene::Medium sm = homogeneous(Rgb(0.05f, 0.1f, 0.2f), Rgb(0.25f, 0.15f, 0.05f));
    sm.scale = 2;  // sigma_t = (0.6, 0.5, 0.5)
    const Medium m(sm);
    EXPECT_FLOAT_EQ(m.sigma_t_rgb().r, 0.6f);
    EXPECT_FLOAT_EQ(m.sigma_t_rgb().b, 0.5f);
    // The scaled RGB coefficients as spectra, summed.
    const Spectrum st = coef(sm.sigma_a * 2.0f) + coef(sm.sigma_s * 2.0f);
    EXPECT_TRUE(spectral::spectra_near(m.sigma_t(kLambda), st, 1e-6));
    EXPECT_FALSE(st.is_flat());  // a coloured medium: the test is about more than one value
    // Under RGB white the film sees the spectrum as the RGB sigma_t (each term's exact fit is within
    // 1e-5 of its RGB; 1 % allows for 4096 x 4 stratified wavelengths' Monte Carlo error).
    const Rgb colour = spectral::film_colour(
        [&](const Wavelengths& l) { return m.sigma_t(l) * spectral::illuminant(Rgb(1.0f), l); });
    EXPECT_TRUE(spectral::rgb_near(colour, m.sigma_t_rgb(), 0.01));
    Sampler s(1);
    const Vec3 d = normalize(Vec3(0.3f, -0.4f, 0.5f));
    for (float t : {0.0f, 0.3f, 1.0f, 4.0f}) {
        const Spectrum T = transmittance(m, Vec3(1, 2, 3), d, t, s, kLambda);
        for (int i = 0; i < kSpectrumSamples; ++i) EXPECT_FLOAT_EQ(T[i], std::exp(-st[i] * t)) << i;
    }
    // An unbounded ray through an absorbing medium keeps nothing; through a clear one, everything.
    EXPECT_EQ(transmittance(m, Vec3(0.0f), d, kInf, s, kLambda).max(), 0.0f);
    const Medium clear(homogeneous(Rgb(0.0f), Rgb(0.0f)));
    EXPECT_EQ(transmittance(clear, Vec3(0.0f), d, kInf, s, kLambda), Spectrum(1.0f));
}

TEST(Tracking, HomogeneousMajorantIsOneSegmentOverTheWholeRange) {
    const Rgb sa(0.1f, 0.2f, 0.3f), ss(0.5f, 0.1f, 0.4f);
    const Medium m(homogeneous(sa, ss));
    Medium::Majorants it = m.majorants(Vec3(0.0f), Vec3(0, 0, 1), 0.25f, 3.5f);
    float ta = 0, tb = 0, sigma = 0;
    ASSERT_TRUE(it.next(ta, tb, sigma));
    EXPECT_EQ(ta, 0.25f);
    EXPECT_EQ(tb, 3.5f);
    // The largest sigma_t over the wavelengths (scanned every 0.1 nm): bounded, and tight to
    // 0.5 % (a looser one only costs null collisions, but is no longer the medium's majorant).
    const spectrum::RgbSpectrum a(sa, spectrum::RgbSpectrum::Use::Unbounded),
        b(ss, spectrum::RgbSpectrum::Use::Unbounded);
    float largest = 0;
    for (int k = 0; k <= 4700; ++k) {
        const float l = spectrum::kLambdaMin + 0.1f * float(k);
        largest = std::max(largest, a(l) + b(l));
    }
    EXPECT_GE(sigma, largest);
    EXPECT_LE(sigma, 1.005f * largest);
    EXPECT_FALSE(it.next(ta, tb, sigma));
    Medium::Majorants empty = m.majorants(Vec3(0.0f), Vec3(0, 0, 1), 1.0f, 1.0f);
    EXPECT_FALSE(empty.next(ta, tb, sigma));
}

TEST(Tracking, GreySlabPassesWithBeerLambertProbabilityAndScattersWithTheAlbedo) {
    // sigma_t = 0.8, albedo 0.75, slab thickness 1.5: T = exp(-1.2) = 0.301.
    const Medium m(homogeneous(Rgb(0.2f), Rgb(0.6f)));
    const float d = 1.5f, sigma_t = 0.8f;
    // Grey coefficients are flat spectra: sigma_t is 0.8 at every wavelength, and so is its
    // majorant (what makes the weights below exact: no null collisions).
    EXPECT_TRUE(spectral::flat_near(m.sigma_t(spectral::fixed_lambda()), sigma_t, 1e-7));
    Medium::Majorants it = m.majorants(Vec3(0.0f), Vec3(0, 1, 0), 0.0f, d);
    float ta = 0, tb = 0, sigma_maj = 0;
    ASSERT_TRUE(it.next(ta, tb, sigma_maj));
    EXPECT_FLOAT_EQ(sigma_maj, sigma_t) << "a grey medium's majorant is its sigma_t";
    const int n = 100000;
    Sampler s(11, 3);
    long passed = 0;
    MeanS pass_weight;
    double worst_pass = 0, worst_albedo = 0;
    // The scattering distances follow the exponential pdf truncated to [0, d): 20 bins of equal
    // probability under it.
    const int bins = 20;
    std::vector<double> observed(bins, 0.0);
    const double norm = -std::expm1(-double(sigma_t) * d);
    for (int i = 0; i < n; ++i) {
        // Each flight at its own wavelengths: a grey medium is the same at all of them.
        const FreeFlight f =
            sample_free_flight(m, Vec3(0.0f), Vec3(0, 1, 0), d, s, spectral::stratified_lambda(i, n));
        ASSERT_TRUE(f.emitted.is_black());
        if (f.scattered) {
            ASSERT_GE(f.t, 0.0f);
            ASSERT_LT(f.t, d);
            for (int c = 0; c < kSpectrumSamples; ++c)
                worst_albedo = std::max(worst_albedo, double(std::fabs(f.weight[c] - 0.75f)));
            const double cdf = -std::expm1(-double(sigma_t) * f.t) / norm;
            observed[size_t(std::min(bins - 1, int(cdf * bins)))] += 1;
            pass_weight.add(Spectrum(0.0f));
        } else {
            ++passed;
            for (int c = 0; c < kSpectrumSamples; ++c)
                worst_pass = std::max(worst_pass, double(std::fabs(f.weight[c] - 1)));
            pass_weight.add(f.weight);
        }
    }
    const double T = std::exp(-double(sigma_t) * d);
    // Binomial: the fraction passing has standard error sqrt(T (1 - T) / n) = 0.0015.
    EXPECT_NEAR(double(passed) / n, T, 5 * std::sqrt(T * (1 - T) / n));
    for (int c = 0; c < kSpectrumSamples; ++c)
        EXPECT_NEAR(pass_weight.mean(c), T, 5 * pass_weight.se(c) + 1e-6);
    // A grey medium has no null collisions under its own sigma_t: weights are exact.
    EXPECT_LT(worst_pass, 1e-6) << "a grey flight that passes keeps weight 1";
    EXPECT_LT(worst_albedo, 1e-6)
        << "a grey flight scatters at its first collision with weight sigma_s/sigma_t";
    std::vector<double> expected(bins, double(n - passed) / bins);
    const test::ChiSquareResult chi = test::chi_square(observed, expected, 1e-4);
    EXPECT_TRUE(chi.passed) << "scattering distances: " << chi.detail;
}

// Spectral tracking (one scalar majorant, history-aware probabilities) must stay unbiased per
// channel whatever throughput the path brings in: the mean pass-through weight is exp(-sigma_t d)
// and the mean scattering weight sigma_s / sigma_t (1 - exp(-sigma_t d)) (the integral of
// T(t) sigma_s over [0, d)), channel by channel.
TEST(Tracking, ChromaticFreeFlightsAreUnbiasedPerWavelength) {
    const Rgb sa_rgb(0.05f, 0.3f, 1.0f), ss_rgb(0.9f, 0.4f, 0.2f);
    const Medium m(homogeneous(sa_rgb, ss_rgb));
    const Spectrum ss = coef(ss_rgb), st = coef(sa_rgb) + ss;
    const float d = 1.0f;
    Spectrum chromatic_a, chromatic_b;
    chromatic_a.v = {1.0f, 0.2f, 0.05f, 0.5f};
    chromatic_b.v = {0.01f, 0.5f, 3.0f, 1.0f};
    int seed = 0;
    for (const Spectrum& throughput : {Spectrum(1.0f), chromatic_a, chromatic_b}) {
        Sampler s(13, uint64_t(++seed));
        MeanS pass, scatter;
        const int n = 200000;
        for (int i = 0; i < n; ++i) {
            const FreeFlight f = sample_free_flight(m, Vec3(0.0f), Vec3(0, 1, 0), d, s, kLambda, throughput);
            ASSERT_TRUE(f.weight.is_finite());
            pass.add(f.scattered ? Spectrum(0.0f) : f.weight);
            scatter.add(f.scattered ? f.weight : Spectrum(0.0f));
        }
        for (int c = 0; c < kSpectrumSamples; ++c) {
            const double T = std::exp(-double(st[c]) * d);
            const double S = double(ss[c]) / st[c] * (1 - T);
            EXPECT_NEAR(pass.mean(c), T, 5 * pass.se(c) + 1e-6)
                << "pass-through, wavelength " << kLambda[c] << ", throughput "
                << spectral::describe(throughput);
            EXPECT_NEAR(scatter.mean(c), S, 5 * scatter.se(c) + 1e-6)
                << "scattering, wavelength " << kLambda[c] << ", throughput "
                << spectral::describe(throughput);
        }
    }
}

TEST(Tracking, EmissionIsCollectedUnbiasedly) {
    // Emitted radiance per unit absorption Le: along [0, d) the medium contributes
    // int T(t) sigma_a Le dt = sigma_a Le (1 - exp(-sigma_t d)) / sigma_t per channel.
    scene::Medium sm = homogeneous(Rgb(0.5f, 0.1f, 0.3f), Rgb(0.2f, 0.6f, 0.0f));
    sm.emission = Rgb(2.0f, 1.0f, 4.0f);
    const Medium m(sm);
    ASSERT_TRUE(m.emissive());
    const float d = 2.0f;
    Sampler s(21);
    MeanS em;
    for (int i = 0; i < 200000; ++i)
        em.add(sample_free_flight(m, Vec3(0.0f), Vec3(1, 0, 0), d, s, kLambda).emitted);
    // The emission is read as an illuminant, the coefficients as unbounded spectra.
    const Spectrum sa = coef(sm.sigma_a), st = sa + coef(sm.sigma_s),
                   Le = spectral::illuminant(sm.emission, kLambda);
    for (int c = 0; c < kSpectrumSamples; ++c) {
        const double expected = double(sa[c]) * Le[c] * (1 - std::exp(-double(st[c]) * d)) / st[c];
        EXPECT_NEAR(em.mean(c), expected, 5 * em.se(c) + 1e-6) << "wavelength " << kLambda[c];
    }
}

// ---------------------------------------------------------------------------------------------
// Uniform grids

// A grid medium with a non-trivial transform (rotation, anisotropic scale, translation) and a box
// [p0, p1] that is not the unit box.
Transform grid_to_world() {
    return Transform::translate(Vec3(0.5f, -1.0f, 2.0f)) * Transform::rotate(30, normalize(Vec3(1, 2, 3))) *
           Transform::scale(Vec3(1.5f, 2.0f, 0.75f));
}

scene::Medium grid_medium(int nx, int ny, int nz, std::vector<float> density) {
    scene::Medium g = homogeneous(Rgb(0.1f, 0.2f, 0.3f), Rgb(0.4f, 0.2f, 0.1f));
    g.kind = scene::Medium::Kind::UniformGrid;
    g.nx = nx, g.ny = ny, g.nz = nz;
    g.density = std::move(density);
    g.p0 = Vec3(-2, -1, -3);
    g.p1 = Vec3(2, 5, 3);
    g.to_world = grid_to_world();
    return g;
}

// pbrt-v4's SampledGrid lookup, written out independently: samples at cell centres, trilinear in
// between, samples outside the index range are 0, density 0 outside [p0, p1] (medium space).
double reference_density(const scene::Medium& g, Vec3 p) {
    if (p.x < g.p0.x || p.y < g.p0.y || p.z < g.p0.z || p.x > g.p1.x || p.y > g.p1.y || p.z > g.p1.z)
        return 0;
    const int n[3] = {g.nx, g.ny, g.nz};
    double s[3];
    int i0[3];
    double f[3];
    for (int a = 0; a < 3; ++a) {
        s[a] = (double(p[a]) - g.p0[a]) / (double(g.p1[a]) - g.p0[a]) * n[a] - 0.5;
        i0[a] = int(std::floor(s[a]));
        f[a] = s[a] - i0[a];
    }
    const auto v = [&](int x, int y, int z) -> double {
        if (x < 0 || y < 0 || z < 0 || x >= g.nx || y >= g.ny || z >= g.nz) return 0;
        return g.density[size_t((z * g.ny + y) * g.nx + x)];
    };
    double r = 0;
    for (int c = 0; c < 8; ++c) {
        const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
        const double w = (dx ? f[0] : 1 - f[0]) * (dy ? f[1] : 1 - f[1]) * (dz ? f[2] : 1 - f[2]);
        r += w * v(i0[0] + dx, i0[1] + dy, i0[2] + dz);
    }
    return r;
}

// Optical depth per unit sigma_t (density integral) along the world ray o + t d, t in [0, len),
// by composite Simpson on 20000 intervals over the reference lookup (the density is piecewise
// linear along the ray with a few dozen kinks: error < 1e-5 relative).
double density_integral(const scene::Medium& g, Vec3 o, Vec3 d, float len) {
    const Transform to_medium = g.to_world.inverse();
    const int n = 20000;
    const double h = double(len) / n;
    double acc = 0;
    for (int i = 0; i <= n; ++i) {
        const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
        acc += w * reference_density(g, to_medium.point(o + d * float(i * h)));
    }
    return acc * h / 3;
}

// Mean of ratio-tracking transmittance and of delta-tracking pass-through weights over n samples.
void track(const Medium& m, Vec3 o, Vec3 d, float len, int n, uint64_t seed, MeanS& ratio, MeanS& pass) {
    Sampler s(seed);
    for (int i = 0; i < n; ++i) {
        ratio.add(transmittance(m, o, d, len, s, kLambda));
        const FreeFlight f = sample_free_flight(m, o, d, len, s, kLambda);
        pass.add(f.scattered ? Spectrum(0.0f) : f.weight);
    }
}

TEST(Grid, LookupFollowsThePbrtSampledGridConvention) {
    // 2 x 1 x 1 samples (0.5, 3.0): cell centres at medium x = -1 and 1 (the box is x in [-2, 2]).
    const scene::Medium g = grid_medium(2, 1, 1, {0.5f, 3.0f});
    const Medium m(g);
    const Spectrum st1 = coef(g.sigma_a) + coef(g.sigma_s);  // sigma_t at density 1
    const auto density_at = [&](Vec3 p_medium) {             // read at the hero wavelength
        return m.at(g.to_world.point(p_medium), kLambda).sigma_t()[0] / st1[0];
    };
    const float yc = 2.0f, zc = 0.0f;  // the centre of the box in y and z: those factors are 1
    EXPECT_NEAR(density_at(Vec3(-1, yc, zc)), 0.5f, 1e-4f);  // cell centres hold the samples
    EXPECT_NEAR(density_at(Vec3(1, yc, zc)), 3.0f, 1e-4f);
    EXPECT_NEAR(density_at(Vec3(0, yc, zc)), 1.75f, 1e-4f);  // linear in between
    // Half a cell out, at the faces: halfway to 0 (just inside them, so that rounding through the
    // transform cannot put the point outside; 1e-4 in from the face moves the value by < 2e-4).
    EXPECT_NEAR(density_at(Vec3(-1.9999f, yc, zc)), 0.25f, 1e-3f);
    EXPECT_NEAR(density_at(Vec3(1.9999f, yc, zc)), 1.5f, 1e-3f);
    EXPECT_NEAR(density_at(Vec3(-1, 4.9999f, zc)), 0.25f, 1e-3f);  // the y face too
    EXPECT_EQ(density_at(Vec3(2.01f, yc, zc)), 0.0f);              // outside the box
    EXPECT_EQ(density_at(Vec3(0, -1.01f, zc)), 0.0f);
    // The coefficients scale both sigma_a and sigma_s; grids carry no emission.
    const MediumCoefficients c = m.at(g.to_world.point(Vec3(1, yc, zc)), kLambda);
    EXPECT_TRUE(spectral::spectra_near(c.sigma_a, coef(g.sigma_a) * 3.0f, 1e-4));
    EXPECT_TRUE(spectral::spectra_near(c.sigma_s, coef(g.sigma_s) * 3.0f, 1e-4));
    EXPECT_TRUE(c.Le.is_black());
    // Against the reference at random points of (and around) the box.
    Sampler s(31);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 p(-2.5f + 5 * s.next(), -1.5f + 7 * s.next(), -3.5f + 7 * s.next());
        const double ref = reference_density(g, p);
        ASSERT_NEAR(density_at(p), ref, 1e-4) << p.x << " " << p.y << " " << p.z;
        // The density scales sigma_t at every wavelength alike.
        ASSERT_TRUE(
            spectral::spectra_near(m.at(g.to_world.point(p), kLambda).sigma_t(), st1 * float(ref), 0, 1e-4));
    }
}

TEST(Grid, ConstantGridMatchesTheHomogeneousClosedForm) {
    // Trilinear interpolation between cell centres falls off towards the faces, so the ray stays
    // where every lookup is between cell centres: medium y from 0.5 to 3.5 (the two y centres) at
    // x = 0.3, z = 0.4 (centres span x [-1.33, 1.33], z [-2.25, 2.25]), through the transform.
    const scene::Medium g = grid_medium(3, 2, 4, std::vector<float>(24, 1.5f));
    const Medium grid(g);
    const Vec3 a = g.to_world.point(Vec3(0.3f, 0.5f, 0.4f)), b = g.to_world.point(Vec3(0.3f, 3.5f, 0.4f));
    const float len = length(b - a);  // 6 world units (y is scaled by 2)
    const Vec3 d = (b - a) / len;
    // sigma_t = (0.75, 0.6, 0.6) in RGB: T = 0.011 .. 0.027.
    const Spectrum st = (coef(g.sigma_a) + coef(g.sigma_s)) * 1.5f;
    MeanS ratio, pass;
    track(grid, a, d, len, 40000, 5, ratio, pass);
    for (int c = 0; c < kSpectrumSamples; ++c) {
        const double T = std::exp(-double(st[c]) * len);
        EXPECT_NEAR(ratio.mean(c), T, 5 * ratio.se(c) + 1e-6) << "ratio tracking, channel " << c;
        EXPECT_NEAR(pass.mean(c), T, 5 * pass.se(c) + 1e-6) << "delta tracking, channel " << c;
    }
    // Shorter stretch with a larger transmittance (half the length: T = 0.11 .. 0.17).
    MeanS ratio2, pass2;
    track(grid, a, d, 0.5f * len, 40000, 6, ratio2, pass2);
    for (int c = 0; c < kSpectrumSamples; ++c) {
        const double T = std::exp(-double(st[c]) * 0.5 * len);
        EXPECT_NEAR(ratio2.mean(c), T, 5 * ratio2.se(c) + 1e-6) << "ratio tracking, channel " << c;
        EXPECT_NEAR(pass2.mean(c), T, 5 * pass2.se(c) + 1e-6) << "delta tracking, channel " << c;
    }
}

TEST(Grid, DensityGradientMatchesTheOpticalDepthIntegral) {
    // Two samples in x (0.1 and 0.5): along the medium x axis through the centre of y and z, the
    // density is a + 2 (b - a)(u - 1/4) between the cell centres u in [1/4, 3/4] of the box and
    // falls linearly to half the end samples at the faces, so int_0^1 density du = 0.4375 (a + b)
    // (exactly). The box is 4 medium units long in x = 6 world units (x is scaled by 1.5).
    const float a = 0.1f, b = 0.5f;
    const scene::Medium g = grid_medium(2, 1, 1, {a, b});
    const Medium grid(g);
    const Vec3 o = g.to_world.point(Vec3(-3.0f, 2.0f, 0.0f)), e = g.to_world.point(Vec3(3.0f, 2.0f, 0.0f));
    const float len = length(e - o);  // from 1 medium unit before the box to 1 after: 9 world units
    const Vec3 d = (e - o) / len;
    const double closed = 0.4375 * (a + b) * 6.0;
    EXPECT_NEAR(density_integral(g, o, d, len), closed, 1e-4 * closed) << "the reference quadrature";
    // sigma_t = (0.5, 0.4, 0.4) in RGB: optical depths 1.31, 1.05, 1.05.
    const Spectrum st = coef(g.sigma_a) + coef(g.sigma_s);
    MeanS ratio, pass;
    track(grid, o, d, len, 40000, 7, ratio, pass);
    for (int c = 0; c < kSpectrumSamples; ++c) {
        const double T = std::exp(-st[c] * closed);
        EXPECT_NEAR(ratio.mean(c), T, 5 * ratio.se(c) + 1e-6) << "ratio tracking, channel " << c;
        EXPECT_NEAR(pass.mean(c), T, 5 * pass.se(c) + 1e-6) << "delta tracking, channel " << c;
    }
}

TEST(Grid, ObliqueRaysThroughAVaryingGridMatchQuadrature) {
    // A 5 x 4 x 3 grid of varied densities (some cells empty), rays entering, leaving and
    // starting inside the box at odd angles; transmittance against the quadrature of the
    // reference lookup.
    std::vector<float> dens(60);
    Sampler r(41);
    for (size_t i = 0; i < dens.size(); ++i) dens[i] = (i % 7 == 3) ? 0.0f : 0.6f * r.next();
    const scene::Medium g = grid_medium(5, 4, 3, dens);
    const Medium grid(g);
    struct RayCase {
        Vec3 from, to;  // medium space
    };
    const RayCase cases[] = {
        {{-3, -2, -4}, {3, 6, 4}},            // corner to corner, entering and leaving
        {{0.2f, 1, 0}, {1.5f, 4.9f, -2.9f}},  // from inside to near a face
        {{-2.5f, 4, 2}, {2.5f, 0, -1}},       // across, outside at both ends
    };
    for (const RayCase& rc : cases) {
        const Vec3 o = g.to_world.point(rc.from), e = g.to_world.point(rc.to);
        const float len = length(e - o);
        const Vec3 d = (e - o) / len;
        const double tau = density_integral(g, o, d, len);
        MeanS ratio, pass;
        track(grid, o, d, len, 20000, 8, ratio, pass);
        const Spectrum st = coef(g.sigma_a) + coef(g.sigma_s);
        for (int c = 0; c < kSpectrumSamples; ++c) {
            const double T = std::exp(-st[c] * tau);
            EXPECT_NEAR(ratio.mean(c), T, 5 * ratio.se(c) + 1e-5)
                << "ratio tracking, channel " << c << ", tau " << tau;
            EXPECT_NEAR(pass.mean(c), T, 5 * pass.se(c) + 1e-5)
                << "delta tracking, channel " << c << ", tau " << tau;
        }
    }
}

TEST(Grid, MajorantSegmentsCoverTheRayInsideTheBoxAndBoundSigmaT) {
    std::vector<float> dens(60);
    Sampler r(51);
    for (size_t i = 0; i < dens.size(); ++i) dens[i] = (i % 5 == 1) ? 0.0f : 2.0f * r.next() * r.next();
    scene::Medium g = grid_medium(5, 4, 3, dens);
    g.scale = 1.7f;
    const Medium grid(g);
    const Transform to_medium = g.to_world.inverse();
    Sampler s(52);
    int rays_in_box = 0;
    for (int i = 0; i < 300; ++i) {
        // Random rays between random points of a region 1.5 x the box (medium space), random range.
        const auto point = [&] {
            return Vec3(-3 + 6 * s.next(), -2.5f + 9 * s.next(), -4.5f + 9 * s.next());
        };
        const Vec3 o = g.to_world.point(point()), e = g.to_world.point(point());
        const float len = length(e - o);
        if (!(len > 1e-3f)) continue;
        const Vec3 d = (e - o) / len;
        const float t0 = 0.3f * len * s.next(), t1 = t0 + 1.2f * len * s.next();
        // The part of [t0, t1) inside the box, by a slab test in medium space (in double).
        const Vec3 om = to_medium.point(o), dm = to_medium.vector(d);
        double lo = t0, hi = t1;
        for (int a = 0; a < 3; ++a) {
            if (dm[a] == 0) continue;
            double tn = (double(g.p0[a]) - om[a]) / dm[a], tf = (double(g.p1[a]) - om[a]) / dm[a];
            if (tn > tf) std::swap(tn, tf);
            lo = std::max(lo, tn);
            hi = std::min(hi, tf);
        }
        Medium::Majorants it = grid.majorants(o, d, t0, t1);
        float ta, tb, sigma;
        std::vector<float> starts, ends;
        while (it.next(ta, tb, sigma)) {
            ASSERT_LT(ta, tb);
            if (!ends.empty()) {
                ASSERT_EQ(ta, ends.back()) << "segments are contiguous";
            }
            starts.push_back(ta);
            ends.push_back(tb);
            // sigma_maj bounds sigma_t at every wavelength anywhere on the segment.
            for (int k = 0; k < 16; ++k) {
                const float t = ta + (tb - ta) * (k < 2 ? float(k) * 0.9999f : s.next());
                const float st = grid.at(o + d * t, Wavelengths::visible(s.next())).sigma_t().max();
                ASSERT_LE(st, sigma * (1 + 1e-5f) + 1e-6f)
                    << "ray " << i << " t " << t << " in [" << ta << ", " << tb << ")";
            }
        }
        const double tol = 1e-4 * std::max(1.0, double(t1));
        if (!(hi - lo > 2 * tol)) {
            // The ray misses the box within the range: no segment, or only a sliver at rounding.
            if (!starts.empty()) {
                EXPECT_LT(ends.back() - starts.front(), 2 * tol);
            }
            continue;
        }
        ++rays_in_box;
        ASSERT_FALSE(starts.empty()) << "ray " << i;
        EXPECT_NEAR(starts.front(), lo, tol)
            << "ray " << i << ": the segments start where the range enters the box";
        EXPECT_NEAR(ends.back(), hi, tol) << "ray " << i << ": and end where it leaves it";
        // Outside the covered range the density is 0 (nothing is skipped that matters).
        for (int k = 0; k < 8; ++k) {
            const float tout = s.next() < 0.5f ? t0 + (starts.front() - t0) * s.next()
                                               : ends.back() + (t1 - ends.back()) * s.next();
            if (tout >= starts.front() && tout <= ends.back()) continue;  // an empty side (ray starts inside)
            const Vec3 pm = to_medium.point(o + d * tout);
            // Points within rounding of the faces are not tested.
            bool near_face = false;
            for (int a = 0; a < 3; ++a)
                near_face |= std::fabs(pm[a] - g.p0[a]) < 1e-3f || std::fabs(pm[a] - g.p1[a]) < 1e-3f;
            if (!near_face) {
                EXPECT_EQ(grid.at(o + d * tout, kLambda).sigma_t().max(), 0.0f)
                    << "ray " << i << " t " << tout;
            }
        }
    }
    EXPECT_GT(rays_in_box, 100);  // the random rays really exercised the grid
}

}  // namespace
}  // namespace phos::shading
