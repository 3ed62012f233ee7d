// Tests of shading::Bsdf: white furnace (albedo) per lobe, sample/pdf/eval consistency with
// chi-square histograms, reciprocity, the light-leak rule, lobe masks and Russian-roulette albedos.
// BSDF values are spectral: the geometric tests use grey materials, whose values are the same at
// every wavelength (spectral_test_util.h), and check every wavelength sample; coloured inputs are
// compared with their upsampled spectra at the same wavelengths.
#include "shading/bsdf.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "core/rng.h"
#include "core/warp.h"
#include "shading/fresnel.h"
#include "shading/material_bsdfs.h"
#include "shading/measured_tabulation.h"
#include "spectral_test_util.h"
#include "support/chi_square.h"

namespace phos::shading {
namespace {

using scene::Material;
using spectral::flat_near;
using spectral::kSpectrumSamples;

// Direction at polar angle theta (degrees, from +z) and azimuth phi (degrees).
Vec3 sph(float theta_deg, float phi_deg = 0) {
    const float t = theta_deg * kPi / 180, p = phi_deg * kPi / 180;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

accel::SurfaceHit flat_hit(Vec3 ng = {0, 0, 1}, Vec3 ns = {0, 0, 1}) {
    accel::SurfaceHit h;
    h.ng = ng;
    h.ns = ns;
    h.dpdu = {1, 0, 0};
    h.uv = {0.5f, 0.5f};
    return h;
}

const scene::Scene& empty_scene() {
    static const scene::Scene s;
    return s;
}

Bsdf make(const Material& m, BsdfOptions o = {}) { return Bsdf(m, flat_hit(), empty_scene(), o); }

Material lambert(float kd) {
    Material m;
    m.diffuse = Rgb(kd);
    return m;
}
Material phong(float ks, float n) {
    Material m;
    m.specular = Rgb(ks);
    m.shininess = n;
    return m;
}
Material glass(float kt, float ior, float n = 1e6f) {
    Material m;
    m.transmission = Rgb(kt);
    m.ior = ior;
    m.transmission_shininess = n;
    return m;
}

// Mean and standard error of the sampled albedo (mean of the weight averaged over the wavelengths;
// each sample at its own stratified wavelengths).
struct Stat {
    double mean = 0, sem = 0;
};
Stat sampled_albedo(const Bsdf& b, Vec3 wo, int n, uint64_t seed,
                    TransportMode mode = TransportMode::Importance, uint32_t mask = ~0u) {
    Sampler rng(seed);
    double s = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
        const float ul = rng.next();
        const Vec2 u = rng.next2();
        const auto bs = b.sample_lobes(mask, wo, ul, u, spectral::stratified_lambda(i, n), mode);
        const double w = bs ? double(bs->weight.average()) : 0.0;
        s += w;
        s2 += w * w;
    }
    Stat st;
    st.mean = s / n;
    st.sem = std::sqrt(std::max(0.0, s2 / n - st.mean * st.mean) / n);
    return st;
}
// Albedo by quadrature of eval |cos| over the sphere (independent of the sampling code), at the
// fixed wavelengths (averaged over them).
double quadrature_albedo(const Bsdf& b, Vec3 wo, TransportMode mode, int nt = 1024, int np = 256) {
    const Wavelengths& lambda = spectral::fixed_lambda();
    return test::integrate_sphere(
        [&](Vec3 wi) { return double(b.eval(wo, wi, lambda, mode).average()) * std::fabs(wi.z); }, M_PI, nt,
        np);
}

// 5 standard errors: a statistical bound that a correct implementation exceeds with probability
// ~6e-7 (and the seeds are fixed, so the outcome is deterministic).
constexpr double kSigmas = 5;

TEST(BsdfFurnace, Lambert) {
    const Bsdf b = make(lambert(1.0f));
    for (float theta : {0.0f, 30.0f, 60.0f, 85.0f, 120.0f, 175.0f}) {  // both sides: two-sided
        const Vec3 wo = sph(theta, 40);
        // Every cosine-sampled weight is exactly kd, at every wavelength.
        Sampler rng(1);
        for (int i = 0; i < 1000; ++i) {
            const auto bs = b.sample(wo, rng.next(), rng.next2(), spectral::stratified_lambda(i, 1000));
            ASSERT_TRUE(bs);
            EXPECT_TRUE(flat_near(bs->weight, 1.0, 1e-5));
        }
        // Uniform-sphere Monte Carlo of eval |cos| / (1/4pi): independent of the sampler.
        Sampler r2(2);
        double s = 0, s2 = 0;
        const int n = 200000;
        for (int i = 0; i < n; ++i) {
            const Vec3 wi = warp::uniform_sphere(r2.next2());
            const Spectrum f = b.eval(wo, wi, spectral::stratified_lambda(i, n));
            ASSERT_TRUE(f.is_flat());  // grey: the same value at every wavelength
            const double v = double(f[0]) * std::fabs(wi.z) * 4 * M_PI;
            s += v;
            s2 += v * v;
        }
        const double mean = s / n, sem = std::sqrt((s2 / n - mean * mean) / n);
        EXPECT_NEAR(mean, 1.0, kSigmas * sem) << theta;
        EXPECT_NEAR(quadrature_albedo(b, wo, TransportMode::Radiance, 512, 64), 1.0, 1e-3) << theta;
    }
}

TEST(BsdfFurnace, PhongNormalIncidenceIsOne) {
    // At normal incidence the lobe axis is the normal, no sample is lost below the horizon and
    // the albedo is (n+2)/(n+1) * E[cos] = (n+2)/(n+1) * (n+1)/(n+2) = 1 exactly.
    for (float n : {0.0f, 1.0f, 10.0f, 100.0f, 1000.0f}) {
        const Bsdf b = make(phong(1.0f, n));
        const Stat st = sampled_albedo(b, Vec3(0, 0, 1), 200000, 3);
        EXPECT_NEAR(st.mean, 1.0, kSigmas * st.sem + 1e-4) << n;
        EXPECT_LE(st.mean, 1.0 + kSigmas * st.sem + 1e-4) << n;
        if (n <= 100) {
            EXPECT_NEAR(quadrature_albedo(b, Vec3(0, 0, 1), TransportMode::Radiance), 1.0, 2e-3) << n;
        }
    }
}

TEST(BsdfFurnace, PhongOblique) {
    // Away from the normal part of the lobe falls below the horizon: albedo < 1, and the sampled
    // estimate agrees with the quadrature of eval.
    for (float n : {1.0f, 10.0f, 100.0f})
        for (float theta : {30.0f, 60.0f, 80.0f}) {
            const Bsdf b = make(phong(1.0f, n));
            const Vec3 wo = sph(theta, 10);
            const Stat st = sampled_albedo(b, wo, 200000, 4);
            const double q = quadrature_albedo(b, wo, TransportMode::Radiance);
            EXPECT_LT(st.mean, 1.0) << n << " " << theta;
            EXPECT_NEAR(st.mean, q, kSigmas * st.sem + 2e-3) << n << " " << theta;
        }
}

TEST(BsdfFurnace, MirrorAndConductor) {
    const Bsdf mirror = make(phong(1.0f, Material::kMirrorShininess));
    EXPECT_TRUE(mirror.is_purely_specular());
    Material cm = phong(1.0f, 1e6f);
    cm.conductor = true;
    cm.conductor_eta = Rgb(0.2f, 0.9f, 1.1f);
    cm.conductor_k = Rgb(3.0f, 2.5f, 2.0f);
    const Bsdf cond = make(cm);
    const Wavelengths& lambda = spectral::fixed_lambda();
    // The RGB eta and k read as unbounded spectra (no measured spectra given).
    const Spectrum eta = spectral::unbounded(cm.conductor_eta, lambda),
                   k = spectral::unbounded(cm.conductor_k, lambda);
    for (float theta : {0.0f, 45.0f, 89.0f, 135.0f}) {
        const Vec3 wo = sph(theta, 70);
        const auto bs = mirror.sample(wo, 0.3f, Vec2(0.2f, 0.7f), lambda);
        ASSERT_TRUE(bs);
        EXPECT_TRUE(bs->is_specular());
        EXPECT_TRUE(flat_near(bs->weight, 1.0, 1e-6));
        // The documented f convention for delta lobes: f |cos| / pdf is the weight.
        EXPECT_TRUE(flat_near(bs->f * (std::fabs(bs->wi.z) / bs->pdf), 1.0, 1e-5));
        const Vec3 expect = reflect(wo, Vec3(0, 0, 1));
        EXPECT_NEAR(length(bs->wi - expect), 0.0f, 1e-5f);
        EXPECT_EQ(mirror.eval(wo, expect, lambda), Spectrum(0.0f));  // deltas are not in eval
        EXPECT_EQ(mirror.pdf(wo, expect), 0.0f);
        const auto cs = cond.sample(wo, 0.5f, Vec2(0.5f, 0.5f), lambda);
        ASSERT_TRUE(cs);
        // Each wavelength reflects by the Fresnel reflectance of its own eta and k.
        for (int i = 0; i < kSpectrumSamples; ++i)
            EXPECT_NEAR(cs->weight[i], fresnel_conductor(std::fabs(wo.z), eta[i], k[i]), 1e-5f) << i;
        // The albedos (Russian roulette, selection) stay RGB: Fresnel of the RGB eta and k.
        const Rgb fc = fresnel_conductor(std::fabs(wo.z), cm.conductor_eta, cm.conductor_k);
        const auto al = cond.lobe_albedos(wo);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(al.specular[c], fc[c], 1e-5f);
    }
}

TEST(BsdfFurnace, SmoothGlassConservesEnergy) {
    // kt = 1 in Importance mode: every sample (reflected or refracted) has weight exactly 1, for
    // entering and leaving rays, including total internal reflection; the reflected fraction is F.
    const Bsdf b = make(glass(1.0f, 1.5f));
    EXPECT_TRUE(b.is_purely_specular());
    for (float theta : {0.0f, 30.0f, 60.0f, 85.0f, 180.0f, 150.0f, 135.0f, 120.0f, 100.0f}) {
        const Vec3 wo = sph(theta, 200);
        const bool entering = wo.z > 0;
        const float eta = entering ? 1.5f : 1 / 1.5f;
        const float F = fresnel_dielectric(std::fabs(wo.z), eta);
        Sampler rng(5);
        const int n = 20000;
        int reflected = 0;
        for (int i = 0; i < n; ++i) {
            const Wavelengths lambda = spectral::stratified_lambda(i, n);
            const auto bs = b.sample(wo, rng.next(), rng.next2(), lambda, TransportMode::Importance);
            ASSERT_TRUE(bs);
            ASSERT_TRUE(flat_near(bs->weight, 1.0, 1e-5));
            ASSERT_FALSE(bs->dispersive);  // a constant index bends every wavelength alike
            if (bs->flags & kReflection) {
                ++reflected;
                EXPECT_NEAR(length(bs->wi - reflect(wo, Vec3(0, 0, 1))), 0.0f, 1e-5f);
            } else {
                // Snell: n1 sin1 = n2 sin2, and the refracted ray crosses to the other side.
                EXPECT_LT(bs->wi.z * wo.z, 0);
                const float sin_o = std::sqrt(1 - wo.z * wo.z), sin_i = std::sqrt(1 - bs->wi.z * bs->wi.z);
                EXPECT_NEAR(sin_o, eta * sin_i, 1e-4f);
                EXPECT_FLOAT_EQ(bs->eta, eta);
                // Radiance mode divides refracted radiance by eta^2.
                const auto br = b.sample(wo, 0.9999f, Vec2(0.5f, 0.5f), lambda, TransportMode::Radiance);
                ASSERT_TRUE(br);
                if (br->flags & kTransmission) {
                    EXPECT_TRUE(flat_near(br->weight, 1 / (eta * eta), 1e-5));
                }
            }
        }
        const double frac = double(reflected) / n, sd = std::sqrt(F * (1 - F) / n);
        EXPECT_NEAR(frac, F, kSigmas * sd + 1e-9) << theta;
        if (!entering && std::sqrt(1 - wo.z * wo.z) > 1 / 1.5f) {
            EXPECT_EQ(reflected, n) << "TIR " << theta;
        }
    }
}

TEST(BsdfFurnace, ThinAndSchlickGlass) {
    Material m = glass(1.0f, 1.5f);
    m.thin = true;
    const Bsdf thin = make(m);
    BsdfOptions schlick;
    schlick.schlick = true;
    const Bsdf sg = make(glass(1.0f, 1.5f), schlick);
    // A thin sheet has air on both faces: the same reflectance from either side (120 degrees is
    // beyond the critical angle of a solid interface seen from inside; a sheet has no such angle).
    for (float theta : {0.0f, 50.0f, 80.0f, 120.0f, 160.0f}) {
        const Vec3 wo = sph(theta, 30);
        const float r = thin_sheet_reflectance(fresnel_dielectric(std::fabs(wo.z), 1.5f));
        Sampler rng(6);
        const int n = 20000;
        int reflected = 0, sreflected = 0;
        for (int i = 0; i < n; ++i) {
            const float ul = rng.next();
            const Wavelengths lambda = spectral::stratified_lambda(i, n);
            const auto bs = thin.sample(wo, ul, Vec2(0.5f, 0.5f), lambda, TransportMode::Radiance);
            ASSERT_TRUE(bs);
            // No 1/eta^2: the ray leaves into the same medium.
            ASSERT_TRUE(flat_near(bs->weight, 1.0, 1e-5));
            if (bs->flags & kReflection) {
                ++reflected;
            } else {
                EXPECT_NEAR(length(bs->wi + wo), 0.0f, 1e-6f);  // straight through
            }
            const auto ss = sg.sample(wo, ul, Vec2(0.5f, 0.5f), lambda, TransportMode::Importance);
            ASSERT_TRUE(ss);
            ASSERT_TRUE(flat_near(ss->weight, 1.0, 1e-5));
            if (ss->flags & kReflection) ++sreflected;
        }
        EXPECT_NEAR(double(reflected) / n, r, kSigmas * std::sqrt(r * (1 - r) / n) + 1e-9) << theta;
        const float rs = fresnel_schlick(wo.z, 1.5f);
        EXPECT_NEAR(double(sreflected) / n, rs, kSigmas * std::sqrt(rs * (1 - rs) / n) + 1e-9) << theta;
    }
}

TEST(BsdfFurnace, FrostedGlassAtMostOne) {
    for (MicrofacetModel model : {MicrofacetModel::GGX, MicrofacetModel::Beckmann})
        for (float n : {3.0f, 20.0f, 300.0f}) {
            BsdfOptions o;
            o.microfacet = model;
            const Bsdf b = make(glass(1.0f, 1.5f, n), o);
            EXPECT_TRUE(b.flags() & kGlossy);
            EXPECT_FALSE(b.flags() & kSpecular);
            for (float theta : {0.0f, 45.0f, 75.0f, 180.0f, 150.0f, 120.0f}) {
                const Vec3 wo = sph(theta, 15);
                const Stat st = sampled_albedo(b, wo, 60000, 7);
                EXPECT_LE(st.mean, 1.0 + kSigmas * st.sem + 1e-4) << n << " " << theta;
                // Single-scattering microfacets lose energy (to paths they ignore), more the
                // rougher they are; a loose sanity bound, 1 - 0.75 alpha, catches gross losses.
                const double alpha = MicrofacetDistribution::alpha_from_phong(n);
                if (std::fabs(wo.z) > 0.5f) {
                    EXPECT_GT(st.mean, 1 - 0.75 * alpha) << n << " " << theta;
                }
            }
        }
}

TEST(BsdfFurnace, CombinedMaterialAtMostOne) {
    Material m;
    m.diffuse = Rgb(0.3f);
    m.specular = Rgb(0.3f);
    m.shininess = 20;
    m.transmission = Rgb(0.4f);
    m.ior = 1.5f;
    m.transmission_shininess = 50;
    Material m2 = m;
    m2.shininess = 1e6f;
    m2.transmission_shininess = 1e6f;
    for (const Material& mat : {m, m2}) {
        const Bsdf b = make(mat);
        for (float theta : {0.0f, 40.0f, 80.0f, 170.0f}) {
            const Stat st = sampled_albedo(b, sph(theta, 100), 100000, 8);
            EXPECT_LE(st.mean, 1.0 + kSigmas * st.sem) << theta;
            EXPECT_GT(st.mean, 0.5) << theta;
        }
    }
}

// Materials with non-delta lobes (some with delta lobes too) for the consistency tests.
struct Case {
    std::string name;
    Material m;
    BsdfOptions o;
};
// A rough conductor (alpha 0.25, eta 0.2, k 3) tabulated as an RGB measured BRDF on a coarse grid,
// built once.
std::shared_ptr<const scene::MeasuredBsdf> tabulated_conductor() {
    static const auto table = [] {
        TabulatedModel model;
        model.alpha_x = model.alpha_y = 0.25f;
        model.eta = [](float) { return 0.2f; };
        model.k = [](float) { return 3.0f; };
        TabulationGrid grid;
        grid.n_theta_i = 6;
        grid.ndf_n = 32;
        grid.vndf_n = grid.n = 16;
        return std::make_shared<const scene::MeasuredBsdf>(tabulate_brdf(model, grid));
    }();
    return table;
}

std::vector<Case> consistency_cases() {
    std::vector<Case> c;
    c.push_back({"lambert", lambert(0.8f), {}});
    c.push_back({"phong1", phong(0.7f, 1), {}});
    c.push_back({"phong20", phong(0.7f, 20), {}});
    c.push_back({"phong100", phong(0.7f, 100), {}});
    Material lp = lambert(0.4f);
    lp.specular = Rgb(0.5f);
    lp.shininess = 30;
    c.push_back({"lambert+phong", lp, {}});
    Material cond = phong(1.0f, 15);
    cond.conductor = true;
    cond.conductor_eta = Rgb(0.2f, 0.9f, 1.1f);
    cond.conductor_k = Rgb(3.0f, 2.5f, 2.0f);
    c.push_back({"conductor-phong", cond, {}});
    c.push_back({"frosted-ggx", glass(0.9f, 1.5f, 20), {}});
    BsdfOptions beck;
    beck.microfacet = MicrofacetModel::Beckmann;
    c.push_back({"frosted-beckmann", glass(0.9f, 1.5f, 40), beck});
    BsdfOptions sch;
    sch.schlick = true;
    c.push_back({"frosted-schlick", glass(1.0f, 1.33f, 8), sch});
    Material dt = lambert(0.3f);
    dt.diffuse_transmission = Rgb(0.5f);
    c.push_back({"lambert+diffuse-transmission", dt, {}});
    Material lm = lambert(0.5f);
    lm.specular = Rgb(0.3f);
    lm.shininess = 1e6f;
    c.push_back({"lambert+mirror", lm, {}});
    Material all = lambert(0.2f);
    all.specular = Rgb(0.2f);
    all.shininess = 10;
    all.transmission = Rgb(0.3f);
    all.ior = 1.5f;
    all.transmission_shininess = 30;
    all.diffuse_transmission = Rgb(0.2f);
    c.push_back({"all-lobes", all, {}});
    // pbrt's materials: Trowbridge-Reitz reflection and refraction, isotropic and anisotropic.
    Material tr_cond;
    tr_cond.specular = Rgb(1.0f);
    tr_cond.conductor = true;
    tr_cond.conductor_eta = Rgb(0.2f, 0.9f, 1.1f);
    tr_cond.conductor_k = Rgb(3.0f, 2.5f, 2.0f);
    tr_cond.microfacet = true;
    tr_cond.roughness_u = tr_cond.roughness_v = 0.3f;
    tr_cond.remap_roughness = false;
    c.push_back({"tr-conductor", tr_cond, {}});
    Material tr_aniso = tr_cond;
    tr_aniso.roughness_u = 0.05f;
    tr_aniso.roughness_v = 0.4f;
    c.push_back({"tr-conductor-anisotropic", tr_aniso, {}});
    Material tr_refl;
    tr_refl.specular = Rgb(0.9f, 0.6f, 0.3f);
    tr_refl.conductor_from_reflectance = true;
    tr_refl.microfacet = true;
    tr_refl.roughness_u = tr_refl.roughness_v = 0.1f;  // remapped: alpha 0.316
    c.push_back({"tr-conductor-reflectance", tr_refl, {}});
    Material tr_glass = glass(1.0f, 1.5f);
    tr_glass.microfacet = true;
    tr_glass.roughness_u = 0.1f;
    tr_glass.roughness_v = 0.35f;
    tr_glass.remap_roughness = false;
    c.push_back({"tr-glass-anisotropic", tr_glass, {}});
    Material tr_coat = lambert(0.5f);  // pbrt's diffuse + microfacet coat without interreflection
    tr_coat.specular = Rgb(0.04f);
    tr_coat.microfacet = true;
    tr_coat.roughness_u = tr_coat.roughness_v = 0.2f;
    c.push_back({"lambert+tr-reflection", tr_coat, {}});
    // pbrt's hair (Chiang et al. 2016): reflection and transmission all around the fibre.
    Material hair;
    hair.hair = true;
    hair.hair_colour = Material::HairColour::SigmaA;
    hair.hair_sigma_a = Rgb(0.2f, 0.6f, 1.4f);
    c.push_back({"hair", hair, {}});
    // pbrt's measured: a rough conductor tabulated on a coarse grid (Dupuy & Jakob's tables).
    Material measured;
    measured.measured = tabulated_conductor();
    c.push_back({"measured", measured, {}});
    return c;
}

TEST(BsdfConsistency, SampleMatchesEvalAndPdf) {
    for (const Case& c : consistency_cases()) {
        const Bsdf b = make(c.m, c.o);
        for (float theta : {25.0f, 70.0f, 160.0f}) {
            const Vec3 wo = sph(theta, 50);
            for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                Sampler rng(9);
                int produced = 0;
                for (int i = 0; i < 5000; ++i) {
                    const Wavelengths lambda = spectral::stratified_lambda(i, 5000);
                    const auto bs = b.sample(wo, rng.next(), rng.next2(), lambda, mode);
                    if (!bs) continue;
                    ++produced;
                    ASSERT_TRUE(bs->weight.is_finite()) << c.name;
                    ASSERT_NEAR(length(bs->wi), 1.0f, 1e-4f);
                    if (bs->is_specular()) continue;
                    const float p = b.pdf(wo, bs->wi);
                    const Spectrum f = b.eval(wo, bs->wi, lambda, mode);
                    ASSERT_NEAR(bs->pdf, p, 1e-3f * p) << c.name << " " << theta;
                    for (int k = 0; k < kSpectrumSamples; ++k) {
                        ASSERT_NEAR(bs->f[k], f[k], 1e-3f * f[k] + 1e-7f) << c.name;
                        ASSERT_NEAR(bs->weight[k], f[k] * std::fabs(bs->wi.z) / p,
                                    2e-3f * bs->weight[k] + 1e-7f)
                            << c.name;
                    }
                    // The sampled branch's flags match the side wi is on.
                    ASSERT_EQ(bool(bs->flags & kTransmission), bs->wi.z * wo.z < 0) << c.name;
                }
                EXPECT_GT(produced, 1000) << c.name << " " << theta;
            }
        }
    }
}

TEST(BsdfConsistency, HistogramsMatchPdf) {
    const bool verbose = std::getenv("PHOS_TEST_VERBOSE") != nullptr;
    for (const Case& c : consistency_cases()) {
        const Bsdf b = make(c.m, c.o);
        for (float theta : {25.0f, 70.0f, 160.0f}) {
            const Vec3 wo = sph(theta, 50);
            test::DirectionHistogram h(36, 72, M_PI);
            Sampler rng(10);
            const int n = 150000;
            for (int i = 0; i < n; ++i) {
                // Directions must not depend on the wavelengths (pdf() has no wavelength argument).
                const auto bs = b.sample(wo, rng.next(), rng.next2(), spectral::stratified_lambda(i, n));
                if (bs && !bs->is_specular()) {
                    h.add(bs->wi);
                } else {
                    h.add_residual();  // delta and rejected samples: the mass pdf() does not hold
                }
            }
            h.total = n;
            const auto r =
                test::chi_square(h.counts, h.expected([&](Vec3 wi) { return double(b.pdf(wo, wi)); }));
            EXPECT_TRUE(r.passed) << c.name << " theta " << theta << ": " << r.detail;
            if (verbose) {
                const auto e = h.expected([&](Vec3 wi) { return double(b.pdf(wo, wi)); });
                std::printf("%s %g: %s residual obs %g exp %g\n", c.name.c_str(), double(theta),
                            r.detail.c_str(), h.counts.back(), e.back());
            }
        }
    }
}

TEST(BsdfReciprocity, ReflectionLobesAreSymmetric) {
    Material cond = phong(0.9f, 25);
    cond.conductor = true;
    cond.conductor_eta = Rgb(0.2f, 0.9f, 1.1f);
    cond.conductor_k = Rgb(3.0f, 2.5f, 2.0f);
    Material lp = lambert(0.4f);
    lp.specular = Rgb(0.5f);
    lp.shininess = 7;
    const std::vector<Material> mats = {lambert(0.7f),     phong(0.8f, 3), phong(0.8f, 60), cond, lp,
                                        glass(1, 1.5f, 15)};
    Sampler rng(12);
    for (const Material& m : mats) {
        const Bsdf b = make(m);
        for (int i = 0; i < 2000; ++i) {
            Vec3 a = warp::cosine_hemisphere(rng.next2()), c = warp::cosine_hemisphere(rng.next2());
            if (i % 2) a.z = -a.z, c.z = -c.z;  // the other side as well
            const Wavelengths lambda = spectral::stratified_lambda(i, 2000);
            for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                const Spectrum f1 = b.eval(a, c, lambda, mode), f2 = b.eval(c, a, lambda, mode);
                for (int k = 0; k < kSpectrumSamples; ++k)
                    ASSERT_NEAR(f1[k], f2[k], 1e-4f * std::max(f1[k], 1.0f));
            }
        }
    }
}

