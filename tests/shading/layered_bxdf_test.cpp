// Tests of pbrt-v4's layered BSDF (shading/layered_bxdf.h): white furnace of the sampled albedo
// (1 for lossless stacks, the closed form F + (1 - F) r (1 - Fi) / (1 - r Fi) of a smooth coat over
// a Lambertian base, < 1 when something absorbs), the estimate f() integrated over the hemisphere
// against the sampled albedo, reciprocity of f's expectation, the no-interface limit (f = r / pi),
// f() and the sampled albedo against a brute-force analog photon simulation of the same stack (coat
// sampled through shading/dielectric.h, free flights, Lambert, conductor and Henyey-Greenstein by
// survival probabilities), a chi-square of sample()'s directions against pdf() where pbrt-v4's
// estimate is exact, and how far pdf() is from sample()'s density elsewhere; determinism.
#include "shading/layered_bxdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "core/warp.h"
#include "shading/bsdf.h"
#include "shading/dielectric.h"
#include "shading/fresnel.h"
#include "shading/phase.h"
#include "support/chi_square.h"

namespace phos::shading {
namespace {

using spectrum::RgbSpectrum;

Vec3 sph(float theta_deg, float phi_deg = 0) {
    const float t = theta_deg * kPi / 180, p = phi_deg * kPi / 180;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

RgbSpectrum grey(float v) { return RgbSpectrum(Rgb(v), RgbSpectrum::Use::Albedo); }

const Wavelengths& lambda() {
    static const Wavelengths w = Wavelengths::visible(0.37f);
    return w;
}

LayeredParams coated_diffuse(float eta, float alpha, float r, float thickness) {
    LayeredParams p;
    p.eta = eta;
    p.coat_alpha_x = p.coat_alpha_y = alpha;
    p.reflectance = grey(r);
    p.thickness = thickness;
    return p;
}

struct Albedo {
    double mean = 0, stderr_ = 0;
    double specular = 0;  // the part carried by specular samples
};

// Mean of f |cos| / pdf over n samples of wo (failed samples count 0), and its standard error.
Albedo sampled_albedo(const LayeredBxdf& b, Vec3 wo, int n, uint64_t seed = 1) {
    Sampler s(seed, 77);
    double sum = 0, sum2 = 0, spec = 0;
    for (int i = 0; i < n; ++i) {
        const float uc = s.next();
        const Vec2 u = s.next2();
        const auto smp = b.sample(wo, uc, u, lambda());
        if (!smp) continue;
        const double w = smp->weight[0];
        EXPECT_TRUE(std::isfinite(w));
        sum += w;
        sum2 += w * w;
        if (smp->is_specular()) spec += w;
    }
    Albedo a;
    a.mean = sum / n;
    a.stderr_ = std::sqrt(std::max(0.0, sum2 / n - a.mean * a.mean) / n);
    a.specular = spec / n;
    return a;
}

// Integral of f(wo, wi) cos(wi) over the upper hemisphere by uniform directions (one f estimate
// each), with its standard error.
Albedo integrated_f(const LayeredBxdf& b, Vec3 wo, int n, uint64_t seed = 2) {
    Sampler s(seed, 78);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        const Vec2 u = s.next2();
        const float z = u.x, r = std::sqrt(std::max(0.0f, 1 - z * z)), phi = 2 * kPi * u.y;
        const Vec3 wi(r * std::cos(phi), r * std::sin(phi), z);
        const double v = double(b.f(wo, wi, lambda())[0]) * wi.z * 2 * M_PI;
        sum += v;
        sum2 += v * v;
    }
    Albedo a;
    a.mean = sum / n;
    a.stderr_ = std::sqrt(std::max(0.0, sum2 / n - a.mean * a.mean) / n);
    return a;
}

// The cosine-weighted hemispherical average of the Fresnel reflectance seen from inside a coat of
// index eta (the fraction of diffuse light it reflects back), by the midpoint rule.
double internal_diffuse_fresnel(float eta) {
    const int n = 20000;
    double acc = 0;
    for (int i = 0; i < n; ++i) {
        const double mu = (i + 0.5) / n;  // cos theta
        acc += fresnel_dielectric(float(mu), 1 / eta) * 2 * mu / n;
    }
    return acc;
}

TEST(LayeredBxdf, WhiteFurnaceSmoothCoatIsLossless) {
    LayeredParams p = coated_diffuse(1.5f, 0, 1, 1e-6f);
    p.max_depth = 200;
    const LayeredBxdf b(p);
    for (float theta : {0.0f, 45.0f, 80.0f}) {
        const Albedo a = sampled_albedo(b, sph(theta, 30), 40000);
        EXPECT_NEAR(a.mean, 1.0, 4 * a.stderr_ + 2e-3) << "theta " << theta << " +- " << a.stderr_;
        // From below (two-sided): the same.
        const Albedo below = sampled_albedo(b, -sph(theta, 30), 20000);
        EXPECT_NEAR(below.mean, 1.0, 4 * below.stderr_ + 2e-3) << "theta " << theta;
    }
}

TEST(LayeredBxdf, SmoothCoatOverLambertMatchesClosedForm) {
    // Thin, clear coat: R = F(theta) + (1 - F) r (1 - Fi) / (1 - r Fi) with Fi the internal diffuse
    // Fresnel reflectance.
    const float eta = 1.5f;
    const double fi = internal_diffuse_fresnel(eta);
    for (float r : {0.2f, 0.8f}) {
        LayeredParams p = coated_diffuse(eta, 0, r, 1e-6f);
        p.max_depth = 100;
        const LayeredBxdf b(p);
        for (float theta : {20.0f, 70.0f}) {
            const double f = fresnel_dielectric(std::cos(theta * kPi / 180), eta);
            const double expect = f + (1 - f) * r * (1 - fi) / (1 - r * fi);
            const Albedo a = sampled_albedo(b, sph(theta), 40000);
            EXPECT_NEAR(a.mean, expect, 4 * a.stderr_ + 2e-3) << "r " << r << " theta " << theta;
            EXPECT_NEAR(a.specular, f, 1e-2) << "the specular part is the coat's Fresnel reflection";
        }
    }
}

TEST(LayeredBxdf, AbsorbingStacksReflectLess) {
    // A thick clear slab (transmittance exp(-t / cos)), a grey base, an absorbing medium and a
    // coated conductor all reflect less than 1.
    std::vector<LayeredParams> cases;
    cases.push_back(coated_diffuse(1.5f, 0.2f, 1, 0.3f));
    cases.push_back(coated_diffuse(1.5f, 0, 0.5f, 1e-6f));
    LayeredParams med = coated_diffuse(1.5f, 0.2f, 1, 0.5f);
    med.albedo = grey(0.7f);
    med.g = 0.4f;
    cases.push_back(med);
    LayeredParams cond;
    cond.base = LayeredParams::Base::Conductor;
    cond.conductor_from_reflectance = true;
    cond.reflectance = grey(0.9f);
    cond.base_alpha_x = cond.base_alpha_y = 0.3f;
    cond.coat_alpha_x = cond.coat_alpha_y = 0.1f;
    cases.push_back(cond);
    for (size_t i = 0; i < cases.size(); ++i) {
        cases[i].max_depth = 100;
        const LayeredBxdf b(cases[i]);
        const Albedo a = sampled_albedo(b, sph(35, 0), 20000);
        EXPECT_LT(a.mean + 4 * a.stderr_, 0.99) << "case " << i;
        EXPECT_GT(a.mean, 0.05) << "case " << i;
    }
}

TEST(LayeredBxdf, IntegratedEstimateMatchesSampledAlbedo) {
    // f() has no delta part: compare with the sampled albedo less its specular samples.
    std::vector<LayeredParams> cases;
    cases.push_back(coated_diffuse(1.5f, 0, 0.8f, 0.01f));
    cases.push_back(coated_diffuse(1.5f, 0.3f, 0.8f, 0.01f));
    LayeredParams med = coated_diffuse(1.33f, 0.2f, 0.6f, 0.3f);
    med.albedo = grey(0.8f);
    med.g = -0.3f;
    cases.push_back(med);
    LayeredParams cond;
    cond.base = LayeredParams::Base::Conductor;
    cond.conductor_eta.rgb = RgbSpectrum(Rgb(0.2f, 0.9f, 1.1f), RgbSpectrum::Use::Unbounded);
    cond.conductor_k.rgb = RgbSpectrum(Rgb(3.9f, 2.4f, 2.2f), RgbSpectrum::Use::Unbounded);
    cond.base_alpha_x = 0.2f;
    cond.base_alpha_y = 0.4f;
    cond.coat_alpha_x = cond.coat_alpha_y = 0.15f;
    cases.push_back(cond);
    for (size_t i = 0; i < cases.size(); ++i) {
        const LayeredBxdf b(cases[i]);
        for (float theta : {10.0f, 55.0f}) {
            const Vec3 wo = sph(theta, 40);
            const Albedo s = sampled_albedo(b, wo, 40000);
            const Albedo f = integrated_f(b, wo, 40000);
            const double sampled = s.mean - s.specular;
            EXPECT_NEAR(f.mean, sampled, 4 * std::hypot(f.stderr_, s.stderr_) + 3e-3)
                << "case " << i << " theta " << theta << ": integral of f " << f.mean << " +- " << f.stderr_
                << ", sampled " << sampled << " +- " << s.stderr_;
        }
    }
}

TEST(LayeredBxdf, EstimateIsReciprocalInExpectation) {
    std::vector<LayeredParams> cases;
    cases.push_back(coated_diffuse(1.5f, 0.25f, 0.7f, 0.05f));
    LayeredParams med = coated_diffuse(1.5f, 0, 0.5f, 0.4f);
    med.albedo = grey(0.9f);
    med.g = 0.5f;
    cases.push_back(med);
    const std::pair<Vec3, Vec3> pairs[] = {{sph(20, 0), sph(60, 150)}, {sph(70, 10), sph(35, 250)}};
    for (size_t i = 0; i < cases.size(); ++i)
        for (const auto& [a, c] : pairs) {
            double fab = 0, fba = 0, var = 0, fimp = 0, var_imp = 0;
            const int n = 4000;
            for (int k = 0; k < n; ++k) {
                LayeredParams p = cases[i];
                p.seed = uint64_t(k);
                const LayeredBxdf b(p);
                const double x = b.f(a, c, lambda())[0], y = b.f(c, a, lambda())[0];
                // Importance transport is the adjoint: f_importance(c, a) = f_radiance(a, c).
                const double z = b.f(c, a, lambda(), TransportMode::Importance)[0];
                fab += x;
                fba += y;
                fimp += z;
                var += (x - y) * (x - y);
                var_imp += (x - z) * (x - z);
            }
            fab /= n;
            fba /= n;
            fimp /= n;
            const double se = std::sqrt(var / n / n), se_imp = std::sqrt(var_imp / n / n);
            EXPECT_NEAR(fab, fba, 4 * se + 1e-3 * fab) << "case " << i << ": " << fab << " vs " << fba;
            EXPECT_NEAR(fab, fimp, 4 * se_imp + 1e-3 * fab) << "case " << i << ": " << fab << " vs " << fimp;
        }
}

TEST(LayeredBxdf, NoInterfaceIsTheBareLambertian) {
    LayeredParams p = coated_diffuse(1, 0, 0.6f, 1e-7f);
    const LayeredBxdf b(p);
    for (const auto& [wo, wi] : {std::pair{sph(0), sph(30, 90)}, std::pair{sph(75, 0), sph(10, 200)}}) {
        const Spectrum f = b.f(wo, wi, lambda());
        for (int i = 0; i < spectrum::kSpectrumSamples; ++i) EXPECT_NEAR(f[i], 0.6 / M_PI, 1e-5);
        EXPECT_FLOAT_EQ(b.f(-wo, -wi, lambda())[0], f[0]);  // two-sided
        EXPECT_EQ(b.f(wo, -wi, lambda())[0], 0.0f);         // opaque
        EXPECT_NEAR(b.pdf(wo, wi), 0.1 / (4 * M_PI) + 0.9 * wi.z / M_PI, 1e-6);
    }
    // sample(): cosine-distributed, weight r.
    const Albedo a = sampled_albedo(b, sph(40), 2000);
    EXPECT_NEAR(a.mean, 0.6, 1e-4);
}

// Brute-force analog simulation of the stack for photons arriving from w_in: the fraction leaving
// into each (theta, phi) bin. Independent of layered_bxdf.cpp: the coat through dielectric.h's
// samplers (kept with probability f |cos| / pdf), free flights of unit extinction, Lambert and
// Henyey-Greenstein with survival probabilities r and albedo. Photons reflected by the coat
// specularly on arrival (a delta f() leaves out) are not counted. A conductor base is given in
// the reflectance form.
std::vector<double> brute_force(const LayeredParams& p, Vec3 w_in, int n, int nt, int np) {
    std::vector<double> bins(size_t(nt * np), 0.0);
    const MicrofacetDistribution dist(p.coat_alpha_x, p.coat_alpha_y);
    const MicrofacetDistribution base_dist(p.base_alpha_x, p.base_alpha_y);
    const bool smooth = std::max(p.coat_alpha_x, p.coat_alpha_y) < 1e-3f;
    const float r = p.reflectance(550.0f), albedo = p.albedo(550.0f);
    const PhaseFunction phase{p.g};
    Sampler s(99, 1);
    // Crossing the coat from the side of `wo` (pointing away from it, either side): the new
    // direction (pointing away), or nullopt when absorbed by the microfacets' shadowing.
    const auto coat = [&](Vec3 wo, bool& specular_reflection) -> std::optional<Vec3> {
        float eta = p.eta, flip = 1;
        if (wo.z < 0) {
            wo = -wo;
            eta = 1 / eta;
            flip = -1;
        }
        specular_reflection = false;
        if (smooth) {
            const auto d =
                dielectric::sample_smooth(wo, eta, false, false, s.next(), TransportMode::Importance);
            if (!d) return std::nullopt;
            specular_reflection = !d->transmitted;
            return d->wi * flip;
        }
        const auto wi = dielectric::rough_sample(dist, wo, eta, false, s.next(), s.next2());
        if (!wi) return std::nullopt;
        const float keep = dielectric::rough_eval(dist, wo, *wi, eta, false, TransportMode::Importance) *
                           std::fabs(wi->z) / dielectric::rough_pdf(dist, wo, *wi, eta, false);
        if (s.next() >= keep) return std::nullopt;
        return *wi * flip;
    };
    const auto record = [&](Vec3 out) {
        const double theta = std::acos(std::min(1.0f, out.z));
        double phi = std::atan2(out.y, out.x);
        if (phi < 0) phi += 2 * M_PI;
        const int it = std::min(nt - 1, int(theta / (M_PI / 2) * nt));
        const int ip = std::min(np - 1, int(phi / (2 * M_PI) * np));
        bins[size_t(it * np + ip)] += 1.0 / n;
    };
    for (int i = 0; i < n; ++i) {
        bool spec = false;
        auto d = coat(w_in, spec);
        if (!d || spec) continue;
        if (d->z > 0) {  // the rough coat's own reflection
            record(*d);
            continue;
        }
        Vec3 w = *d;
        float z = p.thickness;
        for (int bounce = 0; bounce < 1000; ++bounce) {
            if (w.z > 0 && z >= p.thickness) {  // leaving through the coat's underside?
                const auto out = coat(-w, spec);
                if (!out) break;
                if (out->z > 0) {
                    record(*out);
                    break;
                }
                w = *out;
                continue;
            }
            if (w.z < 0 && z <= 0) {  // the base
                if (p.base == LayeredParams::Base::Diffuse) {
                    if (s.next() >= r) break;
                    w = warp::cosine_hemisphere(s.next2());
                    continue;
                }
                // A conductor (reflectance form): a mirror or a microfacet reflection, kept with
                // probability F (x G / G1 when rough), eta and k relative to the coat.
                const float rc = std::min(p.reflectance(550.0f), 0.9999f);
                const float ce = 1 / p.eta, ck = 2 * std::sqrt(rc) / std::sqrt(1 - rc) / p.eta;
                const Vec3 wo = -w;
                Vec3 m(0, 0, 1);
                float keep = 1;
                if (std::max(p.base_alpha_x, p.base_alpha_y) >= 1e-3f) {
                    m = base_dist.sample_wm(wo, s.next2());
                    const Vec3 wi = reflect(wo, m);
                    keep = wi.z > 0 ? base_dist.G(wo, wi) / base_dist.G1(wo) : 0;
                }
                keep *= fresnel_conductor(dot(wo, m), ce, ck);
                if (s.next() >= keep) break;
                w = reflect(wo, m);
                continue;
            }
            const float dist_z = -std::log1p(-s.next()) * std::fabs(w.z);
            const float zp = w.z > 0 ? z + dist_z : z - dist_z;
            if (zp <= 0 || zp >= p.thickness) {
                z = zp <= 0 ? 0 : p.thickness;
                continue;
            }
            z = zp;
            if (s.next() >= albedo) break;  // absorbed (no medium: albedo 0)
            Vec3 nw;
            phase.sample(-w, s.next2(), nw);
            w = nw;
        }
    }
    return bins;
}

TEST(LayeredBxdf, WhiteFurnaceRoughCoatMatchesBruteForce) {
    // pbrt-v4's rough dielectric is single-scattering: masking and reflections below the horizon
    // lose energy at every hit (at alpha 0.3, 17 % of the diffuse light meeting the coat from
    // inside), so a rough coat over a white base reflects less than 1: as much as the brute-force
    // simulation of the same stack.
    for (float alpha : {0.05f, 0.3f}) {
        LayeredParams p = coated_diffuse(1.5f, alpha, 1, 1e-6f);
        p.max_depth = 200;
        const LayeredBxdf b(p);
        for (float theta : {0.0f, 60.0f}) {
            const Albedo a = sampled_albedo(b, sph(theta, 10), 40000);
            const int n = 200000;
            const double bf = brute_force(p, sph(theta, 10), n, 1, 1)[0],
                         se_bf = std::sqrt(bf * (1 - bf) / n);
            EXPECT_NEAR(a.mean, bf, 4 * std::hypot(a.stderr_, se_bf)) << alpha << " " << theta;
            EXPECT_LT(a.mean, 1.0 - 4 * a.stderr_) << alpha << " " << theta;
            std::printf(
                "layered white furnace, coat alpha %.2f, theta %.0f: sampled %.4f +- %.4f, brute force "
                "%.4f\n",
                alpha, theta, a.mean, a.stderr_, bf);
        }
    }
}

TEST(LayeredBxdf, EstimateMatchesBruteForceSimulation) {
    std::vector<LayeredParams> cases;
    cases.push_back(coated_diffuse(1.5f, 0, 0.8f, 0.1f));
    LayeredParams med = coated_diffuse(1.5f, 0.3f, 0.7f, 0.4f);
    med.albedo = grey(0.8f);
    med.g = 0.3f;
    cases.push_back(med);
    LayeredParams cond;
    cond.base = LayeredParams::Base::Conductor;
    cond.conductor_from_reflectance = true;
    cond.reflectance = grey(0.9f);
    cond.base_alpha_x = cond.base_alpha_y = 0.3f;
    cond.coat_alpha_x = cond.coat_alpha_y = 0.2f;
    cond.thickness = 0.05f;
    cases.push_back(cond);
    const int nt = 6, np = 4;
    const Vec3 w_in = sph(40, 180);
    for (size_t c = 0; c < cases.size(); ++c) {
        cases[c].max_depth = 100;
        const LayeredBxdf b(cases[c]);
        const std::vector<double> bf = brute_force(cases[c], w_in, 400000, nt, np);
        // The integral of f(w_out, w_in) cos(w_out) over each bin, by uniform directions in it.
        Sampler s(5, 6);
        double worst = 0, total_bf = 0, total_f = 0;
        for (int it = 0; it < nt; ++it)
            for (int ip = 0; ip < np; ++ip) {
                const double z0 = std::cos((it + 1) * M_PI / 2 / nt), z1 = std::cos(it * M_PI / 2 / nt);
                const double area = (z1 - z0) * 2 * M_PI / np;
                const int m = 3000;
                double sum = 0, sum2 = 0;
                for (int k = 0; k < m; ++k) {
                    const Vec2 u = s.next2();
                    const float z = float(z0 + (z1 - z0) * u.x), phi = float((ip + u.y) * 2 * M_PI / np);
                    const float rr = std::sqrt(std::max(0.0f, 1 - z * z));
                    const Vec3 wo(rr * std::cos(phi), rr * std::sin(phi), z);
                    const double v = double(b.f(wo, w_in, lambda())[0]) * z * area;
                    sum += v;
                    sum2 += v * v;
                }
                const double mean = sum / m, se_f = std::sqrt(std::max(0.0, sum2 / m - mean * mean) / m);
                const double pb = bf[size_t(it * np + ip)], se_b = std::sqrt(pb * (1 - pb) / 400000);
                const double zscore = (mean - pb) / std::hypot(se_f, se_b);
                worst = std::max(worst, std::fabs(zscore));
                total_bf += pb;
                total_f += mean;
                EXPECT_LT(std::fabs(zscore), 4.5)
                    << "case " << c << " bin " << it << "," << ip << ": f " << mean << " +- " << se_f
                    << ", brute force " << pb << " +- " << se_b;
            }
        EXPECT_NEAR(total_f, total_bf, 0.01) << "case " << c;
        std::printf("layered case %zu: brute-force reflectance %.4f, integrated f %.4f, worst bin |z| %.2f\n",
                    c, total_bf, total_f, worst);
    }
}

TEST(LayeredBxdf, SampledDirectionsFollowPdfWhereTheEstimateIsExact) {
    // Without an interface (eta 1, thin) sample() draws cosine directions and pdf() is
    // 0.1 / (4 pi) + 0.9 cos / pi exactly: a chi-square of the sampled directions against pdf().
    const LayeredBxdf b(coated_diffuse(1, 0, 0.9f, 1e-7f));
    const Vec3 wo = sph(50, 20);
    test::DirectionHistogram h(10, 20, M_PI / 2);
    Sampler s(7, 8);
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        const auto smp = b.sample(wo, s.next(), s.next2(), lambda());
        if (smp)
            h.add(smp->wi);
        else
            h.add_residual();
    }
    h.total = n;
    const auto expected = h.expected([&](Vec3 w) { return (double(b.pdf(wo, w)) - 0.1 / (4 * M_PI)) / 0.9; });
    const auto r = test::chi_square(h.counts, expected);
    EXPECT_TRUE(r.passed) << r.detail;
    std::printf("layered, no interface, sample against pdf: %s\n", r.detail.c_str());
}

TEST(LayeredBxdf, PdfEstimateApproximatesSampledDensity) {
    // pbrt-v4's pdf() is an approximation (the first transmission-reflection-transmission path,
    // no refraction Jacobian): check it against sample()'s histogram, both normalised over the
    // upper hemisphere, by the total variation distance, and that it is positive wherever sample()
    // lands.
    std::vector<LayeredParams> cases;
    cases.push_back(coated_diffuse(1.5f, 0.3f, 0.8f, 0.01f));
    LayeredParams cond;
    cond.base = LayeredParams::Base::Conductor;
    cond.conductor_from_reflectance = true;
    cond.reflectance = grey(0.8f);
    cond.base_alpha_x = cond.base_alpha_y = 0.3f;
    cond.coat_alpha_x = cond.coat_alpha_y = 0.2f;
    cases.push_back(cond);
    for (size_t c = 0; c < cases.size(); ++c) {
        const LayeredBxdf b(cases[c]);
        const Vec3 wo = sph(30, 0);
        const int nt = 8, np = 8, n = 100000;
        test::DirectionHistogram h(nt, np, M_PI / 2);
        Sampler s(11, 12);
        int landed = 0;
        for (int i = 0; i < n; ++i) {
            const auto smp = b.sample(wo, s.next(), s.next2(), lambda());
            if (!smp) continue;
            EXPECT_GT(b.pdf(wo, smp->wi), 0.0f);
            h.add(smp->wi);
            ++landed;
        }
        // pdf() averaged over many directions per bin (it is an estimate).
        std::vector<double> pdf_mass(size_t(nt * np), 0.0);
        Sampler q(13, 14);
        double pdf_total = 0;
        for (int it = 0; it < nt; ++it)
            for (int ip = 0; ip < np; ++ip) {
                const double t0 = it * M_PI / 2 / nt, t1 = (it + 1) * M_PI / 2 / nt;
                const double area = (std::cos(t0) - std::cos(t1)) * 2 * M_PI / np;
                double acc = 0;
                const int m = 400;
                for (int k = 0; k < m; ++k) {
                    const Vec2 u = q.next2();
                    const double z = std::cos(t0) + (std::cos(t1) - std::cos(t0)) * u.x;
                    const double phi = (ip + u.y) * 2 * M_PI / np, rr = std::sqrt(std::max(0.0, 1 - z * z));
                    acc += b.pdf(wo, Vec3(float(rr * std::cos(phi)), float(rr * std::sin(phi)), float(z)));
                }
                pdf_mass[size_t(it * np + ip)] = acc / m * area;
                pdf_total += acc / m * area;
            }
        double tv = 0;
        for (size_t i = 0; i < pdf_mass.size(); ++i)
            tv += std::fabs(h.counts[i] / landed - pdf_mass[i] / pdf_total);
        tv *= 0.5;
        std::printf("layered case %zu: total variation between pdf() and sample()'s density %.3f\n", c, tv);
        EXPECT_LT(tv, 0.2) << "case " << c;
    }
}

TEST(LayeredBxdf, PartsSumToTheWhole) {
    // f(All) = f(Coat) + f(Walk) for the same inputs; the sampled albedos add up; sample(Coat) is
    // exactly distributed as pdf(Coat) (chi-square); the albedo estimates are exact for a thin,
    // smooth coat over a Lambertian base.
    const float fi = LayeredBxdf::internal_reflectance(1.5f);
    EXPECT_NEAR(fi, internal_diffuse_fresnel(1.5f), 2e-4);
    EXPECT_NEAR(fi, 0.596, 2e-3);  // the classic value for n = 1.5
    for (float alpha : {0.0f, 0.25f}) {
        LayeredParams p = coated_diffuse(1.5f, alpha, 0.7f, 1e-6f);
        p.max_depth = 100;
        const LayeredBxdf b(p);
        for (const auto& [wo, wi] :
             {std::pair{sph(20, 0), sph(25, 180)}, std::pair{sph(60, 30), sph(10, 100)}}) {
            const float all = b.f(wo, wi, lambda())[0];
            const float parts = b.f(wo, wi, lambda(), TransportMode::Radiance, LayeredPart::Coat)[0] +
                                b.f(wo, wi, lambda(), TransportMode::Radiance, LayeredPart::Walk)[0];
            EXPECT_NEAR(all, parts, 1e-5f * all);
        }
        const Vec3 wo = sph(35, 0);
        double sums[3] = {0, 0, 0};
        const LayeredPart kinds[3] = {LayeredPart::All, LayeredPart::Coat, LayeredPart::Walk};
        const int n = 40000;
        for (int k = 0; k < 3; ++k) {
            Sampler s(21, uint64_t(k));
            for (int i = 0; i < n; ++i) {
                const auto smp =
                    b.sample(wo, s.next(), s.next2(), lambda(), TransportMode::Radiance, kinds[k]);
                if (smp) sums[k] += smp->weight[0] / n;
            }
        }
        EXPECT_NEAR(sums[0], sums[1] + sums[2], 1e-2) << alpha;
        if (alpha == 0) {
            EXPECT_NEAR(sums[1], b.coat_albedo(wo.z), 1e-5);
            EXPECT_NEAR(sums[2], b.walk_albedo(wo.z, 0.7f, fi), 5e-3);
            continue;
        }
        // The rough coat's reflection: sample(Coat) against pdf(Coat).
        test::DirectionHistogram h(12, 24, M_PI / 2);
        Sampler s(23, 24);
        for (int i = 0; i < 200000; ++i) {
            const auto smp =
                b.sample(wo, s.next(), s.next2(), lambda(), TransportMode::Radiance, LayeredPart::Coat);
            if (!smp) {
                h.add_residual();
                continue;
            }
            EXPECT_FALSE(smp->pdf_is_proportional);
            EXPECT_EQ(smp->part, LayeredPart::Coat);
            EXPECT_NEAR(smp->pdf, b.pdf(wo, smp->wi, LayeredPart::Coat), 1e-3f * smp->pdf);
            h.add(smp->wi);
        }
        h.total = 200000;
        const auto r =
            test::chi_square(h.counts, h.expected([&](Vec3 w) { return b.pdf(wo, w, LayeredPart::Coat); }));
        EXPECT_TRUE(r.passed) << r.detail;
        std::printf("layered rough coat's reflection, sample against pdf: %s\n", r.detail.c_str());
    }
}

TEST(LayeredBxdf, FlagsAsPbrt) {
    EXPECT_EQ(LayeredBxdf(coated_diffuse(1.5f, 0, 0.5f, 0.01f)).flags(), kReflection | kSpecular | kDiffuse);
    EXPECT_EQ(LayeredBxdf(coated_diffuse(1.5f, 0.2f, 0.5f, 0.01f)).flags(), kReflection | kDiffuse);
    LayeredParams cond;
    cond.base = LayeredParams::Base::Conductor;
    cond.conductor_from_reflectance = true;
    cond.reflectance = grey(0.9f);
    EXPECT_EQ(LayeredBxdf(cond).flags(), kReflection | kSpecular);  // smooth over smooth: a delta
    EXPECT_EQ(LayeredBxdf(cond).walk_kind(), kSpecular);
    EXPECT_EQ(LayeredBxdf(coated_diffuse(1.5f, 0.2f, 0.5f, 0.01f)).coat_kind(), kGlossy);
    EXPECT_EQ(LayeredBxdf(coated_diffuse(1.5f, 0.2f, 0.5f, 0.01f)).walk_kind(), kDiffuse);
    const LayeredBxdf mirror(cond);
    Sampler s(1, 2);
    for (int i = 0; i < 100; ++i) {
        const auto smp = mirror.sample(sph(30, 0), s.next(), s.next2(), lambda());
        if (!smp) continue;
        EXPECT_TRUE(smp->is_specular());
        EXPECT_NEAR(smp->wi.z, sph(30).z, 1e-5);
        EXPECT_EQ(mirror.f(sph(30, 0), smp->wi, lambda())[0], 0.0f);
    }
    cond.base_alpha_x = cond.base_alpha_y = 0.2f;
    EXPECT_EQ(LayeredBxdf(cond).flags(), kReflection | kSpecular | kGlossy);
    cond.albedo = grey(0.5f);
    EXPECT_EQ(LayeredBxdf(cond).flags(), kReflection | kSpecular | kDiffuse);
}

TEST(LayeredBxdf, DeterministicAndWavelengthIndependentDecisions) {
    LayeredParams p = coated_diffuse(1.5f, 0.2f, 0.5f, 0.1f);
    p.reflectance = RgbSpectrum(Rgb(0.8f, 0.3f, 0.1f), RgbSpectrum::Use::Albedo);
    p.albedo = grey(0.5f);
    const LayeredBxdf b(p);
    const Vec3 wo = sph(30, 10), wi = sph(50, 200);
    EXPECT_EQ(b.f(wo, wi, lambda()), b.f(wo, wi, lambda()));
    EXPECT_EQ(b.pdf(wo, wi), b.pdf(wo, wi));
    // Other wavelengths: the same sampled direction where both walks survive their Russian
    // roulette (which reads the largest throughput over the wavelengths, so survival may differ).
    const Wavelengths l1 = Wavelengths::at_values({500, 400, 600, 700});
    const Wavelengths l2 = Wavelengths::at_values({500, 650, 450, 380});
    Sampler s(3, 4);
    int both = 0;
    for (int i = 0; i < 200; ++i) {
        const float uc = s.next();
        const Vec2 u = s.next2();
        const auto a = b.sample(wo, uc, u, l1), c = b.sample(wo, uc, u, l2);
        if (!a || !c) continue;
        ++both;
        EXPECT_EQ(a->wi, c->wi);
    }
    EXPECT_GT(both, 100);  // most samples (the rest: the coat reflected, a walk lost or cut)
}

// A saturated red base seen at a wavelength set whose hero is blue: each wavelength's sampled
// albedo (the walk's weights) matches the integral of its f, red included. With Russian roulette
// on the hero's throughput alone, the red wavelength rode on rare survivors boosted 20-fold, and
// its sampled albedo read several percent off at these sample counts.
TEST(LayeredBxdf, ColouredBaseSampledAlbedoMatchesItsIntegralAtEveryWavelength) {
    LayeredParams p = coated_diffuse(1.5f, 0.0f, 0.0f, 0.01f);
    p.reflectance = RgbSpectrum(Rgb(0.7f, 0.08f, 0.06f), RgbSpectrum::Use::Albedo);
    const LayeredBxdf b(p);
    const Wavelengths l = Wavelengths::at_values({480, 650, 550, 420});  // hero in the blue
    const Vec3 wo = sph(20, 30);
    const int n = 200000;
    Sampler s(5, 6);
    double sampled[4] = {}, integral[4] = {};
    for (int i = 0; i < n; ++i) {
        if (const auto smp = b.sample(wo, s.next(), s.next2(), l); smp && !smp->is_specular())
            for (int k = 0; k < 4; ++k) sampled[k] += smp->weight[k] / n;
        const Vec2 u = s.next2();
        const float z = u.x, r = std::sqrt(std::max(0.0f, 1 - z * z)), phi = 2 * kPi * u.y;
        const Vec3 wi(r * std::cos(phi), r * std::sin(phi), z);
        const Spectrum f = b.f(wo, wi, l);
        for (int k = 0; k < 4; ++k) integral[k] += f[k] * wi.z * 2 * M_PI / n;
    }
    for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(sampled[k], integral[k], 0.015 * integral[k] + 2e-3) << l[k] << " nm";
    EXPECT_GT(integral[1], 0.3);  // the red wavelength reflects strongly
}

}  // namespace
}  // namespace phos::shading
