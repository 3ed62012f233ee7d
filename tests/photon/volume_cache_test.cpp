// Tests of the volume cache (photon/volume_cache.h):
//  - in an isotropic medium (g = 0) a lookup at a cache point gives exactly the two maps' k-nearest
//    estimates there (the first-order expansion is exact for g = 0);
//  - for g != 0 it is the first-order Legendre expansion: with every photon arriving from one
//    direction d the estimate is F0 (1 + 3 g mu) / 4 pi, mu = cos(-wo, d), which is within O(g^2) of
//    the exact Henyey-Greenstein value;
//  - lookups farther than the maximum radius from every cache point fail (the caller falls back to
//    the full estimate), and the cache is the same whatever the thread count.
#include "photon/volume_cache.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "shading/phase.h"

namespace phos::photon {
namespace {

std::vector<Photon> cloud(int n, uint64_t seed, const Vec3* direction = nullptr) {
    Sampler rng(seed);
    // The fourth channel and the wavelengths from their own stream: the positions and directions
    // are those of the RGB photons these tests were written with.
    Sampler spectral(seed + 1000);
    std::vector<Photon> v;
    for (int i = 0; i < n; ++i) {
        const Vec3 p(rng.next(), rng.next(), rng.next());
        Spectrum power;
        for (int k = 0; k < 3; ++k) power[k] = 0.2f + rng.next();
        power[3] = 0.2f + spectral.next();
        const Wavelengths lambda = Wavelengths::visible(spectral.next());
        const Vec3 wi =
            direction ? *direction : Vec3(rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f);
        v.push_back(Photon(p, power, lambda, normalize(wi), Vec3(0.0f)));
    }
    return v;
}

TEST(VolumeCache, IsotropicLookupEqualsTheFullEstimates) {
    const PhotonKdTree volume(cloud(4000, 1)), caustic(cloud(2000, 2));
    const VolumeEstimateOptions vo{40, 0.2f}, co{20, 0.1f};
    VolumeCache cache;
    cache.build(volume, vo, caustic, co, 8);
    ASSERT_EQ(cache.size(), 500u);
    const shading::PhaseFunction iso{0.0f};
    for (int i = 0; i < 4000; i += 97) {
        const Vec3 x = volume.photon(uint32_t(i)).position;
        const Vec3 wo = normalize(Vec3(0.3f, -0.5f, 0.8f));
        Rgb cached;
        ASSERT_TRUE(cache.lookup(x, 0.2f, wo, 0.0f, cached));
        // the cache point nearest to x: the estimate there is what the lookup must return
        Rgb best(0.0f);
        float best_d2 = 1e30f;
        for (int j = 0; j < 4000; j += 8) {
            const Vec3 y = volume.photon(uint32_t(j)).position;
            const float d2 = dot(y - x, y - x);
            if (d2 < best_d2)
                best_d2 = d2, best = volume_radiance_estimate(volume, vo, y, wo, iso) +
                                     volume_radiance_estimate(caustic, co, y, wo, iso);
        }
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(cached[c], best[c], 1e-5f * best[c]) << i;
    }
}

TEST(VolumeCache, FirstOrderExpansionOfHenyeyGreenstein) {
    const Vec3 d = normalize(Vec3(0.2f, 1.0f, -0.3f));
    const PhotonKdTree volume(cloud(3000, 3, &d)), none;
    const VolumeEstimateOptions vo{50, 0.25f};
    const Vec3 x(0.5f, 0.5f, 0.5f);
    const VolumeMoments m = volume_moments(volume, vo, x);
    const Vec3 wi = volume.photon(0).wi();  // d as the photon record stores it
    for (const float g : {-0.3f, 0.05f, 0.3f})
        for (const Vec3 wo : {normalize(Vec3(1, 0, 0)), -wi, wi, normalize(Vec3(-0.4f, 0.2f, 0.9f))}) {
            const float mu = dot(-wo, wi);
            const Rgb e = m.estimate(wo, g);
            const Rgb exact =
                volume_radiance_estimate(volume, vo, x, wo, shading::PhaseFunction{g});  // F0 * HG(mu)
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(e[c], std::max(0.0f, m.f0[c] * (1 + 3 * g * mu)) / (4 * kPi), 1e-4f * m.f0[c]);
                // the neglected orders are O(g^2): small for a weakly anisotropic medium
                if (std::fabs(g) < 0.1f) {
                    EXPECT_NEAR(e[c], exact[c], 0.03f * exact[c]) << g << " " << mu;
                }
            }
        }
    VolumeCache empty_caustic;
    empty_caustic.build(volume, vo, none, vo, 1);
    Rgb e;
    EXPECT_FALSE(empty_caustic.lookup(Vec3(5, 5, 5), 0.25f, Vec3(0, 0, 1), 0.0f, e));
    EXPECT_TRUE(empty_caustic.lookup(x, 0.25f, Vec3(0, 0, 1), 0.0f, e));
}

TEST(VolumeCache, SameAtOneAndTwoThreads) {
    const PhotonKdTree volume(cloud(3000, 5)), caustic(cloud(1000, 6));
    const VolumeEstimateOptions vo{30, 0.2f}, co{15, 0.1f};
    VolumeCache a, b;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        a.build(volume, vo, caustic, co, 3);
    }
    {
        tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
        b.build(volume, vo, caustic, co, 3);
    }
    Sampler rng(9);
    for (int i = 0; i < 200; ++i) {
        const Vec3 x(rng.next(), rng.next(), rng.next());
        Rgb ea, eb;
        ASSERT_EQ(a.lookup(x, 0.2f, Vec3(0, 1, 0), 0.3f, ea), b.lookup(x, 0.2f, Vec3(0, 1, 0), 0.3f, eb));
        EXPECT_EQ(ea, eb);
    }
}

}  // namespace
}  // namespace phos::photon