TEST(BsdfReciprocity, FrostedTransmissionAdjoint) {
    // Radiance-mode f(wo, wi) equals Importance-mode f(wi, wo) (the adjoint BTDF), for both
    // microfacet distributions; the radiance BTDF itself is not symmetric (eta^2 factor).
    for (MicrofacetModel model : {MicrofacetModel::GGX, MicrofacetModel::Beckmann}) {
        BsdfOptions o;
        o.microfacet = model;
        const Bsdf b = make(glass(1, 1.5f, 10), o);
        Sampler rng(13);
        int nonzero = 0;
        for (int i = 0; i < 2000; ++i) {
            const Vec3 a = warp::cosine_hemisphere(rng.next2());
            Vec3 c = warp::cosine_hemisphere(rng.next2());
            c.z = -c.z;
            const Wavelengths lambda = spectral::stratified_lambda(i, 2000);
            const Spectrum fr = b.eval(a, c, lambda, TransportMode::Radiance);
            const Spectrum fi = b.eval(c, a, lambda, TransportMode::Importance);
            ASSERT_TRUE(fr.is_flat());  // grey glass: the same at every wavelength
            ASSERT_TRUE(flat_near(fi, fr[0], 1e-3 * fr[0] + 1e-5));
            if (fr[0] > 0) {
                ++nonzero;
                EXPECT_TRUE(flat_near(b.eval(c, a, lambda, TransportMode::Radiance), fr[0] * 1.5f * 1.5f,
                                      2e-3 * fr[0] * 2.25 + 1e-5));
            }
        }
        EXPECT_GT(nonzero, 200);
    }
}

