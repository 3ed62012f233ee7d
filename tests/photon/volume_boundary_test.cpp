// The volume estimates beside a surface (photon/volume_estimate.h, photon/beam_estimate.h with
// `surfaces`): photons spread uniformly over a box standing on a floor quad, each of flat power 1
// at the same wavelengths (colour C, to_srgb of that power there), so the in-scattered radiance
// per unit length is the same everywhere, C n / V / (4 pi) for isotropic scattering. Just above the floor the
// kernels' balls reach below it, where no photon can be. The k-nearest estimate that divides by the open part
// of its ball (photon/open_ball.h) reads the true value there; the beam estimate, whose balls are the
// photons' own, keeps the power of the photons beside the floor (the slab next to it averages the true
// value); the plain estimates read clearly low. This is the cause of the photon mapper's dark smoke next to
// walls that the agreement matrix found.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "accel/embree_scene.h"
#include "core/rng.h"
#include "photon/beam_bvh.h"
#include "photon/beam_estimate.h"
#include "photon/volume_estimate.h"
#include "scene/medium.h"
#include "spectrum/color.h"
#include "support/shapes.h"

namespace phos::photon {
namespace {

constexpr int kPhotons = 200000;
// The box [-1, 1] x [0, 1] x [-1, 1]: volume 4.
constexpr double kVolume = 4.0;

// Every photon's wavelengths.
Wavelengths photon_wavelengths() { return Wavelengths::visible(0.5f); }

// The red channel (what the checks read) of n / V times the isotropic phase times the photons'
// colour.
double truth() {
    const Rgb colour = spectrum::to_srgb(Spectrum(1.0f), photon_wavelengths());
    return kPhotons / kVolume / (4 * M_PI) * colour.r;
}

std::vector<Photon> uniform_photons() {
    Sampler rng(17);
    std::vector<Photon> v;
    v.reserve(kPhotons);
    for (int i = 0; i < kPhotons; ++i) {
        const Vec3 p(2 * rng.next() - 1, rng.next(), 2 * rng.next() - 1);
        const Vec3 wi = normalize(Vec3(rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f));
        v.push_back(Photon(p, Spectrum(1.0f), photon_wavelengths(), wi, Vec3(0.0f)));
    }
    return v;
}

shading::Medium vacuum_like() {
    scene::Medium m;
    m.sigma_a = Rgb(0.0f);
    m.sigma_s = Rgb(1e-6f);
    m.g = 0;
    return shading::Medium(m);
}

TEST(VolumeBoundary, KNearestEstimateBesideAFloorReadsTheTrueDensity) {
    const scene::Scene s = testing::floor_scene();
    const accel::EmbreeScene accel(s);
    const PhotonKdTree map(uniform_photons());
    const shading::Medium medium = vacuum_like();
    VolumeEstimateOptions plain{60, 0.3f, nullptr}, open{60, 0.3f, &accel};
    // 64 points 0.02 above the floor, away from the box's other sides.
    double sum_plain = 0, sum_open = 0;
    int n = 0;
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j, ++n) {
            const Vec3 x(-0.56f + 0.16f * float(i), 0.02f, -0.56f + 0.16f * float(j));
            sum_plain += volume_radiance_estimate(map, plain, x, Vec3(0, 0, 1), medium.phase())[0];
            sum_open += volume_radiance_estimate(map, open, x, Vec3(0, 0, 1), medium.phase())[0];
        }
    const double want = truth();
    const double r_plain = sum_plain / n / want, r_open = sum_open / n / want;
    std::printf("[ measured ] k-nearest 0.02 above the floor: plain %.4f, open part %.4f of the truth\n",
                r_plain, r_open);
    // 64 estimates of 60 photons: the mean's noise is about 1.6 %; the plain estimate's ball
    // (radius ~0.09) is about a third below the floor.
    EXPECT_NEAR(r_open, 1.0, 0.06);
    EXPECT_LT(r_plain, 0.85);
}

TEST(VolumeBoundary, BeamEstimateKeepsThePowerOfPhotonsBesideAFloor) {
    // The beam estimate's balls are the photons' own, so the correction divides each photon's power
    // by its ball's open share: what a photon beside the floor would have spread below it is spread
    // over the rest of its ball instead. That conserves the power next to the floor, not the value
    // at each point (within a radius of the floor points read a little low and points a radius
    // away a little high), so the check is on the slab 0 < y < 0.3 (three radii) as a whole: rays
    // along +x at heights spread evenly through it average the true value.
    const scene::Scene s = testing::floor_scene();
    const accel::EmbreeScene accel(s);
    const PhotonKdTree map(uniform_photons());
    const shading::Medium medium = vacuum_like();
    BeamBvh plain, open;
    plain.build(photon_spheres(map, 60, 0.3f));
    open.build(photon_spheres(map, 60, 0.3f, &accel));
    double sum_plain = 0, sum_open = 0, near_plain = 0, near_open = 0;
    int n = 0;
    for (int i = 0; i < 60; ++i)
        for (int j = 0; j < 4; ++j, ++n) {
            const Vec3 o(-0.5f, 0.0025f + 0.005f * float(i), -0.45f + 0.3f * float(j)), d(1, 0, 0);
            const StretchTransmittance T(medium, o, d, 1.0f, 0.1f, 0.5f);
            const double a = beam_radiance_estimate(plain, o, d, T, medium.phase())[0];
            const double b = beam_radiance_estimate(open, o, d, T, medium.phase())[0];
            sum_plain += a, sum_open += b;
            if (i < 4) near_plain += a, near_open += b;  // within 0.02 of the floor
        }
    const double want = truth();
    const double r_plain = sum_plain / n / want, r_open = sum_open / n / want;
    std::printf(
        "[ measured ] beam estimate over the slab 0 < y < 0.3: plain %.4f, open part %.4f of the truth;"
        " within 0.02 of the floor: plain %.4f, open part %.4f\n",
        r_plain, r_open, near_plain / 16 / want, near_open / 16 / want);
    // 240 rays of length 1 through ~600 balls each: the mean's noise is under 1 %, and the open
    // shares, measured along 16 directions, are each within about 0.03 of the truth (open_ball.h).
    EXPECT_NEAR(r_open, 1.0, 0.025);
    EXPECT_LT(r_plain, 0.98);
    EXPECT_LT(std::abs(r_open - 1), std::abs(r_plain - 1));
    EXPECT_GT(near_open, near_plain * 1.15);
    // Away from the floor the correction changes nothing.
    const Vec3 o(-0.5f, 0.5f, 0.0f), d(1, 0, 0);
    const StretchTransmittance T(medium, o, d, 1.0f, 0.1f, 0.5f);
    EXPECT_FLOAT_EQ(beam_radiance_estimate(open, o, d, T, medium.phase())[0],
                    beam_radiance_estimate(plain, o, d, T, medium.phase())[0]);
}

}  // namespace
}  // namespace phos::photon
