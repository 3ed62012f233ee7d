// The progressive photon-mapping update (sppm_pixel_stats.h) against closed forms: after photon
// counts M_1..M_k with α, N, R² and τ must equal their closed-form values (Hachisuka & Jensen
// 2009, eq. 9-12); a pixel without photons keeps its statistics; the pilot radius rule; and the
// final estimate with its direct / indirect film layers (sppm_core.h, resolve).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "film/film.h"
#include "integrators/pilot_radius.h"
#include "integrators/sppm_core.h"
#include "integrators/sppm_pixel_stats.h"

namespace phos::integrators::sppm {
namespace {

void expect_rel(double got, double want, const char* what, int step) {
    EXPECT_NEAR(got, want, 1e-12 * std::abs(want)) << what << " after iteration " << step;
}

// Constant M photons per iteration: N_k = α M k (eq. 9), and since N_i = α M i,
// R²_{i+1}/R²_i = (α M i + α M)/(α M i + M) = α (i+1)/(α i + 1) (eq. 10), so
// R²_k = R²_0 Π_{i<k} α (i+1)/(α i + 1) = R²_0 Γ(k+1) Γ(1/α) / Γ(k + 1/α); with constant flux Φ, τ/R² grows
// by Φ/R²_i (eq. 11): τ_k = R²_k Φ Σ_{i<k} 1/R²_i.
TEST(SppmUpdate, ConstantPhotonCountsFollowTheClosedForm) {
    for (const double alpha : {0.5, 0.7, 0.9}) {
        const double r2_0 = 0.04, M = 12, Phi[3] = {0.3, 1.5, 0.0};
        PixelStats s;
        s.r2 = r2_0;
        double r2 = r2_0, inv_r2_sum = 0;
        for (int k = 1; k <= 40; ++k) {
            inv_r2_sum += 1 / r2;                                   // Σ_{i<k} 1/R²_i
            r2 *= alpha * double(k) / (alpha * double(k - 1) + 1);  // R²_k, from the product
            progressive_update(s, uint64_t(M), Phi, alpha);
            expect_rel(s.n, alpha * M * k, "N", k);
            expect_rel(s.r2, r2, "R²", k);
            for (int c = 0; c < 3; ++c) expect_rel(s.tau[c], r2 * Phi[c] * inv_r2_sum, "τ", k);
        }
        // The product in closed form: R²_k = R²_0 Γ(k+1) Γ(1/α) / Γ(k + 1/α) (~ k^(1-1/α)).
        const double k = 40, gamma_form = std::exp(std::lgamma(k + 1) + std::lgamma(1 / alpha) -
                                                   std::lgamma(k + 1 / alpha));
        EXPECT_NEAR(s.r2, r2_0 * gamma_form, 1e-10 * s.r2) << alpha;
    }
}

// Flux proportional to the disc's area (a uniform irradiance ρ: Φ_i = ρ R²_i per unit) gives
// τ_k = k ρ R²_k for ANY photon counts: the estimate τ/(π R² N_emitted) stays exact while the
// radius shrinks. The counts vary, and N = α Σ M.
TEST(SppmUpdate, UniformDensityStaysExactForAnyCounts) {
    const double alpha = 0.6, rho = 2.5;
    const uint64_t counts[] = {3, 17, 1, 40, 8, 8, 250, 2, 99, 5};
    PixelStats s;
    s.r2 = 1.0;
    double total = 0;
    int k = 0;
    for (const uint64_t m : counts) {
        ++k;
        const double phi[3] = {rho * s.r2, 2 * rho * s.r2, 0.5 * rho * s.r2};
        progressive_update(s, m, phi, alpha);
        total += double(m);
        expect_rel(s.n, alpha * total, "N", k);
        expect_rel(s.tau[0], k * rho * s.r2, "τ", k);
        expect_rel(s.tau[1], 2 * k * rho * s.r2, "τ", k);
        expect_rel(s.tau[2], 0.5 * k * rho * s.r2, "τ", k);
    }
    // Radiance (eq. 12) with N_emitted = 1000 k: k ρ / (π 1000 k), independent of the radius.
    const double L = s.tau[0] * radiance_scale(s.r2, 1.0 / (1000.0 * k));
    expect_rel(L, rho / (M_PI * 1000.0), "L", k);
}

// α = 1 keeps every photon: R² never shrinks, N = Σ M, τ = Σ Φ (plain progressive averaging).
TEST(SppmUpdate, AlphaOneNeverShrinks) {
    PixelStats s;
    s.r2 = 0.25;
    double n = 0, tau = 0;
    int k = 0;
    for (const uint64_t m : {5u, 1u, 30u, 7u}) {
        ++k;
        const double phi[3] = {0.1 * double(m), 0, 1};
        progressive_update(s, m, phi, 1.0);
        n += double(m);
        tau += phi[0];
        EXPECT_EQ(s.r2, 0.25) << k;
        expect_rel(s.n, n, "N", k);
        expect_rel(s.tau[0], tau, "τ", k);
        expect_rel(s.tau[2], k, "τ", k);
    }
}

// No photon this iteration: N, R² and τ stay exactly as they were (a fresh pixel too, where the
// update would otherwise compute 0/0).
TEST(SppmUpdate, NoPhotonsKeepsEverything) {
    const double phi[3] = {5, 5, 5};  // ignored: no photon carried it
    PixelStats fresh;
    fresh.r2 = 0.5;
    progressive_update(fresh, 0, phi, 0.7);
    EXPECT_EQ(fresh.n, 0);
    EXPECT_EQ(fresh.r2, 0.5);
    EXPECT_EQ(fresh.tau[0], 0);

    PixelStats s;
    s.r2 = 0.5;
    const double phi1[3] = {1, 2, 3};
    progressive_update(s, 10, phi1, 0.7);
    const PixelStats before = s;
    progressive_update(s, 0, phi, 0.7);
    EXPECT_EQ(s.n, before.n);
    EXPECT_EQ(s.r2, before.r2);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(s.tau[c], before.tau[c]);
}

// One step by hand: N 10 → 10 + 0.5·6 = 13, R² 1 → 13/16, τ (2 + 1)·13/16.
TEST(SppmUpdate, OneStepByHand) {
    PixelStats s;
    s.n = 10;
    s.r2 = 1;
    s.tau[0] = 2;
    const double phi[3] = {1, 0, 0};
    progressive_update(s, 6, phi, 0.5);
    EXPECT_DOUBLE_EQ(s.n, 13);
    EXPECT_DOUBLE_EQ(s.r2, 13.0 / 16.0);
    EXPECT_DOUBLE_EQ(s.tau[0], 3 * 13.0 / 16.0);
    EXPECT_EQ(next_n(10, 0.5, 6), 13);
    EXPECT_EQ(next_r2(1, 10, 13, 6), 13.0 / 16.0);
    EXPECT_EQ(next_tau(2, 1, 0.5), 1.5);
    EXPECT_DOUBLE_EQ(radiance_scale(2, 0.001), 0.001 / (2 * M_PI));
    EXPECT_EQ(radiance_scale(0, 0.001), 0);  // no visible point yet
}

// The pilot: r2 is the largest disc (R₀² max_scale); the kept disc would hold ~k photons.
TEST(SppmUpdate, PilotRule) {
    const PilotRadius a{32, 0.25, 9};                   // R²/R₀² within [0.25, 9]
    const double r2 = 9.0;                              // R₀ = 1, gathered in the largest disc
    EXPECT_DOUBLE_EQ(pilot_r2(a, r2, 64), 4.5);         // twice k: half the area
    EXPECT_DOUBLE_EQ(pilot_r2(a, r2, 32), 9.0);         // exactly k: the largest disc
    EXPECT_DOUBLE_EQ(pilot_r2(a, r2, 3), 9.0);          // too few: no larger than the largest
    EXPECT_DOUBLE_EQ(pilot_r2(a, r2, 1u << 20), 0.25);  // a bright caustic: the smallest
    EXPECT_DOUBLE_EQ(pilot_r2(a, r2, 0), 1.0);          // no photons: R₀ kept
}

// resolve: each pixel is the mean over its slots of direct × scale + τ/(π R² N_emitted); the
// direct and indirect layers hold the two terms and sum to the image; asking for layers does not
// change the image.
TEST(SppmResolve, PixelValueAndLayers) {
    const int w = 4, h = 3, spp = 2;
    std::vector<PixelStats> stats(size_t(w * h * spp));
    for (size_t i = 0; i < stats.size(); ++i) {
        PixelStats& s = stats[i];
        s.r2 = i % 5 == 0 ? 0.0 : 0.01 * double(i + 1);  // some slots without a visible point
        s.n = double(i);
        for (int c = 0; c < 3; ++c) {
            s.tau[c] = 0.37 * double(i + c) + 0.01;
            s.direct[c] = 1.0 / double(i + c + 3);
        }
    }
    const double direct_scale = 1.0 / 7, emitted = 12345;
    film::Film plain(w, h), layered(w, h);
    resolve(stats, spp, 1.0 / spp, direct_scale, uint64_t(emitted), plain, false, {});
    resolve(stats, spp, 1.0 / spp, direct_scale, uint64_t(emitted), layered, true, {});
    EXPECT_EQ(plain.find_layer("direct"), nullptr);
    const film::Layer* direct = layered.find_layer("direct");
    const film::Layer* indirect = layered.find_layer("indirect");
    ASSERT_NE(direct, nullptr);
    ASSERT_NE(indirect, nullptr);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Rgb v = layered.main().value(x, y), d = direct->value(x, y), l = indirect->value(x, y);
            for (int c = 0; c < 3; ++c) {
                double want_d = 0, want_l = 0;
                for (int s = 0; s < spp; ++s) {
                    const PixelStats& st = stats[size_t((y * w + x) * spp + s)];
                    want_d += st.direct[c] * direct_scale / spp;
                    if (st.r2 > 0) want_l += st.tau[c] / (M_PI * st.r2 * emitted) / spp;
                }
                EXPECT_EQ(v[c], plain.main().value(x, y)[c]);
                EXPECT_NEAR(d[c], want_d, 1e-6 * want_d);
                EXPECT_NEAR(l[c], want_l, 1e-6 * want_l + 1e-30);
                // The layers sum to the image within float rounding of the three values.
                EXPECT_NEAR(d[c] + l[c], v[c], 2 * std::numeric_limits<float>::epsilon() * std::abs(v[c]));
            }
        }
}

}  // namespace
}  // namespace phos::integrators::sppm
