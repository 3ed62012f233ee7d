// Tests of the beam radiance estimate (photon/beam_estimate.h) and the stretch transmittance it
// weights photons with (photon/stretch_transmittance.h):
//  - the photon radii are the k-th nearest distances found by brute force;
//  - in a homogeneous chromatic medium the beam estimate equals the integral along the ray of the
//    3D volume estimate with the same per-photon radii, sum_p p Phi_p [|x - x_p| < r_p] /
//    (4/3 pi r_p^3) times T, computed by fine numerical quadrature (exact for this kernel: the
//    beam estimate integrates each photon's ball along its chord), for segments that pass through
//    the cloud, start inside it and end inside it;
//  - the 2D kernel is normalised: one photon seen through a grid of parallel rays gives back
//    p Phi, and in vacuum a photon on the ray gives K(d, r) = 3 sqrt(r^2 - d^2) / (2 pi r^3);
//  - the transmittance table in a grid medium: integrals consistent with T(t), a constant grid
//    equal to the homogeneous closed form, and T close to exp(-optical depth) by quadrature.
#include "photon/beam_estimate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <vector>

#include "core/rng.h"
#include "photon/knn_brute_force.h"
#include "scene/medium.h"
#include "spectrum/color.h"

namespace phos::photon {
namespace {

scene::Medium homogeneous(Rgb sigma_a, Rgb sigma_s, float g) {
    scene::Medium m;
    m.sigma_a = sigma_a;
    m.sigma_s = sigma_s;
    m.g = g;
    return m;
}

// n photons in the box [-0.5, 0.5] x [-0.5, 0.5] x [0, 2] (around the +z axis), random powers at
// random wavelengths, and random directions.
std::vector<Photon> photon_cloud(int n, uint64_t seed) {
    Sampler rng(seed);
    // The fourth channel and the wavelengths from their own stream: the positions and directions
    // are those of the RGB photons these tests were written with.
    Sampler spectral(seed + 1000);
    std::vector<Photon> v;
    for (int i = 0; i < n; ++i) {
        const Vec3 p(rng.next() - 0.5f, rng.next() - 0.5f, 2.0f * rng.next());
        Spectrum power;
        for (int k = 0; k < 3; ++k) power[k] = 0.2f + rng.next();
        power[3] = 0.2f + spectral.next();
        const Wavelengths lambda = Wavelengths::visible(spectral.next());
        const Vec3 wi(rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f);
        v.push_back(Photon(p, power, lambda, wi, Vec3(0.0f)));
    }
    return v;
}

TEST(BeamEstimate, RadiiAreTheKthNearestDistances) {
    const PhotonKdTree map(photon_cloud(3000, 1));
    const uint32_t k = 12;
    const float max_radius = 0.16f;
    const std::vector<PhotonSphere> s = photon_spheres(map, k, max_radius);
    ASSERT_EQ(s.size(), map.size());
    std::vector<Neighbour> nb(k);
    int capped = 0;
    for (size_t i = 0; i < s.size(); ++i) {
        const Photon& ph = map.photon(uint32_t(i));
        EXPECT_EQ(s[i].position, ph.position);
        // A sphere carries its photon's power as colour, at the photon's own wavelengths.
        EXPECT_EQ(s[i].power, ph.colour());
        EXPECT_EQ(s[i].power, spectrum::to_srgb(ph.power(), ph.wavelengths()));
        EXPECT_EQ(s[i].wi, ph.wi());
        const KnnResult r = testing::knn_brute_force(map.photons(), s[i].position, k, kInf, nb.data());
        const float expected = std::min(std::sqrt(r.max_dist2), max_radius);
        capped += expected == max_radius;
        EXPECT_FLOAT_EQ(s[i].radius, expected) << i;
    }
    EXPECT_GT(capped, 0) << "some photons (at the cloud's corners) use the maximum radius";
    EXPECT_LT(capped, int(s.size()) / 4);
    std::printf("[ measured ] %d of %zu photons at the maximum radius\n", capped, s.size());
}

// The 3D estimate's integral along o + t d, t in [0, t_end], with transmittance exp(-sigma_t t)
// per channel: for every photon, the midpoint rule over n steps on the indicator |x_t - x_p| <
// r_p, in double. Photons farther than 1.01 r_p from the line are skipped, and only steps within
// r_p of a photon's projection are visited (the others lie outside its ball). Error: about one
// step per chord end, ~1e-5 relative here.
std::array<double, 3> quadrature_3d(std::span<const PhotonSphere> spheres, Vec3 o, Vec3 d, double t_end,
                                    Rgb sigma_t, const shading::PhaseFunction& phase, int n) {
    const double dt = t_end / n;
    std::array<double, 3> total{0, 0, 0};
    for (const PhotonSphere& s : spheres) {
        const double r = s.radius;
        const double vx = double(s.position.x) - o.x, vy = double(s.position.y) - o.y,
                     vz = double(s.position.z) - o.z;
        const double tp = vx * d.x + vy * d.y + vz * d.z;
        if (vx * vx + vy * vy + vz * vz - tp * tp > 1.0201 * r * r) continue;
        const int i0 = std::max(0, int(std::floor((tp - r) / dt)) - 1);
        const int i1 = std::min(n, int(std::ceil((tp + r) / dt)) + 1);
        std::array<double, 3> chord{0, 0, 0};
        for (int i = i0; i < i1; ++i) {
            const double t = (i + 0.5) * dt;
            const double x = o.x + d.x * t - s.position.x, y = o.y + d.y * t - s.position.y,
                         z = o.z + d.z * t - s.position.z;
            if (x * x + y * y + z * z < r * r)
                for (int c = 0; c < 3; ++c) chord[c] += std::exp(-double(sigma_t[c]) * t) * dt;
        }
        const double w = phase.eval(-d, s.wi) / (4.0 / 3.0 * M_PI * r * r * r);
        for (int c = 0; c < 3; ++c) total[c] += w * s.power[c] * chord[c];
    }
    return total;
}

TEST(BeamEstimate, EqualsTheRayIntegralOfThe3dEstimate) {
    const shading::Medium medium(homogeneous(Rgb(0.1f, 0.3f, 0.6f), Rgb(0.5f, 0.4f, 0.2f), 0.4f));
    const PhotonKdTree map(photon_cloud(4000, 2));
    BeamBvh bvh;
    bvh.build(photon_spheres(map, 20, 0.15f));
    struct Segment {
        const char* what;
        Vec3 o, d;
        float t_end;
    };
    const Segment segments[] = {
        {"through the cloud", Vec3(0.05f, -0.1f, -0.5f), normalize(Vec3(0.02f, 0.05f, 1.0f)), 3.0f},
        {"starting inside", Vec3(0.1f, 0.1f, 0.7f), normalize(Vec3(-0.3f, 0.1f, 1.0f)), 3.0f},
        {"ending inside", Vec3(-0.3f, 0.2f, -0.2f), normalize(Vec3(0.1f, -0.1f, 1.0f)), 1.3f},
        {"across", Vec3(-1.0f, 0.0f, 1.0f), normalize(Vec3(1.0f, 0.2f, 0.1f)), 2.0f},
    };
    for (const Segment& s : segments) {
        const StretchTransmittance T(medium, s.o, s.d, s.t_end, 0.1f, 0.5f);
        uint32_t used = 0;
        const Rgb beam = beam_radiance_estimate(bvh, s.o, s.d, T, medium.phase(), &used);
        EXPECT_GT(used, 100u) << s.what << ": the segment meets many photons";
        const std::array<double, 3> q =
            quadrature_3d(bvh.spheres(), s.o, s.d, s.t_end, medium.sigma_t_rgb(), medium.phase(), 400000);
        for (int c = 0; c < 3; ++c) {
            const double ref = q[c];
            std::printf("[ measured ] %s, channel %d: beam %.6f, quadrature %.6f (%+.2e)\n", s.what, c,
                        beam[c], ref, beam[c] / ref - 1);
            EXPECT_NEAR(beam[c], ref, 2e-4 * ref) << s.what << ", channel " << c;
        }
    }
}

TEST(BeamEstimate, KernelIsNormalised) {
    // One photon at the origin, radius 0.3; rays along +z on an m x m grid of cells covering its
    // disc, in vacuum. The beam estimate integrated over the cells is p Phi (the kernel integrates
    // to 1 over the disc); each ray also gives K(d, r) p Phi.
    const shading::Medium vacuum(homogeneous(Rgb(0.0f), Rgb(0.0f), 0.0f));
    const Rgb power(1.0f, 2.0f, 3.0f);
    const float r = 0.3f;
    BeamBvh bvh;
    bvh.build({{Vec3(0.0f), r, power, Vec3(0, 0, -1)}});
    const Vec3 d(0, 0, 1);
    const float p = vacuum.phase().eval(-d, bvh.spheres()[0].wi);
    const Rgb phi = bvh.spheres()[0].power;
    const int m = 600;
    const double cell = 2.0 * r / m;
    double sum = 0;
    for (int i = 0; i < m; ++i) {
        for (int j = 0; j < m; ++j) {
            const Vec3 o(float(-r + (i + 0.5) * cell), float(-r + (j + 0.5) * cell), -1.0f);
            const StretchTransmittance T(vacuum, o, d, 2.0f, 0.1f, 0.5f);
            const float L = beam_radiance_estimate(bvh, o, d, T, vacuum.phase()).g;
            const double d2 = double(o.x) * o.x + double(o.y) * o.y;
            const double K = d2 < r * r ? 3 * std::sqrt(r * r - d2) / (2 * M_PI * r * r * r) : 0.0;
            // Float rounding of r^2 - d^2 grows towards the rim: 1e-4 of the kernel's peak.
            const double K_peak = 3 / (2 * M_PI * r * r);
            ASSERT_NEAR(L, K * p * phi.g, 1e-4 * K_peak * p * phi.g) << i << " " << j;
            sum += L * cell * cell;
        }
    }
    std::printf("[ measured ] kernel integral over the disc: %.6f (expected %.6f)\n", sum, p * phi.g);
    // The midpoint rule on the disc's edge (where K has a square-root singularity): ~1e-4 here.
    EXPECT_NEAR(sum, p * phi.g, 1e-3 * p * phi.g);
}

// ---- the stretch transmittance ----

TEST(StretchTransmittance, HomogeneousIsExact) {
    const shading::Medium m(homogeneous(Rgb(0.2f, 0.5f, 1.0f), Rgb(0.3f, 0.5f, 0.0f), 0.0f));
    const Vec3 o(0.0f), d(1, 0, 0);
    const StretchTransmittance T(m, o, d, 4.0f, 0.1f, 0.3f);
    EXPECT_FLOAT_EQ(T.end(), 4.0f);
    for (int c = 0; c < 3; ++c) {
        const double s = m.sigma_t_rgb()[c];
        EXPECT_NEAR(T.at(1.5f)[c], std::exp(-s * 1.5), 1e-6);
        EXPECT_NEAR(T.total()[c], std::exp(-s * 4.0), 1e-6);
        const double I = (std::exp(-s * 0.7) - std::exp(-s * 3.1)) / s;
        EXPECT_NEAR(T.integral(0.7f, 3.1f)[c], I, 1e-6 * I);
        // A short chord far along: no cancellation.
        const double L = double(3.0001f) - 3.0;  // the chord the floats describe
        const double J = std::exp(-s * 3.0) * (1 - std::exp(-s * L)) / s;
        EXPECT_NEAR(T.integral(3.0f, 3.0001f)[c], J, 1e-5 * J);
    }
    // Thick: the table ends where every channel is below 1e-4 (the thinnest channel, 0.5).
    const shading::Medium thick(homogeneous(Rgb(0.5f, 1.0f, 2.0f), Rgb(0.0f), 0.0f));
    const StretchTransmittance U(thick, o, d, 100.0f, 0.1f, 0.3f);
    EXPECT_NEAR(U.end(), std::log(1e4) / 0.5, 1e-4);
}

scene::Medium grid(std::vector<float> density, int n) {
    scene::Medium g = homogeneous(Rgb(0.3f, 0.6f, 0.9f), Rgb(0.9f, 0.6f, 0.3f), 0.0f);
    g.kind = scene::Medium::Kind::UniformGrid;
    g.nx = g.ny = g.nz = n;
    g.density = std::move(density);
    g.p0 = Vec3(-1.0f);
    g.p1 = Vec3(1.0f);
    return g;
}

TEST(StretchTransmittance, ConstantGridEqualsTheClosedForm) {
    // Density 1 everywhere inside (trilinear between equal samples is constant, but the outermost
    // half cells fade to 0 at the border: stay in the inner part).
    const shading::Medium g(grid(std::vector<float>(8 * 8 * 8, 1.0f), 8));
    const shading::Medium h(homogeneous(Rgb(0.3f, 0.6f, 0.9f), Rgb(0.9f, 0.6f, 0.3f), 0.0f));
    const Vec3 o(-0.8f, 0.1f, 0.0f), d(1, 0, 0);
    const StretchTransmittance Tg(g, o, d, 1.6f, 0.07f, 0.4f), Th(h, o, d, 1.6f, 0.07f, 0.4f);
    for (float a : {0.0f, 0.13f, 0.5f, 1.2f}) {
        for (float b : {a, a + 0.01f, a + 0.3f, 1.6f}) {
            if (b > 1.6f) continue;
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(Tg.integral(a, b)[c], Th.integral(a, b)[c], 2e-6) << a << " " << b;
                EXPECT_NEAR(Tg.at(b)[c], Th.at(b)[c], 2e-6) << b;
            }
        }
    }
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(Tg.total()[c], Th.total()[c], 2e-6);
}

TEST(StretchTransmittance, VaryingGridIsConsistent) {
    // A smooth blob: density = 2 exp(-4 |cell centre|^2) on a 16^3 grid.
    const int n = 16;
    std::vector<float> dens;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const Vec3 p =
                    Vec3(float(x) + 0.5f, float(y) + 0.5f, float(z) + 0.5f) * (2.0f / n) - Vec3(1.0f);
                dens.push_back(2.0f * std::exp(-4.0f * dot(p, p)));
            }
    const shading::Medium g(grid(dens, n));
    const Vec3 o(-1.2f, 0.1f, -0.05f), d = normalize(Vec3(1.0f, 0.05f, 0.02f));
    const float t_end = 2.4f;
    const StretchTransmittance T(g, o, d, t_end, 0.02f, 0.5f);
    ASSERT_FLOAT_EQ(T.end(), t_end);
    // The integral over any interval equals the quadrature of T.at: the two read one table.
    const int steps = 20000;
    for (auto [a, b] : {std::pair{0.0f, 2.4f}, std::pair{0.31f, 0.33f}, std::pair{0.9f, 1.7f}}) {
        Rgb q(0.0f);
        const float h = (b - a) / steps;
        for (int i = 0; i < steps; ++i) q += T.at(a + (float(i) + 0.5f) * h) * h;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(T.integral(a, b)[c], q[c], 1e-4 * q[c]) << a << " " << b;
    }
    // T against exp(-optical depth) by quadrature of sigma_t: the table's steps of 0.02 sample a
    // density that varies over ~0.5 (midpoint-like error ~1e-4 of the depth).
    for (float t : {0.5f, 1.2f, 2.4f}) {
        Rgb depth(0.0f);
        const float h = t / steps;
        for (int i = 0; i < steps; ++i) depth += g.sigma_t_rgb(o + d * ((float(i) + 0.5f) * h)) * h;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(T.at(t)[c], std::exp(-depth[c]), 2e-3) << t;
    }
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(T.total()[c], T.at(t_end)[c], 1e-6);
}

}  // namespace
}  // namespace phos::photon