TEST(BsdfSides, GeometricNormalStopsLightLeaks) {
    // Shading normal tilted 30 degrees away from the geometric one.
    const Vec3 ng(0, 0, 1), ns = sph(30, 0);
    const Bsdf b(lambert(1.0f), flat_hit(ng, ns), empty_scene());
    const Vec3 wo = sph(60, 180);  // above both
    const Vec3 wi = sph(100, 0);   // above ns (cos = cos 70 deg) but below ng
    ASSERT_GT(dot(wi, ns), 0);
    ASSERT_LT(dot(wi, ng), 0);
    const Wavelengths& lambda = spectral::fixed_lambda();
    EXPECT_EQ(b.eval(wo, wi, lambda), Spectrum(0.0f));
    EXPECT_EQ(b.pdf(wo, wi), 0.0f);
    EXPECT_TRUE(flat_near(b.eval(wo, sph(10, 0), lambda), kInvPi, 1e-7));
    Sampler rng(14);
    int lost = 0;
    for (int i = 0; i < 20000; ++i) {
        const auto bs = b.sample(wo, rng.next(), rng.next2(), lambda);
        if (!bs) {
            ++lost;
            continue;
        }
        ASSERT_GT(dot(bs->wi, ng), 0);
    }
    EXPECT_GT(lost, 0);  // part of the cosine lobe around ns lies below ng and is rejected

    // Glass: transmission needs opposite sides of ng, reflection the same side.
    const Bsdf g(glass(1.0f, 1.5f, 20), flat_hit(ng, ns), empty_scene());
    for (int i = 0; i < 20000; ++i) {
        const auto bs = g.sample(wo, rng.next(), rng.next2(), lambda);
        if (!bs) continue;
        ASSERT_EQ(bool(bs->flags & kTransmission), dot(bs->wi, ng) < 0);
    }
}

