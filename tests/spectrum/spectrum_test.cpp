// Tests of the spectral machinery (src/spectrum): the CIE tables and the sRGB matrices (D65 maps
// to the sRGB white, the equal-energy spectrum to X = Y = Z), the visible-wavelength density
// (normalised, sampled exactly by its inverse CDF, the four wavelengths stratified), the hero
// wavelength's termination (unbiased), the Monte Carlo XYZ of a sampled spectrum against the
// tabulated integral, Planck's law (Wien's peak, the normalisation, the Stefan-Boltzmann total) and
// the named glasses against their catalogue n_d and Abbe numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "spectrum/blackbody.h"
#include "spectrum/cie_tables.h"
#include "spectrum/color.h"
#include "spectrum/dispersion.h"
#include "spectrum/piecewise_linear.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::spectrum {
namespace {

TEST(Colour, D65IsTheSrgbWhite) {
    const Vec3 xyz = integrate_xyz([](double l) { return double(d65(float(l))); });
    const Vec3 rgb = apply(xyz_to_srgb(), xyz * (1 / xyz.y));
    std::printf("[ measured ] D65 -> linear sRGB %.6f %.6f %.6f (x %.5f y %.5f)\n", rgb.x, rgb.y, rgb.z,
                xyz.x / (xyz.x + xyz.y + xyz.z), xyz.y / (xyz.x + xyz.y + xyz.z));
    EXPECT_NEAR(rgb.x, 1.0, 1e-4);
    EXPECT_NEAR(rgb.y, 1.0, 1e-4);
    EXPECT_NEAR(rgb.z, 1.0, 1e-4);
    // The white is D65's own chromaticity, which the standard rounds to (0.3127, 0.3290).
    EXPECT_NEAR(xyz.x / (xyz.x + xyz.y + xyz.z), 0.3127, 5e-5);
    EXPECT_NEAR(xyz.y / (xyz.x + xyz.y + xyz.z), 0.3290, 5e-5);
}

TEST(Colour, EqualEnergyHasEqualTristimulusValues) {
    // The CIE 1931 functions are scaled so that the equal-energy spectrum has X = Y = Z.
    const Vec3 xyz = integrate_xyz([](double) { return 1.0; });
    EXPECT_NEAR(xyz.y, 1.0, 1e-6);
    EXPECT_NEAR(xyz.x, 1.0, 2e-3);
    EXPECT_NEAR(xyz.z, 1.0, 2e-3);
}

TEST(Colour, SrgbMatricesAreInverseAndMapWhiteToD65) {
    const Vec3 w = apply(srgb_to_xyz(), Vec3(1.0f));
    EXPECT_NEAR(w.y, 1.0, 1e-6);
    EXPECT_NEAR(w.x / (w.x + w.y + w.z), 0.3127, 5e-5);
    EXPECT_NEAR(w.y / (w.x + w.y + w.z), 0.3290, 5e-5);
    const Vec3 v(0.2f, 0.7f, 0.4f);
    const Vec3 back = apply(xyz_to_srgb(), apply(srgb_to_xyz(), v));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], v[c], 1e-6);
}

TEST(Wavelengths, VisibleDensityIsNormalisedAndSampledByItsInverseCdf) {
    double total = 0;
    for (int i = 0; i < 47000; ++i) total += visible_pdf(kLambdaMin + (float(i) + 0.5f) * 0.01f) * 0.01;
    EXPECT_NEAR(total, 1.0, 1e-4);
    EXPECT_EQ(visible_pdf(300.0f), 0.0f);
    // The inverse CDF: the fraction of u below t lands below sample_visible(t), by the pdf's sum.
    for (const float u : {0.1f, 0.37f, 0.5f, 0.9f}) {
        const float l = sample_visible(u);
        double cdf = 0;
        for (int i = 0; kLambdaMin + (i + 0.5) * 0.01 < l; ++i)
            cdf += visible_pdf(float(kLambdaMin + (i + 0.5) * 0.01)) * 0.01;
        EXPECT_NEAR(cdf, u, 2e-4) << "u " << u;
    }
    EXPECT_NEAR(sample_visible(0.0f), kLambdaMin, 1e-3);
    EXPECT_NEAR(sample_visible(0.99999f), kLambdaMax, 0.5);
}

