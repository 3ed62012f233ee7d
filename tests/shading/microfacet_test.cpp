// Tests of the Trowbridge-Reitz (GGX) distribution, isotropic and anisotropic, and of the BSDF
// lobes pbrt's materials get from it: normalisation of D and of the visible-normal density by
// quadrature, Smith's projected-area identity, the orientation of an anisotropic highlight,
// white-furnace albedos of the rough conductor (sampled against quadrature), reciprocity, the
// smooth limit, a conductor given by its reflectance, and roughness from a texture.
#include "shading/microfacet.h"

#include <gtest/gtest.h>

#include "core/rng.h"
#include "shading/bsdf.h"
#include "spectral_test_util.h"
#include "support/chi_square.h"

namespace phos::shading {
namespace {

using scene::Material;

Vec3 sph(float theta_deg, float phi_deg = 0) {
    const float t = theta_deg * kPi / 180, p = phi_deg * kPi / 180;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

double hemisphere(const std::function<double(Vec3)>& f) {
    return test::integrate_sphere(f, M_PI / 2, 2048, 512);
}

TEST(TrowbridgeReitz, DensityAndVisibleNormalsAreNormalised) {
    for (const auto& [ax, ay] : {std::pair{0.3f, 0.3f}, std::pair{0.1f, 0.5f}, std::pair{0.6f, 0.2f}}) {
        const MicrofacetDistribution d(ax, ay);
        // Projected microfacet area equals the macro surface's: integral of D(m) cos(m) = 1.
        EXPECT_NEAR(hemisphere([&](Vec3 m) { return double(d.D(m)) * m.z; }), 1.0, 2e-3) << ax << " " << ay;
        for (const Vec3 wo : {sph(0), sph(40, 30), sph(75, 120)}) {
            // Smith: the microfacets' projected area towards wo, seen unmasked, is the macro
            // surface's: integral of G1(wo) D(m) max(0, wo.m) dm = cos(wo) (Heitz 2014, eq. 18).
            const double visible =
                hemisphere([&](Vec3 m) { return double(d.G1(wo) * d.D(m) * std::max(0.0f, dot(wo, m))); });
            EXPECT_NEAR(visible, wo.z, 3e-3) << ax << " " << ay << " " << wo.z;
            EXPECT_NEAR(hemisphere([&](Vec3 m) { return double(d.pdf_wm(wo, m)); }), 1.0, 3e-3);
        }
    }
}

TEST(TrowbridgeReitz, EqualAlphasAreTheIsotropicDistribution) {
    const MicrofacetDistribution iso(MicrofacetModel::GGX, 0.35f), aniso(0.35f, 0.35f);
    EXPECT_TRUE(aniso.isotropic());
    for (const Vec3 w : {sph(10, 20), sph(50, 200), sph(85, 300)}) {
        EXPECT_FLOAT_EQ(iso.D(w), aniso.D(w));
        EXPECT_FLOAT_EQ(iso.lambda(w), aniso.lambda(w));
    }
    // An anisotropic distribution's D and Lambda against the isotropic formulas with the alpha
    // of the direction's azimuth (Heitz 2014, eqs. 85-86): along x alpha_x, along y alpha_y.
    const MicrofacetDistribution a(0.2f, 0.6f), along_x(MicrofacetModel::GGX, 0.2f),
        along_y(MicrofacetModel::GGX, 0.6f);
    for (float theta : {15.0f, 45.0f, 80.0f}) {
        EXPECT_NEAR(a.lambda(sph(theta, 0)), along_x.lambda(sph(theta, 0)), 1e-5f);
        EXPECT_NEAR(a.lambda(sph(theta, 90)), along_y.lambda(sph(theta, 90)), 1e-5f);
        // D at azimuth 0 has the x-alpha's tan term but the normalisation 1 / (alpha_x alpha_y).
        const float t2 = std::tan(theta * kPi / 180) * std::tan(theta * kPi / 180);
        const float c4 = std::pow(std::cos(theta * kPi / 180), 4.0f), e = 1 + t2 / (0.2f * 0.2f);
        EXPECT_NEAR(a.D(sph(theta, 0)), 1 / (kPi * 0.2f * 0.6f * c4 * e * e), 1e-4f * a.D(sph(theta, 0)));
    }
}

Material conductor(float ru, float rv, bool remap = false) {
    Material m;
    m.specular = Rgb(0.9999f);  // F = 1 to four digits at every angle: a white furnace
    m.conductor_from_reflectance = true;
    m.microfacet = true;
    m.roughness_u = ru;
    m.roughness_v = rv;
    m.remap_roughness = remap;
    return m;
}

accel::SurfaceHit flat_hit() {
    accel::SurfaceHit h;
    h.ng = h.ns = {0, 0, 1};
    h.dpdu = {1, 0, 0};
    h.uv = {0.25f, 0.75f};
    return h;
}

Bsdf make(const Material& m, const scene::Scene& scene = scene::Scene{}) {
    return Bsdf(m, flat_hit(), scene);
}

TEST(TrowbridgeReitz, AnisotropicHighlightStretchesAlongTheRougherAxis) {
    const Bsdf b = make(conductor(0.05f, 0.4f));
    const Vec3 wo = sph(0);
    // Wider along y (alpha_v = 0.4) than along x (alpha_u = 0.05 along dpdu = x).
    EXPECT_GT(b.pdf(wo, sph(20, 90)), 50 * b.pdf(wo, sph(20, 0)));
    const Bsdf turned = make(conductor(0.4f, 0.05f));
    EXPECT_GT(turned.pdf(wo, sph(20, 0)), 50 * turned.pdf(wo, sph(20, 90)));
}

TEST(TrowbridgeReitz, ConductorFurnaceSampledEqualsQuadratureAndAtMostOne) {
    const Wavelengths& lambda = spectral::fixed_lambda();
    for (const auto& [ru, rv] :
         {std::pair{0.02f, 0.02f}, std::pair{0.3f, 0.3f}, std::pair{0.1f, 0.6f}, std::pair{1.0f, 1.0f}}) {
        const Bsdf b = make(conductor(ru, rv));
        EXPECT_EQ(b.flags(), uint32_t(kGlossy | kReflection));
        for (float theta : {0.0f, 45.0f, 80.0f}) {
            const Vec3 wo = sph(theta, 30);
            Sampler rng(21);
            const int n = 100000;
            double s = 0, s2 = 0;
            for (int i = 0; i < n; ++i) {
                const auto bs = b.sample(wo, rng.next(), rng.next2(), lambda);
                const double w = bs ? double(bs->weight.average()) : 0;
                s += w;
                s2 += w * w;
            }
            const double mean = s / n, sem = std::sqrt(std::max(0.0, s2 / n - mean * mean) / n);
            const double quad = test::integrate_sphere(
                [&](Vec3 wi) { return double(b.eval(wo, wi, lambda).average()) * std::fabs(wi.z); }, M_PI / 2,
                1024, 256);
            EXPECT_LE(mean, 1 + 5 * sem) << ru << " " << rv << " " << theta;
            // Single scattering loses what multiple scattering would return: little when smooth.
            if (ru < 0.05f && theta < 60) {
                EXPECT_GT(mean, 0.99) << theta;
            }
            // Lost below the horizon and to masking: at alpha 1 and normal incidence the visible
            // normals are cosine-distributed, so half the reflections point down (albedo < 0.5).
            if (theta < 60) {
                EXPECT_GT(mean, 1 - 0.75 * std::max(ru, rv)) << ru << " " << rv << " " << theta;
            }
            if (ru == 1.0f && theta == 0) {
                EXPECT_LT(mean, 0.5) << theta;
            }
            // Quadrature of a sharp lobe needs a fine grid: compare where the grid resolves it.
            if (ru >= 0.1f) {
                EXPECT_NEAR(mean, quad, 5 * sem + 5e-3) << ru << " " << rv << " " << theta;
            }
        }
    }
}

TEST(TrowbridgeReitz, RoughConductorIsReciprocal) {
    Material m = conductor(0.15f, 0.45f);
    m.specular = Rgb(0.7f, 0.5f, 0.2f);
    const Bsdf b = make(m);
    const Wavelengths& lambda = spectral::fixed_lambda();
    Sampler rng(5);
    for (int i = 0; i < 200; ++i) {
        const Vec3 a = sph(89 * rng.next(), 360 * rng.next()), c = sph(89 * rng.next(), 360 * rng.next());
        const Spectrum f1 = b.eval(a, c, lambda), f2 = b.eval(c, a, lambda);
        for (int k = 0; k < spectrum::kSpectrumSamples; ++k) EXPECT_NEAR(f1[k], f2[k], 1e-4f * f1[k] + 1e-7f);
    }
}

TEST(TrowbridgeReitz, SmoothLimitIsAMirrorReflectingTheGivenReflectance) {
    Material m = conductor(0, 0);
    m.specular = Rgb(0.6f);
    const Bsdf b = make(m);
    EXPECT_EQ(b.flags(), uint32_t(kSpecular | kReflection));
    const auto bs = b.sample(sph(0), 0.5f, {0.3f, 0.7f}, spectral::fixed_lambda());
    ASSERT_TRUE(bs);
    EXPECT_NEAR(bs->wi.z, 1, 1e-6f);
    // eta = 1, k = 2 sqrt(r) / sqrt(1 - r) reflects r at normal incidence, more at grazing.
    EXPECT_NEAR(bs->weight.average(), 0.6f, 1e-3f);
    const auto grazing = b.sample(sph(85), 0.5f, {0.3f, 0.7f}, spectral::fixed_lambda());
    ASSERT_TRUE(grazing);
    EXPECT_GT(grazing->weight.average(), 0.8f);
    // Remapped roughness 1e-7 is alpha 3.2e-4, below pbrt's smooth threshold 1e-3: a mirror too.
    EXPECT_EQ(make(conductor(1e-7f, 1e-7f, true)).flags(), uint32_t(kSpecular | kReflection));
}

TEST(TrowbridgeReitz, RoughnessFromATexturePerHit) {
    scene::Scene s;
    scene::Texture smooth, rough;
    smooth.value = Rgb(0.0f);
    rough.value = Rgb(0.25f);
    s.textures = {smooth, rough};
    Material m = conductor(0.5f, 0.5f, true);
    m.roughness_u_texture = m.roughness_v_texture = 0;
    EXPECT_EQ(make(m, s).flags(), uint32_t(kSpecular | kReflection));
    m.roughness_u_texture = m.roughness_v_texture = 1;
    const Bsdf b = make(m, s);
    EXPECT_EQ(b.flags(), uint32_t(kGlossy | kReflection));
    // Remapped 0.25 is alpha 0.5: the same lobe as the untextured material of roughness 0.25.
    const Bsdf same = make(conductor(0.25f, 0.25f, true));
    for (float theta : {10.0f, 30.0f, 60.0f})
        EXPECT_FLOAT_EQ(b.pdf(sph(20), sph(theta, 180)), same.pdf(sph(20), sph(theta, 180)));
}

TEST(TrowbridgeReitz, RegularizationWidensEachAxisToTheExponent) {
    const Bsdf b = make(conductor(0.01f, 0.3f));
    // alpha 0.01 along x is sharper than exponent 100 (alpha 0.14); 0.3 along y is not.
    const Bsdf r = b.regularized(100);
    const Bsdf expected = make(conductor(MicrofacetDistribution::alpha_from_phong(100), 0.3f));
    for (float phi : {0.0f, 45.0f, 90.0f})
        EXPECT_FLOAT_EQ(r.pdf(sph(30), sph(30, 180 + phi)), expected.pdf(sph(30), sph(30, 180 + phi)));
    EXPECT_EQ(b.sharp_lobes(100), uint32_t(kGlossy));  // sqrt(0.01 * 0.3) = 0.055 < 0.14
    EXPECT_EQ(r.sharp_lobes(100), 0u);
}

}  // namespace
}  // namespace phos::shading