TEST(BsdfFlags, InterfaceAndBlackBody) {
    Material iface = glass(1, 1.5f);
    iface.interface_only = true;
    const Bsdf i = make(iface);
    const Wavelengths& lambda = spectral::fixed_lambda();
    EXPECT_EQ(i.flags(), 0u);
    EXPECT_FALSE(i.sample(sph(30), 0.5f, Vec2(0.5f, 0.5f), lambda));
    EXPECT_EQ(i.eval(sph(30), sph(40, 180), lambda), Spectrum(0.0f));

    const Bsdf black = make(Material{});
    EXPECT_NE(black.flags(), 0u);  // opaque: integrators must not pass through it
    EXPECT_FALSE(black.sample(sph(30), 0.5f, Vec2(0.5f, 0.5f), lambda));
    EXPECT_EQ(black.eval(sph(30), sph(40, 180), lambda), Spectrum(0.0f));

    EXPECT_EQ(make(lambert(0.5f)).flags(), uint32_t(kDiffuse | kReflection));
    EXPECT_EQ(make(phong(0.5f, 10)).flags(), uint32_t(kGlossy | kReflection));
    EXPECT_EQ(make(glass(1, 1.5f)).flags(), uint32_t(kSpecular | kReflection | kTransmission));
    EXPECT_EQ(make(glass(1, 1.5f, 10)).flags(), uint32_t(kGlossy | kReflection | kTransmission));
}