TEST(Wavelengths, FourWavelengthsAreStratifiedInTheDensity) {
    Sampler rng(3);
    for (int n = 0; n < 100; ++n) {
        const SampledWavelengths w = SampledWavelengths::visible(rng.next());
        std::vector<float> l;
        for (int i = 0; i < kSpectrumSamples; ++i) {
            l.push_back(w[i]);
            // The tabulated density paths sample with, within 3 % of the smooth one (in the tails).
            EXPECT_FLOAT_EQ(w.pdf(i), SampledWavelengths::visible_sampling_pdf(w[i]));
            EXPECT_NEAR(w.pdf(i), visible_pdf(w[i]), 3e-2f * visible_pdf(w[i]));
        }
        std::sort(l.begin(), l.end());
        // One in each quarter of the density's mass: the quartiles of the CDF separate them.
        for (int q = 0; q < kSpectrumSamples; ++q) {
            EXPECT_GE(l[size_t(q)], sample_visible(0.25f * float(q)) - 1e-3f);
            EXPECT_LE(l[size_t(q)], sample_visible(0.25f * float(q + 1) - 1e-7f) + 1e-3f);
        }
    }
}

// A wavelength set is its hero's 16-bit code (what a photon stores): from_code(code()) gives the
// same wavelengths and densities, terminated or not; the tabulated density integrates to 1 and is
// the density of the hero over uniform codes (a histogram of all 2^16 codes in 47 bins).
TEST(Wavelengths, CodesRebuildTheSetAndTheTabulatedDensityIsTheOneSampled) {
    Sampler rng(5);
    for (int n = 0; n < 200; ++n) {
        SampledWavelengths w = SampledWavelengths::visible(rng.next());
        if (n % 2) w.terminate_secondary();
        const SampledWavelengths back = SampledWavelengths::from_code(w.code(), w.secondary_terminated());
        for (int i = 0; i < kSpectrumSamples; ++i) {
            EXPECT_EQ(back[i], w[i]);
            EXPECT_EQ(back.pdf(i), w.pdf(i));
        }
    }
    double total = 0;
    for (int i = 0; i < 47000; ++i)
        total += SampledWavelengths::visible_sampling_pdf(kLambdaMin + (float(i) + 0.5f) * 0.01f) * 0.01;
    EXPECT_NEAR(total, 1.0, 1e-4);
    std::vector<double> bins(47, 0.0);
    for (int c = 0; c < kWavelengthCodes; ++c)
        bins[std::min(size_t(46), size_t((SampledWavelengths::from_code(uint16_t(c))[0] - kLambdaMin) /
                                         10))] += 1.0 / kWavelengthCodes;
    for (size_t b = 0; b < bins.size(); ++b) {
        double expected = 0;
        for (int i = 0; i < 1000; ++i)
            expected += SampledWavelengths::visible_sampling_pdf(kLambdaMin + 10 * float(b) +
                                                                 (float(i) + 0.5f) * 0.01f) *
                        0.01;
        EXPECT_NEAR(bins[b], expected, 1e-4) << "bin " << b;
    }
}

// A pixel's wavelength sequence: its first 2^k points give 2^k wavelength sets that, the four of
// each together, cover 4 × 2^k equal strata of the sampling CDF once each (what independent
// samples leave to chance: colour noise), whichever the pixel's key; the hero's quarter is the one
// each point falls in, uniform over the four across pixels.
TEST(Wavelengths, APixelsSequenceCoversTheSpectrumInEqualStrata) {
    int hero_quarters[4] = {0, 0, 0, 0};
    for (uint64_t key = 0; key < 64; ++key) {
        const uint64_t k = mix64(key + 99);
        for (int log_n : {0, 2, 4, 6}) {
            const int n = 1 << log_n;
            std::vector<int> strata(size_t(4 * n), 0);
            for (int s = 0; s < n; ++s) {
                const float u = wavelength_sequence_point(uint32_t(s), k);
                ASSERT_GE(u, 0.0f);
                ASSERT_LT(u, 1.0f);
                const uint16_t code = SampledWavelengths::code_of(u);
                for (int i = 0; i < kSpectrumSamples; ++i) {
                    const int c =
                        (int(code) + i * (kWavelengthCodes / kSpectrumSamples)) & (kWavelengthCodes - 1);
                    ++strata[size_t(c / (kWavelengthCodes / (4 * n)))];
                }
            }
            for (size_t b = 0; b < strata.size(); ++b)
                EXPECT_EQ(strata[b], 1) << "n " << n << " stratum " << b;
        }
        for (int s = 0; s < 16; ++s) ++hero_quarters[int(4 * wavelength_sequence_point(uint32_t(s), k))];
    }
    for (int q = 0; q < 4; ++q) EXPECT_NEAR(hero_quarters[q], 256, 64) << "quarter " << q;  // 1024 draws
}

