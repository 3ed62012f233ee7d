// LightSet: building runtime lights from a scene, the power-proportional choice (pmf sums to 1, is
// proportional to power, choose() inverts the CDF), zero-power handling and input errors; plus the
// 1D/2D piecewise-constant distributions underneath.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.h"
#include "core/log.h"
#include "light_test_util.h"
#include "shading/distribution2d.h"
#include "shading/lights.h"

namespace phos::shading {
namespace {

Bounds unit_bounds() {
    Bounds b;
    b.extend({-1, -1, -1});
    b.extend({1, 1, 1});
    return b;
}

scene::Scene mixed_scene() {
    scene::Scene s;
    scene::Light point;
    point.kind = scene::Light::Kind::Point;
    point.color = Rgb(1, 2, 3);
    s.lights.push_back(point);
    scene::Light dead = point;
    dead.color = Rgb(0.0f);
    s.lights.push_back(dead);
    scene::Light spot = point;
    spot.kind = scene::Light::Kind::Spot;
    spot.cutoff = 0.4f;
    spot.dropoff = 2;
    s.lights.push_back(spot);
    scene::Light dir;
    dir.kind = scene::Light::Kind::Directional;
    dir.color = Rgb(0.5f);
    s.lights.push_back(dir);
    s.add_area_light(test::rectangle_y(0, 2, 0, 1, 1), Rgb(3.0f));
    scene::Light env;
    env.kind = scene::Light::Kind::Infinite;
    env.color = Rgb(0.01f);
    s.lights.push_back(env);
    return s;
}

TEST(LightSet, PmfIsProportionalToPowerAndChooseInvertsTheCdf) {
    log::set_quiet(true);
    const int warnings = log::warning_count();
    const scene::Scene scene = mixed_scene();
    const LightSet set(scene, unit_bounds());
    log::set_quiet(false);
    ASSERT_EQ(set.size(), 6u);
    EXPECT_EQ(log::warning_count() - warnings, 1);  // the dead light
    ASSERT_EQ(set.infinite_lights(), std::vector<size_t>{5});
    EXPECT_TRUE(set[5].is_infinite());
    EXPECT_TRUE(set[0].is_delta() && set[2].is_delta() && set[3].is_delta());
    EXPECT_FALSE(set[4].is_delta());

    double total = 0, pmf_sum = 0;
    Rgb power_sum(0.0f);
    for (size_t i = 0; i < set.size(); ++i) {
        total += set[i].power().average();
        power_sum += set[i].power();
    }
    EXPECT_NEAR(set[4].power().r, kPi * 3 * 2, 1e-4f);     // pi L A
    EXPECT_NEAR(set[3].power().r, 0.5f * kPi * 3, 1e-4f);  // E pi R^2, R^2 = 3
    EXPECT_NEAR(set[0].power().g, 4 * kPi * 2, 1e-4f);     // 4 pi I
    EXPECT_NEAR(set.total_power().b, power_sum.b, 1e-4f * power_sum.b);
    std::vector<double> cdf{0};
    for (size_t i = 0; i < set.size(); ++i) {
        EXPECT_NEAR(set.pmf(i), set[i].power().average() / total, 1e-6) << i;
        pmf_sum += set.pmf(i);
        cdf.push_back(cdf.back() + set.pmf(i));
    }
    EXPECT_NEAR(pmf_sum, 1.0, 1e-6);
    EXPECT_EQ(set.pmf(1), 0.0f);
    const int M = 100000;
    for (int k = 0; k < M; ++k) {
        const float u = (float(k) + 0.5f) / M;
        float pmf = -1;
        const size_t i = set.choose(u, pmf);
        ASSERT_LT(i, set.size());
        EXPECT_NE(i, 1u) << "zero-power light chosen";
        EXPECT_EQ(pmf, set.pmf(i));
        EXPECT_LE(cdf[i], u + 1e-6);
        EXPECT_GT(cdf[i + 1], u - 1e-6);
    }
}

TEST(LightSet, AllZeroPowerFallsBackToUniform) {
    scene::Scene s;
    scene::Light dark;
    dark.color = Rgb(0.0f);
    s.lights = {dark, dark, dark, dark};
    log::set_quiet(true);
    const LightSet set(s, unit_bounds());
    log::set_quiet(false);
    float pmf = 0;
    for (size_t i = 0; i < 4; ++i) EXPECT_NEAR(set.pmf(i), 0.25f, 1e-7f);
    EXPECT_EQ(set.choose(0.6f, pmf), 2u);
    EXPECT_NEAR(pmf, 0.25f, 1e-7f);
}

TEST(LightSet, BadReferencesAndNonPhysicalAttenuation) {
    scene::Scene s;
    scene::Light area;
    area.kind = scene::Light::Kind::Area;
    area.shape = 2;
    s.lights.push_back(area);
    EXPECT_THROW(LightSet(s, unit_bounds()), InputError);

    scene::Scene t;
    scene::Light p;
    p.attenuation = {1, 0, 0};
    t.lights.push_back(p);
    log::set_quiet(true);
    const int before = log::warning_count();
    const LightSet physical(t, unit_bounds());
    EXPECT_EQ(log::warning_count() - before, 0);  // the .scn loader warns, once, with the location
    log::set_quiet(false);
    // The default colour, RGB white, read as an illuminant: I(lambda) / d^2 without the .scn terms.
    const Wavelengths& lambda = spectral::fixed_lambda();
    const Spectrum I = spectral::emitted(Rgb(1.0f), lambda);
    EXPECT_TRUE(spectral::spectra_near(physical[0].sample_Li({0, 2, 0}, {}, lambda).L, I * 0.25f, 1e-6));
    const LightSet legacy(t, unit_bounds(), {.legacy_attenuation = true});
    EXPECT_TRUE(spectral::spectra_near(legacy[0].sample_Li({0, 2, 0}, {}, lambda).L, I, 1e-6));
}

TEST(Distribution1D, DiscreteAndContinuous) {
    const Distribution1D d({1, 0, 3, 0, 0, 6});
    EXPECT_NEAR(d.total(), 10, 1e-9);
    const float expected[] = {0.1f, 0, 0.3f, 0, 0, 0.6f};
    std::vector<int> hits(6, 0);
    const int M = 10000;
    float last_remap = -1;
    size_t last = 0;
    for (int k = 0; k < M; ++k) {
        float pmf = 0, remap = 0;
        const size_t i = d.sample_discrete((float(k) + 0.5f) / M, &pmf, &remap);
        ++hits[i];
        EXPECT_EQ(pmf, d.pmf(i));
        ASSERT_GE(remap, 0.0f);
        ASSERT_LT(remap, 1.0f);
        if (i == last) {
            EXPECT_GT(remap, last_remap);  // monotone within a bin
        }
        last = i;
        last_remap = remap;
    }
    for (size_t i = 0; i < 6; ++i) {
        EXPECT_NEAR(d.pmf(i), expected[i], 1e-7f);
        EXPECT_NEAR(hits[i], expected[i] * M, 1.0);
    }
    // Continuous density integrates to 1 and matches the sample's pdf.
    double integral = 0;
    for (int k = 0; k < 600; ++k) integral += d.pdf_continuous((k + 0.5f) / 600) / 600;
    EXPECT_NEAR(integral, 1.0, 1e-6);
    float pdf = 0;
    const float x = d.sample_continuous(0.95f, &pdf);
    EXPECT_NEAR(pdf, d.pdf_continuous(x), 1e-6f);
    EXPECT_GE(x, 5.0f / 6.0f);  // the last bin holds the top 60%

    const Distribution1D zero({0, 0, 0, 0});
    EXPECT_EQ(zero.total(), 0);
    EXPECT_NEAR(zero.pmf(3), 0.25f, 1e-7f);
    EXPECT_EQ(zero.sample_discrete(0.99f), 3u);
}

// One bin (no search; its width of exactly 1 needs no division): the pmf is 1 and u comes back as
// it went in, clamped below 1, with a weight of any size or none.
TEST(Distribution1D, OneBinReturnsUUnchanged) {
    for (float w : {0.0f, 1e-30f, 0.37f, 5e20f}) {
        const Distribution1D d({w});
        const float us[] = {0.0f, 1e-9f, 0.25f, 0.5f, 0.7316f, std::nextafter(1.0f, 0.0f), 1.0f};
        for (float u : us) {
            float pmf = 0, remap = -1;
            EXPECT_EQ(d.sample_discrete(u, &pmf, &remap), 0u);
            EXPECT_EQ(pmf, 1.0f);
            EXPECT_EQ(remap, std::min(u, std::nextafter(1.0f, 0.0f))) << w << " " << u;
        }
    }
}

// The index search of sample_discrete (edges counted for up to 16 bins, a binary search above)
// against a binary search over cdf(): the same bin for every u, the edges themselves and their
// float neighbours included, with empty bins anywhere and bins of very different widths.
TEST(Distribution1D, EverySearchFindsTheBinarySearchsBin) {
    Sampler rng(17);
    int checked = 0;
    for (size_t n = 2; n <= 40; ++n) {
        for (int trial = 0; trial < 6; ++trial) {
            std::vector<float> w(n);
            for (float& v : w) v = rng.next() < 0.25f ? 0.0f : std::ldexp(rng.next(), -int(rng.next() * 20));
            const Distribution1D d(w);
            std::vector<double> cdf(n + 1);
            for (size_t i = 0; i <= n; ++i) cdf[i] = d.cdf(i);
            const auto reference = [&](float u) {
                const double x = std::clamp(double(u), 0.0, std::nextafter(1.0, 0.0));
                size_t i = size_t(std::upper_bound(cdf.begin() + 1, cdf.end(), x) - (cdf.begin() + 1));
                if (i >= n) i = n - 1;
                while (i > 0 && cdf[i + 1] - cdf[i] <= 0) --i;
                return i;
            };
            std::vector<float> us = {0.0f, 1.0f, std::nextafter(1.0f, 0.0f)};
            for (size_t i = 1; i < n; ++i) {
                const float e = float(cdf[i]);
                us.insert(us.end(), {e, std::nextafter(e, 0.0f), std::nextafter(e, 1.0f)});
            }
            for (int k = 0; k < 200; ++k) us.push_back(rng.next());
            for (float u : us) {
                ASSERT_EQ(d.sample_discrete(u), reference(u)) << n << " bins, u = " << u;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 50000);
}

TEST(Distribution2D, PdfIntegratesAndMatchesHistogram) {
    const int nu = 5, nv = 3;
    std::vector<float> f(nu * nv);
    for (int k = 0; k < nu * nv; ++k) f[size_t(k)] = float((k * 7) % 5);  // includes zeros
    const Distribution2D d(f, nu, nv);
    double sum_f = 0, integral = 0;
    for (float v : f) sum_f += v;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) integral += d.pdf({(i + 0.5f) / nu, (j + 0.5f) / nv}) / (nu * nv);
    EXPECT_NEAR(integral, 1.0, 1e-5);
    Sampler rng(2);
    std::vector<int> count(f.size(), 0);
    const int N = 60000;
    for (int n = 0; n < N; ++n) {
        float pdf = 0;
        const Vec2 uv = d.sample(rng.next2(), &pdf);
        EXPECT_NEAR(pdf, d.pdf(uv), 1e-5f * pdf);
        ++count[size_t(std::min(int(uv.y * nv), nv - 1) * nu + std::min(int(uv.x * nu), nu - 1))];
    }
    for (size_t k = 0; k < f.size(); ++k) {
        const double p = f[k] / sum_f;
        EXPECT_NEAR(count[k], N * p, 5 * std::sqrt(N * p * (1 - p)) + 1e-9) << k;
    }
}

}  // namespace
}  // namespace phos::shading