TEST(BsdfLobes, AlbedosAndMaskedSampling) {
    Material m = lambert(0.6f);
    m.specular = Rgb(0.3f);
    m.shininess = 40;
    m.transmission = Rgb(0.5f, 0.6f, 0.7f);
    m.ior = 1.5f;
    m.diffuse_transmission = Rgb(0.1f);
    const Bsdf b = make(m);
    const Vec3 wo = sph(35, 80);
    const auto a = b.lobe_albedos(wo);
    EXPECT_NEAR(a.diffuse.r, 0.7f, 1e-6f);
    EXPECT_NEAR(a.glossy.g, 0.3f, 1e-6f);
    EXPECT_EQ(a.specular, Rgb(0.0f));
    EXPECT_EQ(a.transmission, m.transmission);

    Sampler rng(15);
    const int n = 5000;
    double glass_colour[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        const float ul = rng.next();
        const Vec2 u = rng.next2();
        const Wavelengths lambda = spectral::stratified_lambda(i, n);
        // Glass only: weight is kt, whichever Fresnel branch was taken: the coloured kt read as
        // a transmittance spectrum, at each wavelength.
        const auto t = b.sample_lobes(kTransmission, wo, ul, u, lambda, TransportMode::Importance);
        ASSERT_TRUE(t);
        EXPECT_TRUE(t->is_specular());
        EXPECT_TRUE(spectral::spectra_near(t->weight, spectral::albedo(m.transmission, lambda), 1e-5));
        // Lit by RGB white, the film sees it as kt (below).
        const Rgb c = spectrum::to_srgb(t->weight * spectral::illuminant(Rgb(1.0f), lambda), lambda);
        for (int k = 0; k < 3; ++k) glass_colour[k] += c[k] / n;
        // Glossy only: the Phong lobe's own f cos / pdf = ks (n+2)/(n+1) cos(theta_i).
        if (const auto g = b.sample_lobes(kGlossy, wo, ul, u, lambda)) {
            EXPECT_EQ(g->flags, uint32_t(kGlossy | kReflection));
            EXPECT_TRUE(flat_near(g->weight, 0.3f * 42.0f / 41.0f * g->wi.z, 1e-4));
        }
        // Diffuse: Lambert reflection and transmission, weight = their sum of f cos / mixture pdf,
        // i.e. 0.6 when reflecting and 0.1 when transmitting after renormalising the selection
        // (0.6 : 0.1) -> weight = kd / (6/7) or kdt / (1/7) = 0.7 either way.
        const auto d = b.sample_lobes(kDiffuse, wo, ul, u, lambda);
        ASSERT_TRUE(d);
        EXPECT_TRUE(d->flags & kDiffuse);
        EXPECT_TRUE(flat_near(d->weight, 0.7, 1e-4));
        // The full mask equals sample().
        const auto s1 = b.sample(wo, ul, u, lambda), s2 = b.sample_lobes(b.flags(), wo, ul, u, lambda);
        ASSERT_EQ(bool(s1), bool(s2));
        if (s1) {
            EXPECT_EQ(s1->wi, s2->wi);
            EXPECT_EQ(s1->weight, s2->weight);
        }
    }
    // The glass's weight through the film over the n stratified wavelength sets: kt within 1 %
    // (the exact fit is within 1e-5 of the RGB; 5000 x 4 stratified wavelengths integrate the
    // smooth spectrum to ~1e-4).
    EXPECT_TRUE(spectral::rgb_near(
        Rgb(float(glass_colour[0]), float(glass_colour[1]), float(glass_colour[2])), m.transmission, 0.01));
}

