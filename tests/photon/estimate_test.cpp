// Photon density estimates (photon/estimate.h, photon/filter.h): filter normalisation on a uniform
// density, the surface test (thin walls, corners), the irradiance cache, and convergence of the
// radiance estimate of a diffuse plane under a point light to the analytic value.
#include "photon/estimate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "accel/embree_scene.h"
#include "core/rng.h"
#include "photon/irradiance_cache.h"
#include "photon/tracer.h"
#include "shading/lights.h"
#include "spectrum/color.h"

namespace phos::photon {
namespace {

// The wavelengths of every hand-built photon below. Their colours are then exactly
// to_srgb(power, lambda), and a strongly coloured one (about (1.47, 0.94, 0.49) for a flat power 1)
// shows an estimate that does not take each photon's power to colour at its own wavelengths.
Wavelengths photon_wavelengths() { return Wavelengths::visible(0.5f); }

// The colour of one photon of flat power `power` as the record stores it (the estimates sum these).
Rgb photon_colour(float power) {
    return Photon(Vec3(0.0f), Spectrum(power), photon_wavelengths(), Vec3(0, 0, 1), Vec3(0, 0, 1)).colour();
}

// n photons of flat power `power` each, uniform on the square [-h, h]^2 of the plane z = z0.
std::vector<Photon> uniform_plane(size_t n, float h, float z0, Vec3 normal, float power, uint64_t seed) {
    Sampler s(seed);
    std::vector<Photon> v;
    for (size_t i = 0; i < n; ++i) {
        const Vec2 u = s.next2();
        v.emplace_back(Vec3((2 * u.x - 1) * h, (2 * u.y - 1) * h, z0), Spectrum(power), photon_wavelengths(),
                       normal, normal);
    }
    return v;
}

TEST(PhotonEstimate, PhotonColourIsThePowerAtItsWavelengths) {
    // What the expectations below rest on: the photons' colour is to_srgb of their (rounded) power
    // at their wavelengths, and visibly not grey.
    const Rgb c = photon_colour(1.0f);
    EXPECT_EQ(c, spectrum::to_srgb(Spectrum(1.0f), photon_wavelengths()));
    // Not grey: a channel-for-channel mix-up in the estimates below would show.
    EXPECT_GT(std::max(std::fabs(c.r - c.g), std::fabs(c.b - c.g)), 0.15f * c.g);
}

TEST(PhotonFilter, MeanWeightMatchesNumericalIntegral) {
    for (KernelFilter f : {KernelFilter{FilterKind::Box, 1.1f}, KernelFilter{FilterKind::Cone, 1.1f},
                           KernelFilter{FilterKind::Cone, 2.0f}, KernelFilter{FilterKind::Gauss, 1.1f}}) {
        // Mean of w over the unit disk: integral_0^1 w(d) 2 d dd, midpoint rule.
        double sum = 0;
        const int n = 100000;
        for (int i = 0; i < n; ++i) {
            const double d = (i + 0.5) / n;
            sum += f.weight(float(d * d), 1.0f) * 2 * d / n;
        }
        EXPECT_NEAR(sum, f.mean_weight(), 1e-4) << filter_name(f.kind) << " k " << f.cone_k;
    }
    const KernelFilter cone{FilterKind::Cone, 1.1f}, gauss{FilterKind::Gauss, 1.1f};
    EXPECT_NEAR(cone.mean_weight(), 1 - 2 / 3.3, 1e-6);
    // Jensen's Gaussian: 1 at the centre, alpha-free form.
    EXPECT_NEAR(gauss.weight(0.0f, 1.0f), 1.0f, 1e-6);
}

TEST(PhotonEstimate, UniformDensityIsUnbiasedForEveryFilter) {
    // Density 200000 photons / 4 m^2 of power 1e-5 each: irradiance 0.5 W/m^2. With k = 400 the kNN
    // estimate's own bias is k / (k - 1) = +0.25 % and its relative noise ~1 / sqrt(k) = 5 % per
    // query, ~0.5 % over 100 queries; bound 2 %.
    const auto photons = uniform_plane(200000, 1.0f, 0.0f, Vec3(0, 0, 1), 1e-5f, 3);
    const PhotonKdTree tree(photons);
    const Rgb expected = photon_colour(1e-5f) * (200000 / 4.0f);
    for (FilterKind kind : {FilterKind::Box, FilterKind::Cone, FilterKind::Gauss}) {
        EstimateOptions o;
        o.k = 400;
        o.max_radius = 1.0f;
        o.filter.kind = kind;
        Sampler s(11);
        Rgb sum(0.0f);
        for (int i = 0; i < 100; ++i) {
            const Vec2 u = s.next2();
            SurfaceQuery q;
            q.p = Vec3(u.x - 0.5f, u.y - 0.5f, 0.0f);
            q.n = Vec3(0, 0, 1);
            uint32_t used = 0;
            sum += irradiance_estimate(tree, o, q, &used);
            EXPECT_EQ(used, 400u);
        }
        // Every photon has the same colour: each channel is that colour times the density.
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(sum[c] / 100 / expected[c], 1.0, 0.02) << filter_name(kind) << c;
    }
}

TEST(PhotonEstimate, MinimumRadiusAveragesADenseSpotOverItsDisk) {
    // 1000 photons of power 1e-3 in a 1 mm spot at the origin on a sparse uniform background: the
    // k = 50 estimate at the spot sees only the spot (huge, ~1/mm^2); with a minimum radius of
    // 0.05 it is the spot's power plus the background's over that disk.
    auto photons = uniform_plane(20000, 1.0f, 0.0f, Vec3(0, 0, 1), 1e-5f, 5);
    const auto spot = uniform_plane(1000, 0.0005f, 0.0f, Vec3(0, 0, 1), 1e-3f, 6);
    photons.insert(photons.end(), spot.begin(), spot.end());
    const PhotonKdTree tree(photons);
    EstimateOptions o;
    o.k = 50;
    o.max_radius = 0.5f;
    SurfaceQuery q;
    q.p = Vec3(0.0f);
    q.n = Vec3(0, 0, 1);
    const Rgb plain = irradiance_estimate(tree, o, q);
    q.min_radius = 0.05f;
    uint32_t n = 0;
    const Rgb wide = irradiance_estimate(tree, o, q, &n);
    const double area = kPi * 0.05 * 0.05;
    const Rgb spot_colour = photon_colour(1e-3f), background_colour = photon_colour(1e-5f);
    EXPECT_GT(plain.average(), 10 * (spot_colour * (1000 / float(area))).average());
    for (int c = 0; c < 3; ++c) {
        const double expected = (1000 * spot_colour[c] + 20000 / 4.0 * area * background_colour[c]) / area;
        EXPECT_NEAR(wide[c] / expected, 1.0, 0.02) << c;
    }
    EXPECT_GT(n, 1000u);
    // Where k photons need more than the minimum radius, it changes nothing.
    q.p = Vec3(0.6f, 0.6f, 0.0f);
    const Rgb far_wide = irradiance_estimate(tree, o, q);
    q.min_radius = 0;
    EXPECT_EQ(far_wide, irradiance_estimate(tree, o, q));
}

TEST(PhotonEstimate, SurfaceTestRejectsThinWallsAndCorners) {
    // The query's floor (z = 0, normal +z) has a sparse density; 1 mm below lies the underside of
    // a thin wall lit from below (normal -z), and a perpendicular wall (x = 0.01, normal -x)
    // touches it. Neither may leak into the floor's estimate.
    auto photons = uniform_plane(2000, 1.0f, 0.0f, Vec3(0, 0, 1), 1e-3f, 1);
    auto under = uniform_plane(50000, 1.0f, -0.001f, Vec3(0, 0, -1), 1e-3f, 2);
    photons.insert(photons.end(), under.begin(), under.end());
    Sampler s(5);
    for (int i = 0; i < 50000; ++i) {
        const Vec2 u = s.next2();
        photons.emplace_back(Vec3(0.01f, (2 * u.x - 1), u.y), Spectrum(1e-3f), photon_wavelengths(),
                             Vec3(-1, 0, 0), Vec3(-1, 0, 0));
    }
    // Same-orientation surface 5 cm above (e.g. a shelf): rejected by the flatness test.
    auto shelf = uniform_plane(50000, 1.0f, 0.05f, Vec3(0, 0, 1), 1e-3f, 4);
    photons.insert(photons.end(), shelf.begin(), shelf.end());
    const PhotonKdTree tree(photons);
    EstimateOptions o;
    o.k = 50;
    o.max_radius = 0.5f;
    SurfaceQuery q;
    q.p = Vec3(0.0f, 0.0f, 0.0f);
    q.n = Vec3(0, 0, 1);
    const double expected = (photon_colour(1e-3f) * (2000 / 4.0f)).average();
    EXPECT_NEAR(irradiance_estimate(tree, o, q).average() / expected, 1.0, 0.35);
    int leaked = 0;
    for (const Photon& ph : tree.photons())
        if (ph.position.z != 0.0f && length(ph.position - q.p) < 0.2f && accept_photon(ph, q, o)) ++leaked;
    EXPECT_EQ(leaked, 0);
    // Without the surface test the leaked photons dominate.
    EstimateOptions loose = o;
    loose.normal_cos = -1;
    loose.flatness = 0;
    EXPECT_GT(irradiance_estimate(tree, loose, q).average(), 5 * expected);
}

TEST(PhotonEstimate, IrradianceCacheReturnsTheNearestCompatiblePoint) {
    auto photons = uniform_plane(40000, 1.0f, 0.0f, Vec3(0, 0, 1), 1e-4f, 8);
    const PhotonKdTree tree(photons);
    EstimateOptions o;
    o.k = 100;
    o.max_radius = 0.3f;
    IrradianceCache cache;
    cache.build(tree, o, 4);
    EXPECT_EQ(cache.size(), 10000u);
    SurfaceQuery q;
    q.p = Vec3(0.2f, -0.1f, 0.0f);
    q.n = Vec3(0, 0, 1);
    Rgb E;
    ASSERT_TRUE(cache.lookup(q, 0.3f, 0.9f, E));
    const Rgb colour = photon_colour(1e-4f);
    EXPECT_NEAR(E.average() / (colour * (40000 / 4.0f)).average(), 1.0, 0.35);
    // The cached value is the photons' colour (every photon has the same), its channels in order,
    // within the record's rounding (the cache keeps it as a photon's power).
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(E[c] / E.average(), colour[c] / colour.average(),
                    2 * kPowerMaxRelativeError * colour.max() / colour.average())
            << c;
    q.n = Vec3(0, 0, -1);  // the other side has no cache point
    EXPECT_FALSE(cache.lookup(q, 0.3f, 0.9f, E));
}

TEST(PhotonEstimate, PointLitPlaneConvergesToAnalyticRadiance) {
    // A Lambertian floor (albedo 0.5, z = 0... here y = 0) under a point light of intensity I at
    // height h: L = rho / pi * I cos(theta) / d^2. Only direct photons can reach the floor (nothing
    // sends them back), so the global map's estimate must converge to L.
    scene::Scene s;
    scene::Material m;
    m.diffuse = Rgb(0.5f);
    s.materials.push_back(m);
    scene::Shape floor;
    floor.kind = scene::Shape::Kind::Mesh;
    floor.mesh.positions = {{-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}};
    floor.mesh.indices = {0, 1, 2, 0, 2, 3};
    floor.material = 0;
    s.shapes.push_back(floor);
    scene::Light l;
    l.kind = scene::Light::Kind::Point;
    l.color = Rgb(10.0f);
    l.position = Vec3(0.0f, 1.0f, 0.0f);
    s.lights.push_back(l);
    const accel::EmbreeScene accel(s);
    const shading::LightSet lights(s, accel.bounds());
    const shading::MaterialBsdfs bsdfs(s, {});
    const PhotonScene ps{s, accel, lights, bsdfs};
    const Vec3 points[] = {{0, 0, 0}, {0.5f, 0, 0}, {0, 0, -0.8f}, {1.0f, 0, 1.0f}, {-0.3f, 0, 0.4f}};
    double err[3];
    double channel_ratio[3] = {0, 0, 0};  // at 1e6 photons, each channel's ratio averaged over the points
    const uint64_t counts[3] = {10000, 100000, 1000000};
    for (int c = 0; c < 3; ++c) {
        TraceOptions o;
        o.wanted[kCausticMap] = false;
        o.emit = counts[c];
        const TracedPhotons t = trace_photons(ps, o);
        const PhotonKdTree tree(t.photons[kGlobalMap]);
        EstimateOptions eo;
        // A kNN estimate's noise depends on k, its bias on the radius: k = sqrt(N) lets both
        // shrink as N grows (k -> inf, k / N -> 0).
        eo.k = uint32_t(std::sqrt(double(counts[c])));
        eo.max_radius = 1.0f;
        double e = 0;
        for (const Vec3 p : points) {
            const Vec3 d = l.position - p;
            const float L = 0.5f * kInvPi * 10.0f * (d.y / length(d)) / length_squared(d);
            accel::SurfaceHit hit;
            hit.p = p;
            hit.ng = hit.ns = Vec3(0, 1, 0);
            hit.dpdu = Vec3(1, 0, 0);
            hit.material = 0;
            const shading::Bsdf bsdf(m, hit, s);
            const Vec3 wo = normalize(Vec3(0.3f, 1.0f, 0.2f));
            const SurfaceQuery q = make_query(p, hit.ng, wo, bsdf);
            const Rgb estimate = radiance_estimate(tree, eo, q, wo, bsdf);
            const double ratio = estimate.average() / L;
            e += std::fabs(ratio - 1.0);
            if (c == 2)
                for (int ch = 0; ch < 3; ++ch) channel_ratio[ch] += estimate[ch] / L / 5;
        }
        err[c] = e / 5;
    }
    std::printf("mean relative error: %.4f (1e4) %.4f (1e5) %.4f (1e6 photons)\n", err[0], err[1], err[2]);
    EXPECT_LT(err[1], err[0]);
    EXPECT_LT(err[2], err[1]);
    // At 1e6 photons, k = 1000: relative noise ~ 1 / sqrt(1000) = 3 % per point, radius ~ 6-12 cm
    // (density curvature bias < 1 %); 5 % bound on the mean absolute error over the points.
    EXPECT_LT(err[2], 0.05);
    // The light is white and the floor grey, so the radiance is white: each channel of the photons'
    // colours (to_srgb at their own wavelengths) converges as the average does. Their colour noise
    // over the wavelengths adds relative variance ~0.34 per photon to blue (0.02 red, 0.001 green;
    // see tracer_test.cpp), ~2 % per point at k = 1000, ~1 % over the five points, on top of the
    // density noise all channels share.
    std::printf("channel ratios at 1e6 photons: %.4f %.4f %.4f\n", channel_ratio[0], channel_ratio[1],
                channel_ratio[2]);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(channel_ratio[ch], 1.0, 0.05) << ch;
}

}  // namespace
}  // namespace phos::photon
