// Tests of pbrt-v4's hair BxDF (shading/hair_bxdf.h, Chiang et al. 2016): the white furnace (with
// sigma_a = 0 the integral of f |cos| over the sphere is 1 for every wo and h, by quadrature in the
// fibre's angles), the integral equals albedo() with absorption, pdf() integrates to 1, sample()'s
// directions are distributed as pdf() (chi-square, tests/support/chi_square.h), sample's f, pdf and
// weight agree with f() and pdf() (weight 1 for a lossless fibre), the mirror symmetry of the
// fibre's cross-section and the reciprocity the model has, the colour parameterisations
// (Chiang et al.'s eq. 9 and its inverse; the colour it asks for is what a semi-infinite volume of
// such fibres reflects, by a random walk; the melanin coefficients), and finite values at the edges.
#include "shading/hair_bxdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <vector>

#include "core/frame.h"
#include "core/rng.h"
#include "shading/bsdf.h"
#include "spectrum/rgb_spectrum.h"
#include "support/chi_square.h"

namespace phos::shading {
namespace {

bool verbose() { return std::getenv("PHOS_TEST_VERBOSE") != nullptr; }

const Wavelengths& lambda() {
    static const Wavelengths w = Wavelengths::visible(0.37f);
    return w;
}

// A direction from the fibre's angles: theta from the normal plane towards +x (the fibre), phi
// around it from +y towards +z (hair_bxdf.h's frame).
Vec3 hair_dir(double theta, double phi) {
    return Vec3(float(std::sin(theta)), float(std::cos(theta) * std::cos(phi)),
                float(std::cos(theta) * std::sin(phi)));
}

HairBxdf make(float h, float beta_m, float beta_n, HairAbsorption sigma_a = {}, float alpha = 2.0f) {
    HairParams p;
    p.h = h;
    p.beta_m = beta_m;
    p.beta_n = beta_n;
    p.alpha_degrees = alpha;
    p.sigma_a = sigma_a;
    return HairBxdf(p);
}

// The integral over the sphere of g(w), in the fibre's angles (d omega = cos theta d theta d phi):
// the midpoint rule in both, n_theta x n_phi cells (phi is periodic; in theta the integrands vanish
// at the poles), fine enough for lobes of width sqrt(v) and s (beta >= 0.1).
double integrate_fibre(const std::function<double(Vec3)>& g, int n_theta, int n_phi) {
    const double dt = M_PI / n_theta, dp = 2 * M_PI / n_phi;
    double acc = 0;
    for (int i = 0; i < n_theta; ++i) {
        const double theta = -M_PI / 2 + (i + 0.5) * dt, c = std::cos(theta);
        double row = 0;
        for (int j = 0; j < n_phi; ++j) row += g(hair_dir(theta, -M_PI + (j + 0.5) * dp));
        acc += row * c;
    }
    return acc * dt * dp;
}

struct Case {
    float beta_m, beta_n, h;
    Vec3 wo;
};

std::vector<Case> furnace_cases() {
    const Vec3 a = normalize(Vec3(0.3f, 0.5f, 0.81f)), b = normalize(Vec3(-0.85f, 0.2f, -0.45f));
    const Vec3 grazing = normalize(Vec3(0.97f, -0.1f, 0.2f));
    return {{0.1f, 0.1f, 0.35f, a}, {0.1f, 0.7f, -0.8f, b},       {0.3f, 0.3f, 0.0f, a},
            {0.3f, 0.3f, 0.95f, b}, {0.3f, 0.3f, -0.5f, grazing}, {0.7f, 0.1f, 0.6f, grazing},
            {1.0f, 1.0f, -0.2f, a}};
}

TEST(HairBxdf, WhiteFurnaceIsOneForEveryWoAndH) {
    // sigma_a = 0: A_0..A_3 sum to 1 (the geometric series is summed exactly) and M_p, N_p are
    // normalised, so the integral is 1 up to float rounding and the quadrature (~1e-4 here).
    for (const Case& c : furnace_cases()) {
        const HairBxdf hair = make(c.h, c.beta_m, c.beta_n);
        const int n_phi = c.beta_n < 0.2f ? 1024 : 256;
        const double e = integrate_fibre(
            [&](Vec3 wi) { return double(hair.f(c.wo, wi, lambda())[0]) * std::fabs(wi.z); }, 768, n_phi);
        EXPECT_NEAR(e, 1.0, 5e-4) << "beta_m " << c.beta_m << " beta_n " << c.beta_n << " h " << c.h;
        if (verbose()) std::printf("furnace bm %g bn %g h %g: %.6f\n", c.beta_m, c.beta_n, c.h, e);
        const Rgb a = hair.albedo(c.wo);
        EXPECT_NEAR(a.r, 1.0f, 1e-5f);
        EXPECT_NEAR(a.b, 1.0f, 1e-5f);
    }
}

TEST(HairBxdf, WhiteFurnaceAveragedOverHByMonteCarlo) {
    // pbrt-v4's own test (bsdfs_test.cpp, Hair.WhiteFurnace): uniform sphere directions, h
    // stratified over the fibre, beta from 0.1 to 0.9; pbrt accepts [0.95, 1.05]. With the
    // Sampler's 200k samples per case the estimate's standard error is under 1 % for the
    // sharpest lobes, so 4 % is more than 4 standard errors.
    const Vec3 wo = normalize(Vec3(0.4f, -0.3f, 0.85f));
    for (float bm : {0.1f, 0.5f, 0.9f})
        for (float bn : {0.1f, 0.5f, 0.9f}) {
            Sampler rng(42, uint64_t(bm * 10), uint64_t(bn * 10));
            const int n = 200000;
            double sum = 0;
            for (int i = 0; i < n; ++i) {
                const float h = -1 + 2 * (float(i) + 0.5f) / float(n);
                const HairBxdf hair = make(h, bm, bn);
                const Vec2 u = rng.next2();
                const float z = 1 - 2 * u.x, r = std::sqrt(std::max(0.0f, 1 - z * z));
                const Vec3 wi(r * std::cos(2 * kPi * u.y), r * std::sin(2 * kPi * u.y), z);
                sum += double(hair.f(wo, wi, lambda())[0]) * std::fabs(wi.z) * 4 * M_PI;
            }
            EXPECT_NEAR(sum / n, 1.0, 0.04) << bm << " " << bn;
            if (verbose()) std::printf("furnace MC bm %g bn %g: %.5f\n", bm, bn, sum / n);
        }
}

TEST(HairBxdf, IntegralWithAbsorptionEqualsAlbedo) {
    // A grey sigma_a is flat over wavelengths, so f at any wavelength integrates to the RGB
    // albedo() (the sum of the A_p), which is < 1 and decreases with sigma_a.
    const Vec3 wo = normalize(Vec3(0.2f, 0.6f, -0.77f));
    float previous = 1;
    for (float sa : {0.1f, 0.5f, 2.0f}) {
        const HairBxdf hair = make(0.4f, 0.3f, 0.3f, HairAbsorption::of_sigma_a(Rgb(sa)));
        const double e = integrate_fibre(
            [&](Vec3 wi) { return double(hair.f(wo, wi, lambda())[2]) * std::fabs(wi.z); }, 512, 256);
        const float a = hair.albedo(wo).g;
        EXPECT_NEAR(e, a, 5e-4) << sa;
        if (verbose()) std::printf("albedo sigma_a %g: integral %.6f albedo %.6f\n", sa, e, a);
        EXPECT_LT(a, previous);
        previous = a;
    }
}

TEST(HairBxdf, PdfIntegratesToOne) {
    const HairAbsorption brown = HairAbsorption::of_concentration(1.3f, 0.2f);
    for (const Case& c : furnace_cases()) {
        const HairBxdf hair = make(c.h, c.beta_m, c.beta_n, brown);
        const int n_phi = c.beta_n < 0.2f ? 1024 : 256;
        const double e = integrate_fibre([&](Vec3 wi) { return double(hair.pdf(c.wo, wi)); }, 768, n_phi);
        EXPECT_NEAR(e, 1.0, 5e-4) << "beta_m " << c.beta_m << " beta_n " << c.beta_n << " h " << c.h;
        if (verbose()) std::printf("pdf bm %g bn %g h %g: %.6f\n", c.beta_m, c.beta_n, c.h, e);
    }
}

TEST(HairBxdf, SampledDirectionsMatchPdfByChiSquare) {
    const HairAbsorption auburn = HairAbsorption::of_reflectance(Rgb(0.6f, 0.3f, 0.15f), 0.3f);
    struct C {
        float beta_m, beta_n, h;
        Vec3 wo;
    };
    const C cases[] = {{0.3f, 0.3f, 0.3f, normalize(Vec3(0.3f, 0.5f, 0.81f))},
                       {0.2f, 0.6f, -0.7f, normalize(Vec3(-0.6f, -0.2f, 0.77f))},
                       {0.6f, 0.2f, 0.9f, normalize(Vec3(0.1f, 0.9f, -0.42f))}};
    for (const C& c : cases) {
        const HairBxdf hair = make(c.h, c.beta_m, c.beta_n, auburn);
        test::DirectionHistogram hist(36, 72, M_PI);
        Sampler rng(7);
        const int n = 120000;
        for (int i = 0; i < n; ++i) {
            const auto s = hair.sample(c.wo, rng.next(), rng.next2(), lambda());
            if (s)
                hist.add(s->wi);
            else
                hist.add_residual();
        }
        hist.total = n;
        const auto r =
            test::chi_square(hist.counts, hist.expected([&](Vec3 wi) { return double(hair.pdf(c.wo, wi)); }));
        EXPECT_TRUE(r.passed) << "beta_m " << c.beta_m << " h " << c.h << ": " << r.detail;
        if (verbose()) std::printf("chi2 bm %g h %g: %s\n", c.beta_m, c.h, r.detail.c_str());
    }
}

TEST(HairBxdf, SampleAgreesWithFAndPdf) {
    const HairAbsorption brown = HairAbsorption::of_concentration(1.3f, 0);
    Sampler rng(11);
    int lossless = 0;
    for (int i = 0; i < 4000; ++i) {
        const bool white = i % 2 == 0;
        const HairBxdf hair = make(-1 + 2 * rng.next(), 0.05f + 0.95f * rng.next(),
                                   0.05f + 0.95f * rng.next(), white ? HairAbsorption() : brown);
        const Vec2 uo = rng.next2();
        const float z = 1 - 2 * uo.x, r = std::sqrt(std::max(0.0f, 1 - z * z));
        const Vec3 wo(r * std::cos(2 * kPi * uo.y), r * std::sin(2 * kPi * uo.y), z);
        const auto s = hair.sample(wo, rng.next(), rng.next2(), lambda());
        ASSERT_TRUE(s.has_value());
        ASSERT_NEAR(length(s->wi), 1.0f, 1e-5f);
        ASSERT_EQ(s->pdf, hair.pdf(wo, s->wi));
        // The direction and its density do not depend on the path's wavelengths (bsdf.h).
        const float uc2 = rng.next();
        const Vec2 u2 = rng.next2();
        const auto a = hair.sample(wo, uc2, u2, lambda());
        const auto b = hair.sample(wo, uc2, u2, Wavelengths::visible(0.81f));
        ASSERT_TRUE(a && b);
        ASSERT_TRUE(a->wi == b->wi && a->pdf == b->pdf);
        const Spectrum f = hair.f(wo, s->wi, lambda());
        ASSERT_TRUE(s->weight.is_finite());
        EXPECT_EQ(s->flags & kGlossy, uint32_t(kGlossy));
        EXPECT_EQ(bool(s->flags & kTransmission), s->wi.z * wo.z < 0);
        for (int k = 0; k < spectrum::kSpectrumSamples; ++k) {
            ASSERT_EQ(s->f[k], f[k]);
            if (std::fabs(s->wi.z) > 1e-3f) {
                ASSERT_NEAR(s->weight[k], f[k] * std::fabs(s->wi.z) / s->pdf, 1e-4f * s->weight[k] + 1e-7f);
            }
            // A lossless fibre samples its f exactly: every weight is 1 (pbrt's SamplingWeights).
            if (white) {
                ASSERT_NEAR(s->weight[k], 1.0f, 1e-4f);
            }
        }
        lossless += white;
    }
    EXPECT_EQ(lossless, 2000);
}

TEST(HairBxdf, MirrorSymmetryOfTheCrossSection) {
    // Reflecting the fibre's cross-section (h -> -h, and z -> -z for both directions, so
    // phi -> -phi) maps the model onto itself.
    const HairAbsorption sa = HairAbsorption::of_sigma_a(Rgb(0.3f, 0.6f, 1.2f));
    Sampler rng(5);
    for (int i = 0; i < 200; ++i) {
        const float h = -1 + 2 * rng.next();
        const HairBxdf a = make(h, 0.3f, 0.4f, sa), b = make(-h, 0.3f, 0.4f, sa);
        const Vec3 wo = hair_dir(M_PI * (rng.next() - 0.5), 2 * M_PI * rng.next());
        const Vec3 wi = hair_dir(M_PI * (rng.next() - 0.5), 2 * M_PI * rng.next());
        const Vec3 mo(wo.x, wo.y, -wo.z), mi(wi.x, wi.y, -wi.z);
        const Spectrum fa = a.f(wo, wi, lambda()), fb = b.f(mo, mi, lambda());
        for (int k = 0; k < spectrum::kSpectrumSamples; ++k) ASSERT_NEAR(fa[k], fb[k], 1e-4f * fa[k] + 1e-7f);
        ASSERT_NEAR(a.pdf(wo, wi), b.pdf(mo, mi), 1e-4f * a.pdf(wo, wi) + 1e-7f);
    }
}

TEST(HairBxdf, ReciprocalWhereTheModelIs) {
    // A_p read theta_o only and the scales tilt wo's cone, so f(wo, wi) |wi.z| is not symmetric
    // in general (nor in pbrt). It is where both hold still: without tilt (alpha = 0) and for
    // directions of equal |theta|, swapping wo and wi equals mirroring h:
    // f_h(wo, wi) |wi.z| = f_{-h}(wi, wo) |wo.z|; at h = 0 plain reciprocity.
    const HairAbsorption sa = HairAbsorption::of_sigma_a(Rgb(0.2f, 0.5f, 0.9f));
    Sampler rng(3);
    for (int i = 0; i < 300; ++i) {
        const float h = i % 3 == 0 ? 0.0f : -1 + 2 * rng.next();
        const HairBxdf a = make(h, 0.2f + 0.7f * rng.next(), 0.2f + 0.7f * rng.next(), sa, 0.0f);
        HairBxdf mirrored = a;
        mirrored.set_h(-h);
        const double theta = M_PI * (rng.next() - 0.5);
        const Vec3 wo = hair_dir(theta, 2 * M_PI * rng.next());
        const Vec3 wi = hair_dir(rng.next() < 0.5 ? theta : -theta, 2 * M_PI * rng.next());
        const Spectrum x = a.f(wo, wi, lambda()) * std::fabs(wi.z);
        const Spectrum y = mirrored.f(wi, wo, lambda()) * std::fabs(wo.z);
        for (int k = 0; k < spectrum::kSpectrumSamples; ++k) ASSERT_NEAR(x[k], y[k], 2e-4f * x[k] + 1e-7f);
    }
}

TEST(HairAbsorption, ReflectanceInversionIsChiangEq9) {
    for (float bn : {0.01f, 0.3f, 0.7f, 1.0f})
        for (float c : {0.05f, 0.3f, 0.62f, 0.9f, 1.0f}) {
            const float sa = hair_sigma_a_from_reflectance(c, bn);
            EXPECT_NEAR(hair_reflectance_from_sigma_a(sa, bn), c, 2e-6f) << c << " " << bn;
        }
    // The published polynomial at beta_n = 0.3: D = 5.969 - 0.0645 + 0.22788 - 0.28971 + 0.0451494
    // + 0.000595 = 5.88823; c = 0.5 gives (ln 0.5 / D)^2.
    EXPECT_NEAR(hair_sigma_a_from_reflectance(0.5f, 0.3f), std::pow(std::log(0.5) / 5.88823, 2), 1e-6);
    EXPECT_EQ(hair_sigma_a_from_reflectance(1.0f, 0.3f), 0.0f);
    EXPECT_TRUE(std::isinf(hair_sigma_a_from_reflectance(0.0f, 0.3f)));
    // Darker colours absorb more; the single-fibre albedo falls with them.
    const Vec3 wo = normalize(Vec3(0.1f, 0.7f, 0.7f));
    float previous_sa = -1, previous_albedo = 2;
    for (float c : {0.9f, 0.6f, 0.3f, 0.1f}) {
        const HairAbsorption a = HairAbsorption::of_reflectance(Rgb(c), 0.3f);
        EXPECT_GT(a.rgb().r, previous_sa);
        previous_sa = a.rgb().r;
        const float albedo = make(0.2f, 0.3f, 0.3f, a).albedo(wo).r;
        EXPECT_LT(albedo, previous_albedo);
        previous_albedo = albedo;
    }
    // Per wavelength as pbrt-v4: the colour's albedo spectrum inverted at each wavelength (a grey
    // colour is flat, so every wavelength gets eq. 9 of the grey value).
    const Spectrum s = HairAbsorption::of_reflectance(Rgb(0.4f), 0.3f).at(lambda());
    for (int k = 0; k < spectrum::kSpectrumSamples; ++k)
        EXPECT_NEAR(s[k], hair_sigma_a_from_reflectance(0.4f, 0.3f), 1e-6f);
    const Rgb colour(0.7f, 0.4f, 0.2f);
    const Spectrum c = spectrum::RgbSpectrum(colour, spectrum::RgbSpectrum::Use::Albedo).sample(lambda());
    const Spectrum t = HairAbsorption::of_reflectance(colour, 0.5f).at(lambda());
    for (int k = 0; k < spectrum::kSpectrumSamples; ++k)
        EXPECT_NEAR(t[k], hair_sigma_a_from_reflectance(c[k], 0.5f), 1e-5f);
}

// The multiple-scattering albedo of a semi-infinite medium of isotropically oriented fibres
// (unit mean free path; the fibre a ray meets oriented with density proportional to the sine of
// its angle to the ray, its projected width; h uniform across it), lit uniformly from above: the
// colour a large hair volume shows under white light, what Chiang et al. 2016 fitted eq. 9 to
// (with beta_m = 0.3; other beta_m shift it: 0.8 gives 0.27 for 0.2).
double hair_volume_albedo(float colour, float beta_m, float beta_n, int paths, uint64_t seed) {
    HairParams p;
    p.beta_m = beta_m;
    p.beta_n = beta_n;
    p.sigma_a = HairAbsorption::of_reflectance(Rgb(colour), beta_n);
    HairBxdf hair(p);
    Sampler rng(seed);
    const auto sphere = [&] {
        const Vec2 u = rng.next2();
        const float z = 1 - 2 * u.x, r = std::sqrt(std::max(0.0f, 1 - z * z));
        return Vec3(r * std::cos(2 * kPi * u.y), r * std::sin(2 * kPi * u.y), z);
    };
    double sum = 0;
    for (int i = 0; i < paths; ++i) {
        const Vec2 u = rng.next2();  // cosine-weighted incidence
        const float sin_t = std::sqrt(1 - u.x);
        Vec3 d(sin_t * std::cos(2 * kPi * u.y), sin_t * std::sin(2 * kPi * u.y), -std::sqrt(u.x));
        float z = 0, w = 1;
        for (int event = 0; event < 10000; ++event) {
            z += d.z * -std::log(1 - rng.next());
            if (z > 0) {
                sum += w;
                break;
            }
            Vec3 t;
            do t = sphere();
            while (rng.next() >= std::sqrt(std::max(0.0f, 1 - dot(t, d) * dot(t, d))));
            const Vec3 n = normalize(cross(t, d));
            const Frame frame(t, cross(n, t), n);
            hair.set_h(-1 + 2 * rng.next());
            const auto s = hair.sample(frame.to_local(-d), rng.next(), rng.next2(), lambda());
            if (!s) break;
            w *= s->weight[0];  // a grey colour: every wavelength alike
            d = normalize(frame.to_world(s->wi));
            if (w < 0.01f) {  // Russian roulette
                if (rng.next() < 0.5f) break;
                w *= 2;
            }
        }
    }
    return sum / paths;
}

TEST(HairAbsorption, ReflectanceIsTheColourOfAHairVolume) {
    // Measured with 10^4 paths: 0.217, 0.495, 0.79 for 0.2, 0.5, 0.8 at beta_n = 0.3 (0.124, 0.31,
    // 0.693, 0.885 for 0.1, 0.3, 0.7, 0.9); 0.19, 0.48, 0.78 at beta_n = 0.8. Within 0.04 with 3000
    // paths (standard error under 0.01).
    for (float bn : {0.3f, 0.8f})
        for (float c : {0.2f, 0.5f, 0.8f}) {
            const double a = hair_volume_albedo(c, 0.3f, bn, 3000, uint64_t(c * 100 + bn * 10));
            EXPECT_NEAR(a, c, 0.04) << "colour " << c << " beta_n " << bn;
            if (verbose()) std::printf("volume colour %g beta_n %g: %.4f\n", c, bn, a);
        }
}

TEST(HairAbsorption, MelaninConcentrations) {
    // Chiang et al. 2016, sec. 4.1: eumelanin (0.419, 0.697, 1.37), pheomelanin (0.187, 0.4, 1.05).
    const Rgb e = hair_sigma_a_from_concentration(1, 0), p = hair_sigma_a_from_concentration(0, 1);
    EXPECT_FLOAT_EQ(e.r, 0.419f);
    EXPECT_FLOAT_EQ(e.g, 0.697f);
    EXPECT_FLOAT_EQ(e.b, 1.37f);
    EXPECT_FLOAT_EQ(p.r, 0.187f);
    EXPECT_FLOAT_EQ(p.g, 0.4f);
    EXPECT_FLOAT_EQ(p.b, 1.05f);
    const Rgb mix = hair_sigma_a_from_concentration(2, 0.5f);
    EXPECT_FLOAT_EQ(mix.g, 2 * 0.697f + 0.5f * 0.4f);
    const Rgb clamped = hair_sigma_a_from_concentration(-1, 1);
    EXPECT_FLOAT_EQ(clamped.r, 0.187f);
    // pbrt-v4's default hair (eumelanin 1.3) as an unbounded spectrum.
    const HairAbsorption d = HairAbsorption::of_concentration(kHairDefaultEumelanin, 0);
    EXPECT_FLOAT_EQ(d.rgb().b, 1.3f * 1.37f);
    const Spectrum want =
        spectrum::RgbSpectrum(d.rgb(), spectrum::RgbSpectrum::Use::Unbounded).sample(lambda());
    EXPECT_EQ(d.at(lambda()), want);
}

TEST(HairBxdf, LongitudinalVariancesAreChiangEq7) {
    // v_0 = (0.726 b + 0.812 b^2 + 3.7 b^20)^2, v_1 = v_0 / 4, v_2 = v_3 = 4 v_0.
    const HairBxdf hair = make(0, 0.3f, 0.3f);
    const float v0 = std::pow(0.726f * 0.3f + 0.812f * 0.09f + 3.7f * std::pow(0.3f, 20.0f), 2.0f);
    EXPECT_NEAR(hair.longitudinal_variance(0), v0, 1e-6f);
    EXPECT_NEAR(hair.longitudinal_variance(1), v0 / 4, 1e-6f);
    EXPECT_NEAR(hair.longitudinal_variance(2), 4 * v0, 1e-6f);
    EXPECT_NEAR(hair.longitudinal_variance(3), 4 * v0, 1e-6f);
    // Clamped to pbrt-v4's [0.01, 1].
    EXPECT_EQ(make(0, 0, 0.3f).longitudinal_variance(0), make(0, 0.01f, 0.3f).longitudinal_variance(0));
}

TEST(HairBxdf, FiniteAtTheEdges) {
    // pbrt's HOnTheEdge case, h = +-1, directions along the fibre, wi in the tangent plane,
    // the roughest and smoothest betas, an opaque colour.
    const Vec3 dirs[] = {Vec3(0.54986966f, 0.03359017f, 0.83457476f),
                         Vec3(-0.37383357f, -0.91920084f, 0.12376696f),
                         Vec3(1, 0, 0),
                         Vec3(-1, 0, 0),
                         Vec3(0, 1, 0),
                         normalize(Vec3(0.6f, 0.8f, 0))};
    for (float h : {-1.0f, -0.999f, 0.0f, 1.0f})
        for (float beta : {0.0f, 0.01f, 1.0f})
            for (const HairAbsorption& sa :
                 {HairAbsorption(), HairAbsorption::of_reflectance(Rgb(0, 0.5f, 1), 0.3f)}) {
                const HairBxdf hair = make(h, beta, beta, sa);
                for (Vec3 wo : dirs) {
                    for (Vec3 wi : dirs) {
                        ASSERT_TRUE(hair.f(wo, wi, lambda()).is_finite()) << h << " " << beta;
                        ASSERT_TRUE(std::isfinite(hair.pdf(wo, wi)));
                    }
                    for (float uc : {0.0f, 0.5f, 0x1.fffffep-1f}) {
                        const auto s = hair.sample(wo, uc, Vec2(0, 0x1.fffffep-1f), lambda());
                        if (s) {
                            ASSERT_TRUE(s->weight.is_finite() && s->f.is_finite()) << h << " " << beta;
                            ASSERT_TRUE(is_finite(s->wi));
                        }
                    }
                }
            }
}

}  // namespace
}  // namespace phos::shading