// sample_lobes takes a short path for a single Lambert lobe; it must give what the general
// definitions give, to the bit: wi from the cosine warp in the shading frame, f = eval(wo, wi),
// pdf = pdf(wo, wi) (both through the general code) and weight = f |cos| / pdf, on either side,
// with a tilted shading normal and tangent, and nothing for masks without the diffuse kind.
TEST(BsdfLambert, ShortPathEqualsTheGeneralDefinitionsToTheBit) {
    accel::SurfaceHit h = flat_hit(Vec3(0, 0, 1), normalize(Vec3(0.1f, 0.2f, 1)));
    h.dpdu = Vec3(2, 0, 0.5f);
    Material m = lambert(0.6f);
    m.diffuse = Rgb(0.7f, 0.3f, 0.05f);
    const Bsdf b(m, h, empty_scene());
    Sampler rng(5);
    int produced = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 wo = sph(175.0f * rng.next() + 2.5f, 360.0f * rng.next());
        const Vec2 u = rng.next2();
        const float ul = rng.next();
        const Wavelengths lambda = spectral::stratified_lambda(i, 20000);
        ASSERT_FALSE(b.sample_lobes(kGlossy | kSpecular | kTransmission, wo, ul, u, lambda));
        const auto bs = b.sample_lobes(kDiffuse, wo, ul, u, lambda, TransportMode::Importance);
        const auto all = b.sample(wo, ul, u, lambda);
        ASSERT_EQ(bool(bs), bool(all));
        if (!bs) continue;
        ++produced;
        const float side = dot(wo, b.geometric_normal()) > 0 ? 1.0f : -1.0f;
        Vec3 wi_l = warp::cosine_hemisphere(u);
        const float cos = std::fabs(wi_l.z);
        wi_l.z *= side;
        ASSERT_EQ(bs->wi, b.frame().to_world(wi_l));
        ASSERT_EQ(bs->f, b.eval(wo, bs->wi, lambda));
        ASSERT_EQ(bs->pdf, b.pdf(wo, bs->wi));
        ASSERT_EQ(bs->weight, bs->f * (cos / bs->pdf));
        ASSERT_EQ(bs->flags, uint32_t(kDiffuse | kReflection));
        ASSERT_EQ(bs->eta, 1.0f);
        ASSERT_EQ(all->weight, bs->weight);
    }
    EXPECT_GT(produced, 15000);
}

