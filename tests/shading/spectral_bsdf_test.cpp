// Spectral BSDF values (shading/bsdf.h): a grey Lambert lobe is the same at every wavelength, a
// coloured one gives its colour back through the film, a dispersive smooth dielectric refracts the
// hero wavelength at that wavelength's own index (and says so), and a conductor with measured
// optical constants reflects each wavelength by its own Fresnel reflectance.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "shading/bsdf.h"
#include "shading/fresnel.h"
#include "spectral_test_util.h"
#include "spectrum/dispersion.h"
#include "spectrum/distribution.h"
#include "spectrum/named_metals.h"

namespace phos::shading {
namespace {

using scene::Material;
using spectral::kSpectrumSamples;

Vec3 sph(float theta_deg, float phi_deg = 0) {
    const float t = theta_deg * kPi / 180, p = phi_deg * kPi / 180;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

Bsdf make(const Material& m) {
    static const scene::Scene empty;
    accel::SurfaceHit h;
    h.ng = h.ns = {0, 0, 1};
    h.dpdu = {1, 0, 0};
    h.uv = {0.5f, 0.5f};
    return Bsdf(m, h, empty);
}

TEST(SpectralBsdf, GreyLambertIsFlatAtEveryWavelength) {
    Material m;
    m.diffuse = Rgb(0.6f);
    const Bsdf b = make(m);
    const float expected = 0.6f * kInvPi;
    Sampler rng(1);
    for (int k = 0; k < 64; ++k) {
        const Wavelengths lambda = spectral::stratified_lambda(k, 64);
        EXPECT_TRUE(spectral::flat_near(b.diffuse_albedo(lambda), 0.6, 1e-7));
        const Vec3 wo = sph(80 * rng.next(), 360 * rng.next()), wi = sph(80 * rng.next(), 360 * rng.next());
        const Spectrum f = b.eval(wo, wi, lambda);
        EXPECT_TRUE(spectral::flat_near(f, expected, 1e-7)) << "lambda " << lambda[0];
        const auto bs = b.sample(wo, rng.next(), rng.next2(), lambda);
        ASSERT_TRUE(bs);
        EXPECT_TRUE(spectral::flat_near(bs->f, expected, 1e-7));
        EXPECT_TRUE(spectral::flat_near(bs->weight, 0.6, 1e-6));  // cosine sampling: weight = kd
        EXPECT_FALSE(bs->dispersive);
    }
}

// A coloured reflectance is the smooth spectrum its RGB gives (rgb_spectrum.h), fitted so that
// under the colour space's white (D65, the Illuminant reading of RGB white) it has that RGB. So the
// BSDF value lit by RGB white, averaged through the film over 4096 stratified wavelength sets, is
// kd / pi. Tolerance 1 %: the exact fit is within 1e-5 of the RGB and 4096 x 4 stratified
// wavelengths integrate these smooth spectra to ~1e-4; a BSDF that ignored the colour (grey, or a
// wrong channel) is off by tens of percent.
TEST(SpectralBsdf, ColouredLambertGivesItsColourThroughTheFilm) {
    for (const Rgb kd : {Rgb(0.7f, 0.3f, 0.05f), Rgb(0.2f, 0.5f, 0.8f), Rgb(0.4f, 0.6f, 0.3f)}) {
        Material m;
        m.diffuse = kd;
        const Bsdf b = make(m);
        const Vec3 wo = sph(30, 20), wi = sph(50, 200);
        // At each wavelength: the upsampled kd over pi.
        for (int k = 0; k < 16; ++k) {
            const Wavelengths lambda = spectral::stratified_lambda(k, 16);
            EXPECT_TRUE(
                spectral::spectra_near(b.eval(wo, wi, lambda), spectral::albedo(kd, lambda) * kInvPi, 1e-6));
        }
        const Rgb colour = spectral::film_colour(
            [&](const Wavelengths& l) { return b.eval(wo, wi, l) * spectral::illuminant(Rgb(1.0f), l); });
        EXPECT_TRUE(spectral::rgb_near(colour, kd * kInvPi, 0.01)) << kd.r << " " << kd.g << " " << kd.b;
    }
}

// SF10 (a dense flint, n from about 1.70 to 1.78 over the visible range) as a smooth dispersive
// dielectric: a sampled refraction is marked dispersive and bends by the hero wavelength's index,
// sin(theta_t) = sin(theta_i) / n(lambda_0), entering from air; a reflection is marked too.
TEST(SpectralBsdf, DispersiveGlassRefractsTheHeroAtItsOwnIndex) {
    const auto sf10 = spectrum::named_glass("glass-SF10");
    ASSERT_TRUE(sf10);
    Material m;
    m.transmission = Rgb(1.0f);
    m.ior = float(sf10->ior(spectrum::kLineD));
    m.ior_spectrum = spectrum::Distribution::sellmeier(*sf10);
    const Bsdf b = make(m);
    EXPECT_TRUE(b.dispersive());
    EXPECT_TRUE(b.is_purely_specular());
    const Vec3 wo = sph(50, 30);
    const double sin_i = std::sin(50 * M_PI / 180);
    std::vector<double> sin_t;
    for (float u : {0.02f, 0.3f, 0.55f, 0.8f, 0.98f}) {
        const Wavelengths lambda = Wavelengths::visible(u);
        const double n = sf10->ior(lambda[0]);
        // u_lobe picks the Fresnel branch (F ~ 0.08 here): high for refraction.
        const auto t = b.sample(wo, 0.99f, Vec2(0.5f, 0.5f), lambda, TransportMode::Radiance);
        ASSERT_TRUE(t);
        EXPECT_TRUE(t->dispersive);
        ASSERT_TRUE(t->flags & kTransmission);
        EXPECT_LT(t->wi.z, 0);
        const double s = std::sqrt(std::max(0.0, 1.0 - double(t->wi.z) * t->wi.z));
        EXPECT_NEAR(s, sin_i / n, 1e-5) << "hero " << lambda[0] << " nm";
        EXPECT_NEAR(t->eta, n, 1e-5);
        // The plane of incidence is kept: wi's tangential part is opposite wo's.
        EXPECT_NEAR(t->wi.x * wo.y - t->wi.y * wo.x, 0.0f, 1e-6f);
        EXPECT_LT(t->wi.x * wo.x + t->wi.y * wo.y, 0.0f);
        // Radiance mode: the hero's weight is kt (1 - F) / (1 - F) / n^2 = 1 / n(lambda_0)^2.
        EXPECT_NEAR(t->weight[0], 1 / (n * n), 1e-5);
        sin_t.push_back(s);
        // The reflected branch depends on the index through F: marked as well, mirror direction.
        const auto r = b.sample(wo, 0.001f, Vec2(0.5f, 0.5f), lambda, TransportMode::Importance);
        ASSERT_TRUE(r);
        EXPECT_TRUE(r->dispersive);
        EXPECT_TRUE(r->flags & kReflection);
        EXPECT_NEAR(length(r->wi - Vec3(-wo.x, -wo.y, wo.z)), 0.0f, 1e-6f);
    }
    // Normal dispersion: shorter heroes are bent more (smaller sin theta_t), and visibly so.
    for (size_t i = 1; i < sin_t.size(); ++i) EXPECT_GT(sin_t[i], sin_t[i - 1]);
    EXPECT_GT(sin_t.back() - sin_t.front(), 5e-3);

    // The same glass without the spectrum is not dispersive.
    Material plain = m;
    plain.ior_spectrum.reset();
    const Bsdf p = make(plain);
    EXPECT_FALSE(p.dispersive());
    const auto ps = p.sample(wo, 0.99f, Vec2(0.5f, 0.5f), spectral::fixed_lambda());
    ASSERT_TRUE(ps);
    EXPECT_FALSE(ps->dispersive);
}

// A thin sheet of SF10 does not bend light, so it is not dispersive in direction: every wavelength
// goes the same way, reflected or straight through, with its own thin-sheet reflectance. The
// branch is chosen at the d line's reflectance, and each wavelength's weight is its own
// coefficient over that probability, so the expected weight per wavelength (over the branch) is
// exactly R(lambda) + T(lambda) = 1 and the reflected weight alone averages to R(lambda).
TEST(SpectralBsdf, ThinDispersiveSheetWeighsEachWavelengthByItsOwnReflectance) {
    const auto sf10 = spectrum::named_glass("glass-SF10");
    ASSERT_TRUE(sf10);
    Material m;
    m.transmission = Rgb(1.0f);
    m.thin = true;
    m.ior = float(sf10->ior(spectrum::kLineD));
    m.ior_spectrum = spectrum::Distribution::sellmeier(*sf10);
    const Bsdf b = make(m);
    const Vec3 wo = sph(70, 10);
    const Wavelengths lambda = Wavelengths::visible(0.13f);
    const float rd = thin_sheet_reflectance(fresnel_dielectric(wo.z, m.ior));
    for (const float ul : {0.25f * rd, 0.5f + 0.5f * rd}) {  // one reflection, one transmission
        const auto s = b.sample(wo, ul, Vec2(0.5f, 0.5f), lambda, TransportMode::Radiance);
        ASSERT_TRUE(s);
        EXPECT_FALSE(s->dispersive);
        const bool reflected = s->flags & kReflection;
        EXPECT_EQ(reflected, ul < rd);
        const Vec3 expected_wi = reflected ? Vec3(-wo.x, -wo.y, wo.z) : -wo;
        EXPECT_NEAR(length(s->wi - expected_wi), 0.0f, 1e-6f);
        for (int i = 0; i < kSpectrumSamples; ++i) {
            const float ri = thin_sheet_reflectance(fresnel_dielectric(wo.z, float(sf10->ior(lambda[i]))));
            const float expected = reflected ? ri / rd : (1 - ri) / (1 - rd);
            EXPECT_NEAR(s->weight[i], expected, 1e-5f) << lambda[i] << " nm";
        }
        // The wavelengths differ in reflectance by more than the tolerance (SF10 is strongly
        // dispersive), so a weight flat over wavelengths would fail above.
        if (reflected) {
            EXPECT_GT(std::fabs(s->weight[0] - s->weight[2]), 1e-3f);
        }
    }
}

// Gold as a mirror with pbrt's measured eta and k: at normal incidence each wavelength reflects
// ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2) of its own constants.
TEST(SpectralBsdf, MeasuredConductorReflectsEachWavelengthByItsFresnel) {
    const auto au = spectrum::named_metal("Au");
    ASSERT_TRUE(au);
    std::vector<float> l, eta, k;
    for (const spectrum::OpticalConstant& c : au->table) {
        l.push_back(c.lambda);
        eta.push_back(c.eta);
        k.push_back(c.k);
    }
    Material m;
    m.specular = Rgb(1.0f);
    m.shininess = Material::kMirrorShininess;
    m.conductor = true;
    // The RGB constants only choose lobes (and hold the colour): gold's, roughly.
    m.conductor_eta = Rgb(0.143f, 0.374f, 1.442f);
    m.conductor_k = Rgb(3.983f, 2.385f, 1.603f);
    m.conductor_eta_spectrum = spectrum::Distribution::tabulated(l, eta);
    m.conductor_k_spectrum = spectrum::Distribution::tabulated(l, k);
    const Bsdf b = make(m);
    ASSERT_TRUE(b.is_purely_specular());
    const Vec3 wo(0, 0, 1);
    float blue = 0, red = 0;
    for (int s = 0; s < 32; ++s) {
        const Wavelengths lambda = spectral::stratified_lambda(s, 32);
        const auto bs = b.sample(wo, 0.5f, Vec2(0.5f, 0.5f), lambda);
        ASSERT_TRUE(bs);
        ASSERT_TRUE(bs->is_specular());
        EXPECT_FALSE(bs->dispersive);
        EXPECT_NEAR(bs->wi.z, 1.0f, 1e-6f);
        for (int i = 0; i < kSpectrumSamples; ++i) {
            const float r = au->normal_reflectance(lambda[i]);
            EXPECT_NEAR(bs->weight[i], r, 1e-4f) << lambda[i] << " nm";
            if (std::fabs(lambda[i] - 450) < 15) blue = r;
            if (std::fabs(lambda[i] - 650) < 15) red = r;
        }
    }
    // Gold: reflects red far better than blue.
    ASSERT_GT(blue, 0.0f);
    EXPECT_GT(red, blue + 0.3f);
}

}  // namespace
}  // namespace phos::shading