// The film's estimate (1/n) sum L(λi) x̄(λi) / p(λi) averages to the integral: a smooth spectrum's
// XYZ by Monte Carlo over visible wavelengths against the 1 nm sum, and the same with the
// secondary wavelengths terminated (the hero alone, weighted n times).
TEST(Wavelengths, MonteCarloXyzMatchesTheIntegralWithAndWithoutTheSecondaries) {
    const auto S = [](double l) { return 0.5 + 0.4 * std::sin(l / 40.0); };
    const Vec3 exact = integrate_xyz(S);
    Sampler rng(11);
    const int n = 200000;
    double sum[2][3] = {};
    for (int k = 0; k < n; ++k) {
        const float u = (float(k) + rng.next()) / float(n);  // stratified
        for (int terminated = 0; terminated < 2; ++terminated) {
            SampledWavelengths w = SampledWavelengths::visible(u);
            if (terminated) w.terminate_secondary();
            SampledSpectrum L;
            for (int i = 0; i < kSpectrumSamples; ++i) L[i] = float(S(w[i]));
            const Vec3 xyz = to_xyz(L, w);
            for (int c = 0; c < 3; ++c) sum[terminated][c] += xyz[c];
        }
    }
    for (int t = 0; t < 2; ++t)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[t][c] / n, exact[c], 2e-3 * exact[c]) << t << " " << c;
}

TEST(Blackbody, PeaksAtWiensWavelengthWithValueOne) {
    for (const double T : {2700.0, 5000.0, 6500.0}) {
        const Blackbody b(T);
        const float peak = float(kWien / T * 1e9);
        EXPECT_NEAR(b(peak), 1.0f, 1e-5) << T;
        EXPECT_LT(b(peak - 20), 1.0f);
        EXPECT_LT(b(peak + 20), 1.0f);
    }
    EXPECT_EQ(Blackbody(0)(500.0f), 0.0f);
}

TEST(Blackbody, TotalRadianceIsStefanBoltzmann) {
    // ∫ B dλ = σ T⁴ / π.
    const double T = 3000, sigma = 5.670374419e-8;
    double total = 0;
    for (double l = 10; l < 200000; l += 1) total += planck(l + 0.5, T) * 1e-9;
    EXPECT_NEAR(total, sigma * T * T * T * T / M_PI, 1e-3 * sigma * T * T * T * T / M_PI);
}

TEST(Blackbody, LowerTemperaturesAreRedder) {
    const auto rgb_of = [](double T) {
        const Blackbody b(T);
        return apply(xyz_to_srgb(), integrate_xyz([&](double l) { return double(b(float(l))); }));
    };
    const Vec3 warm = rgb_of(2700), cool = rgb_of(10000);
    EXPECT_GT(warm.x / warm.z, 1.5f);
    EXPECT_LT(cool.x / cool.z, 1.0f);
}

TEST(NamedGlass, IndexAndAbbeNumberMatchTheCatalogue) {
    for (const NamedGlass& g : named_glasses()) {
        const double nd = g.sellmeier.ior(kLineD), vd = abbe_number(g.sellmeier);
        std::printf("[ measured ] %-12s n_d %.5f (catalogue %.5f), V_d %.2f (%.2f)\n", g.name.c_str(), nd,
                    g.n_d, vd, g.v_d);
        EXPECT_NEAR(nd, g.n_d, 1e-4) << g.name;
        EXPECT_NEAR(vd, g.v_d, 0.01 * g.v_d) << g.name;
        // Normal dispersion: the index falls with wavelength over the visible range.
        EXPECT_GT(g.sellmeier.ior(400), g.sellmeier.ior(700)) << g.name;
    }
    EXPECT_TRUE(named_glass("glass-F11").has_value());
    EXPECT_FALSE(named_glass("glass-unknown").has_value());
}

TEST(PiecewiseLinear, InterpolatesHoldsItsEndsAndTakesTheFirstValueAtAStep) {
    const std::vector<float> x{400, 500, 600, 600, 700}, y{1, 3, 3, 5, 7};
    const auto at = [&](float l) {
        return piecewise_linear(
            x.size(), [&](size_t i) { return x[i]; }, [&](size_t i) { return y[i]; }, l);
    };
    EXPECT_FLOAT_EQ(at(450), 2.0f);
    EXPECT_FLOAT_EQ(at(300), 1.0f);
    EXPECT_FLOAT_EQ(at(900), 7.0f);
    EXPECT_FLOAT_EQ(at(500), 3.0f);
    EXPECT_FLOAT_EQ(at(600), 3.0f);  // the step's first point
    EXPECT_FLOAT_EQ(at(650), 6.0f);
    EXPECT_EQ(piecewise_linear(
                  0, [](size_t) { return 0.0f; }, [](size_t) { return 0.0f; }, 500.0f),
              0.0f);
}

}  // namespace
}  // namespace phos::spectrum