// Bsdf::evaluate (f and both pdfs at once, as bdpt and vcm use them) gives exactly the values of
// eval and of pdf in both directions: for a lone Lambert lobe (its short path, with a shading
// normal off the geometric one so the side tests disagree sometimes) and for a Lambert + Phong mix.
TEST(BsdfEvaluate, EqualsEvalAndBothPdfsToTheBit) {
    accel::SurfaceHit h = flat_hit(Vec3(0, 0, 1), normalize(Vec3(0.3f, 0.2f, 1)));
    h.dpdu = Vec3(2, 0, 0.5f);
    Material lone = lambert(0.6f);
    lone.diffuse = Rgb(0.7f, 0.3f, 0.05f);
    Material mix = lone;
    mix.specular = Rgb(0.2f);
    mix.shininess = 30;
    Sampler rng(11);
    for (const Material& m : {lone, mix}) {
        const Bsdf b(m, h, empty_scene());
        int nonzero = 0, zero = 0;
        for (int i = 0; i < 20000; ++i) {
            const Vec3 wo = sph(180.0f * rng.next(), 360.0f * rng.next());
            const Vec3 wi = sph(180.0f * rng.next(), 360.0f * rng.next());
            const Wavelengths lambda = spectral::stratified_lambda(i, 20000);
            for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                const Bsdf::Evaluation e = b.evaluate(wo, wi, lambda, mode);
                ASSERT_EQ(e.f, b.eval(wo, wi, lambda, mode));
                ASSERT_EQ(e.pdf, b.pdf(wo, wi));
                ASSERT_EQ(e.pdf_rev, b.pdf(wi, wo));
                (e.pdf > 0 ? nonzero : zero) += 1;
            }
        }
        EXPECT_GT(nonzero, 10000);  // both reflection and the other side are covered
        EXPECT_GT(zero, 10000);
    }
}

TEST(BsdfFrame, UsesDpduForTangent) {
    accel::SurfaceHit h = flat_hit(Vec3(0, 0, 1), normalize(Vec3(0, 0.2f, 1)));
    h.dpdu = Vec3(2, 0, 0.5f);
    const Bsdf b(lambert(1), h, empty_scene());
    const Frame& f = b.frame();
    EXPECT_NEAR(dot(f.s, f.n), 0.0f, 1e-6f);
    EXPECT_NEAR(dot(f.t, f.n), 0.0f, 1e-6f);
    EXPECT_NEAR(length(f.s), 1.0f, 1e-6f);
    EXPECT_NEAR(length(cross(f.s, f.t) - f.n), 0.0f, 1e-5f);  // right-handed
    // s is dpdu minus its normal component.
    const Vec3 proj = normalize(h.dpdu - f.n * dot(f.n, h.dpdu));
    EXPECT_NEAR(length(f.s - proj), 0.0f, 1e-5f);
}

}  // namespace
}  // namespace phos::shading

namespace phos::shading {
namespace {

// What the two MaterialBsdfs tests place: every consistency material, a mirror, smooth glass, an
// interface, a black body and a checkerboard-textured Lambert, each as material 1 of its scene
// (texture 0 the checkerboard), at random hits with and without the accelerator's frame.
std::vector<Case> placement_cases() {
    std::vector<Case> cases = consistency_cases();
    cases.push_back({"mirror", phong(0.9f, 1e6f), {}});
    cases.push_back({"smooth-glass", glass(1.0f, 1.5f), {}});
    Material iface;
    iface.interface_only = true;
    cases.push_back({"interface", iface, {}});
    cases.push_back({"black", lambert(0.0f), {}});
    Material textured = lambert(0.8f);
    textured.diffuse_texture = 0;
    cases.push_back({"textured", textured, {}});
    Material transmitting = lambert(0.3f);
    transmitting.diffuse_transmission = Rgb(0.6f);
    transmitting.diffuse_transmission_texture = 0;
    cases.push_back({"textured-transmittance", transmitting, {}});
    return cases;
}
scene::Scene placement_scene(const Material& m) {
    scene::Texture check;
    check.kind = scene::Texture::Kind::Checkerboard;
    check.value = Rgb(0.2f, 0.5f, 0.9f);
    check.value2 = Rgb(0.7f, 0.1f, 0.3f);
    check.u_scale = check.v_scale = 8;
    scene::Scene s;
    s.textures.push_back(check);
    s.materials = {lambert(0.5f), m};
    return s;
}
// On material 1, with random normals, tangent and uv; with `kept` as the accelerator's
// per-triangle frame when `with_frame`.
accel::SurfaceHit placement_hit(Sampler& rng, bool with_frame, ShadingFrame& kept) {
    const auto random_dir = [&] { return sph(180.0f * rng.next(), 360.0f * rng.next()); };
    accel::SurfaceHit h = flat_hit(random_dir(), random_dir());
    h.dpdu = random_dir() * (0.5f + rng.next());
    h.uv = rng.next2();
    h.material = 1;
    if (with_frame) {
        kept = shading_frame(h.ng, h.ns, h.dpdu);
        h.shading = &kept;
    }
    return h;
}

// MaterialBsdfs::at (a per-material BSDF built once, then placed at the hit) is the object the
// constructor builds, bit for bit: same flags, frame, normal and albedo, and the same eval, pdf,
// lobe albedos and samples, for every consistency material, a mirror, smooth glass, an interface,
// a black body and a checkerboard-textured Lambert; at hits with and without the accelerator's
// shading frame, random normals, tangents and uvs.
TEST(BsdfMaterialBsdfs, PlacedEqualsConstructedToTheBit) {
    Sampler rng(21);
    const auto random_dir = [&] { return sph(180.0f * rng.next(), 360.0f * rng.next()); };
    int compared = 0;
    for (const Case& c : placement_cases()) {
        const scene::Scene s = placement_scene(c.m);
        const MaterialBsdfs bsdfs(s, c.o);
        for (int i = 0; i < 300; ++i) {
            ShadingFrame kept;
            const accel::SurfaceHit h = placement_hit(rng, i % 2, kept);
            const Bsdf a(s.materials[1], h, s, c.o);
            const Bsdf b = bsdfs.at(h);
            ASSERT_EQ(a.flags(), b.flags()) << c.name;
            ASSERT_EQ(a.frame().n, b.frame().n);
            ASSERT_EQ(a.frame().s, b.frame().s);
            ASSERT_EQ(a.frame().t, b.frame().t);
            ASSERT_EQ(a.geometric_normal(), b.geometric_normal());
            const Wavelengths lambda = spectral::stratified_lambda(i, 300);
            ASSERT_EQ(a.diffuse_colour(), b.diffuse_colour()) << c.name;
            ASSERT_EQ(a.diffuse_albedo(lambda), b.diffuse_albedo(lambda)) << c.name;
            const Vec3 wo = random_dir(), wi = random_dir();
            for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                ASSERT_EQ(a.eval(wo, wi, lambda, mode), b.eval(wo, wi, lambda, mode)) << c.name;
                const float ul = rng.next();
                const Vec2 u = rng.next2();
                const auto sa = a.sample(wo, ul, u, lambda, mode), sb = b.sample(wo, ul, u, lambda, mode);
                ASSERT_EQ(bool(sa), bool(sb)) << c.name;
                if (sa) {
                    ASSERT_EQ(sa->wi, sb->wi) << c.name;
                    ASSERT_EQ(sa->f, sb->f);
                    ASSERT_EQ(sa->weight, sb->weight);
                    ASSERT_EQ(sa->pdf, sb->pdf);
                    ASSERT_EQ(sa->flags, sb->flags);
                    ++compared;
                }
            }
            ASSERT_EQ(a.pdf(wo, wi), b.pdf(wo, wi)) << c.name;
            const Bsdf::LobeAlbedos la = a.lobe_albedos(wo), lb = b.lobe_albedos(wo);
            ASSERT_EQ(la.diffuse, lb.diffuse);
            ASSERT_EQ(la.glossy, lb.glossy);
            ASSERT_EQ(la.specular, lb.specular);
            ASSERT_EQ(la.transmission, lb.transmission);
        }
    }
    EXPECT_GT(compared, 3000);
}

// The photon tracer's fast path: a lone Lambert lobe taken without building the BSDF samples as
// the BSDF's own sample_lobes(kDiffuse) to the bit (textured or not, with the accelerator's frame
// or without), and only lone Lambert materials take it.
TEST(BsdfMaterialBsdfs, LambertLobeSamplesAsTheBsdfToTheBit) {
    Sampler rng(22);
    const auto random_dir = [&] { return sph(180.0f * rng.next(), 360.0f * rng.next()); };
    int lambertian = 0, sampled = 0;
    for (const Case& c : placement_cases()) {
        const scene::Scene s = placement_scene(c.m);
        const MaterialBsdfs bsdfs(s, c.o);
        for (int i = 0; i < 300; ++i) {
            ShadingFrame kept;
            const accel::SurfaceHit h = placement_hit(rng, i % 2, kept);
            const Bsdf b = bsdfs.at(h);
            LambertLobe lobe;
            ASSERT_EQ(bsdfs.lambert_at(h, lobe), b.is_lambertian()) << c.name;
            if (!b.is_lambertian()) continue;
            ++lambertian;
            const Wavelengths lambda = spectral::stratified_lambda(i, 300);
            ASSERT_EQ(lobe.kd, b.diffuse_colour()) << c.name;
            ASSERT_EQ(lobe.kd_spectrum.sample(lambda), b.diffuse_albedo(lambda)) << c.name;
            for (int k = 0; k < 4; ++k) {
                const Vec3 wo = k == 3 ? Frame(b.geometric_normal()).s : random_dir();  // grazing: none
                const Vec2 u = rng.next2();
                const auto sa =
                    b.sample_lobes(kDiffuse, wo, rng.next(), u, lambda, TransportMode::Importance);
                const auto sb = lobe.sample(wo, u, lambda);
                ASSERT_EQ(bool(sa), bool(sb)) << c.name;
                if (!sa) continue;
                ASSERT_EQ(sa->wi, sb->wi) << c.name;
                ASSERT_EQ(sa->weight, sb->weight);
                ASSERT_EQ(sa->f, sb->f);
                ASSERT_EQ(sa->pdf, sb->pdf);
                ASSERT_EQ(sa->flags, sb->flags);
                ++sampled;
            }
        }
    }
    EXPECT_GT(lambertian, 600);
    EXPECT_GT(sampled, 1000);
}

}  // namespace
}  // namespace phos::shading
