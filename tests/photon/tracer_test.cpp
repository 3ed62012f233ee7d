// Photon tracing (photon/tracer.h): power conservation in a closed grey box (global and indirect
// maps), budget bookkeeping, map classification, thread-count independence and the threads' time.
#include "photon/tracer.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "accel/embree_scene.h"
#include "core/threads.h"
#include "scene/scene.h"
#include "shading/lights.h"
#include "spectrum/color.h"
#include "spectrum/rgb_spectrum.h"

namespace phos::photon {
namespace {

// A closed box [-1, 1]^3 of Lambertian albedo `rho` with an isotropic point light of intensity I at
// its centre, plus optionally a mirror sphere (so caustic photons exist).
struct BoxScene {
    scene::Scene s;
    std::unique_ptr<accel::EmbreeScene> accel;
    std::unique_ptr<shading::LightSet> lights;
    std::unique_ptr<shading::MaterialBsdfs> bsdfs;
    // A sphere of `sphere` material in place of the mirror sphere (`mirror_sphere` then true).
    BoxScene(float rho, float intensity, bool mirror_sphere, const scene::Material* sphere = nullptr) {
        scene::Material grey;
        grey.diffuse = Rgb(rho);
        s.materials.push_back(grey);
        scene::Shape box;
        box.kind = scene::Shape::Kind::Box;
        box.box_min = Vec3(-1.0f);
        box.box_max = Vec3(1.0f);
        box.material = 0;
        s.shapes.push_back(box);
        if (mirror_sphere) {
            scene::Material m;
            m.specular = Rgb(1.0f);
            m.shininess = 1e6f;
            s.materials.push_back(sphere ? *sphere : m);
            scene::Shape sp;
            sp.kind = scene::Shape::Kind::Sphere;
            sp.center = Vec3(0.0f, -0.6f, 0.0f);
            sp.radius = 0.3f;
            sp.material = 1;
            s.shapes.push_back(sp);
        }
        scene::Light l;
        l.kind = scene::Light::Kind::Point;
        l.color = Rgb(intensity);
        l.position = Vec3(0.0f, 0.5f, 0.0f);
        s.lights.push_back(l);
        accel = std::make_unique<accel::EmbreeScene>(s);
        lights = std::make_unique<shading::LightSet>(s, accel->bounds());
        bsdfs = std::make_unique<shading::MaterialBsdfs>(s, shading::BsdfOptions{});
    }
    PhotonScene ps(float sharp_exponent = kInf) const {
        return {s, *accel, *lights, *bsdfs, nullptr, sharp_exponent};
    }
};

// The stored power as linear sRGB: each photon's power taken to colour at its own wavelengths.
std::array<double, 3> total_colour(const std::vector<Photon>& v) {
    std::array<double, 3> sum{0, 0, 0};
    for (const Photon& p : v) {
        const Rgb c = p.colour();
        for (int ch = 0; ch < 3; ++ch) sum[size_t(ch)] += c[ch];
    }
    return sum;
}
double average(const std::array<double, 3>& c) { return (c[0] + c[1] + c[2]) / 3; }

// The colour of one photon of a grey light is a Monte Carlo estimate over its four wavelengths
// (drawn uniformly among the 2^16 codes): its relative variance, per channel and for the channels'
// average, by the exact sum over every code. The light's spectrum is its RGB read as an
// illuminant; the mean over the codes must give back that RGB (else the energy checks below would
// test the colour conversion instead of the tracer).
struct ColourNoise {
    std::array<double, 3> channel{};
    double average = 0;
};
ColourNoise grey_light_colour_noise() {
    const spectrum::RgbSpectrum light(Rgb(1.0f), spectrum::RgbSpectrum::Use::Illuminant);
    double m[4] = {0, 0, 0, 0}, m2[4] = {0, 0, 0, 0};
    const int n = spectrum::kWavelengthCodes;
    for (int code = 0; code < n; ++code) {
        const Wavelengths lambda = Wavelengths::from_code(uint16_t(code));
        const Rgb c = spectrum::to_srgb(light.sample(lambda), lambda);
        const double v[4] = {c.r, c.g, c.b, c.average()};
        for (int k = 0; k < 4; ++k) m[k] += v[k], m2[k] += v[k] * v[k];
    }
    ColourNoise noise;
    for (int k = 0; k < 4; ++k) {
        const double mean = m[k] / n;
        EXPECT_NEAR(mean, 1.0, 1e-3) << "channel " << k;
        const double rel_var = (m2[k] / n - mean * mean) / (mean * mean);
        (k < 3 ? noise.channel[size_t(k)] : noise.average) = rel_var;
    }
    return noise;
}

TEST(PhotonTracer, ClosedBoxPowerSumsToFluxOverOneMinusAlbedo) {
    // Every photon bounces until Russian roulette absorbs it (survival probability rho, power
    // unchanged), so the stored count per emitted photon is geometric: mean 1 / (1 - rho), variance
    // rho / (1 - rho)^2. The global map's total power is Phi / (1 - rho), the indirect map's (no
    // direct photons) Phi rho / (1 - rho). With rho = 0.5 and N emitted, the relative standard
    // deviation of the global sum is sqrt(rho) / sqrt(N) = 0.5 % at N = 20000; we allow 5 sigma
    // plus the power encoding's rounding (unbiased, < 0.4 % per photon, averages out).
    // Each emitted photon also draws its wavelengths, and its colour (to_srgb of its power there)
    // is a Monte Carlo estimate of the light's RGB with relative variance v (measured by
    // grey_light_colour_noise: about 0.034 for the channels' average, 0.023 / 0.001 / 0.34 for
    // red / green / blue). The grey walls leave the spectrum's shape alone, so a path's stored
    // count K and its colour C are independent and the relative variance of K C per emission is
    // (1 + var_K) (1 + v) - 1: for the global map's average 0.55 instead of 0.5 (the bound grows
    // by 5 %); blue's, 1.0, about doubles the variance.
    const float rho = 0.5f, I = 2.0f;
    BoxScene box(rho, I, false);
    TraceOptions o;
    o.wanted[kGlobalMap] = o.wanted[kIndirectMap] = true;
    o.wanted[kCausticMap] = false;
    o.target[kGlobalMap] = 40000;
    o.target[kIndirectMap] = 20000;
    o.seed = 7;
    const TracedPhotons t = trace_photons(box.ps(), o);
    const double flux = 4 * kPi * I;
    const double N = double(t.emitted[kGlobalMap]);
    ASSERT_TRUE(t.reached[kGlobalMap]);
    ASSERT_TRUE(t.reached[kIndirectMap]);
    EXPECT_GT(N, 15000);
    const ColourNoise v = grey_light_colour_noise();
    const auto tol = [](double var_K, double v_C, double n) {
        return 5 * std::sqrt(((1 + var_K) * (1 + v_C) - 1) / n) + 0.002;
    };
    // The light is white (RGB I): every channel of the stored colour is flux / (1 - rho).
    const std::array<double, 3> global = total_colour(t.photons[kGlobalMap]);
    const double want_g = flux / (1 - rho);
    EXPECT_NEAR(average(global) / want_g, 1.0, tol(rho, v.average, N));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(global[size_t(c)] / want_g, 1.0, tol(rho, v.channel[size_t(c)], N)) << "channel " << c;
    // Indirect: mean rho / (1 - rho) per emission, variance rho / (1 - rho)^2 -> relative
    // variance 1 / rho (relative std 1 / sqrt(rho N) before the colour noise).
    const double Ni = double(t.emitted[kIndirectMap]);
    const std::array<double, 3> indirect = total_colour(t.photons[kIndirectMap]);
    const double want_i = flux * rho / (1 - rho);
    EXPECT_NEAR(average(indirect) / want_i, 1.0, tol(1 / rho, v.average, Ni));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(indirect[size_t(c)] / want_i, 1.0, tol(1 / rho, v.channel[size_t(c)], Ni))
            << "channel " << c;
    std::printf("[ measured ] stored colour / expected: global %.4f %.4f %.4f, indirect %.4f %.4f %.4f\n",
                global[0] / want_g, global[1] / want_g, global[2] / want_g, indirect[0] / want_i,
                indirect[1] / want_i, indirect[2] / want_i);
    EXPECT_TRUE(t.photons[kCausticMap].empty());
}

TEST(PhotonTracer, SharpGlossyChainsAreCausticsAndStoreNothing) {
    // A glossy sphere (Phong ks 0.9, exponent 200) in the grey box, below the point light. Split at
    // exponent 100 its lobe is followed like a mirror: light reflected by it reaches the box as
    // caustic photons (through the projection map, which must count the sphere as a caster), and
    // no photon is stored on the sphere itself. Their power is the sphere's share of the flux,
    // Phi (1 - cos psi_max) / 2 with sin psi_max = r / d, times the lobe's albedo. The modified
    // Phong lobe's sampling weight is ks (n + 2) / (n + 1) cos theta, so for a narrow lobe the
    // albedo is that at cos theta_i, averaged over the lit cap: <cos theta_i> = int sqrt(1 -
    // (d sin psi / r)^2) sin psi dpsi / int sin psi dpsi over [0, psi_max] (0.664 here, by the
    // midpoint rule below); what the lobe loses below the surface near the silhouette is a few
    // percent. Allowed: 0.95 to 1.0 of that, plus 5 sigma (1/sqrt(N) over N > 4000 photons, times
    // sqrt(1 + v) for the photons' colour noise over their wavelengths, v ~ 0.034: see above).
    // Without the split (infinite exponent) the sphere is an estimated surface: photons are
    // stored on it and nothing is a caustic.
    scene::Material glossy;
    glossy.specular = Rgb(0.9f);
    glossy.shininess = 200;
    const float I = 2.0f;
    const BoxScene box(0.5f, I, true, &glossy);
    const Vec3 centre(0.0f, -0.6f, 0.0f);
    const float radius = 0.3f;
    const auto on_sphere = [&](const std::vector<Photon>& v) {
        size_t n = 0;
        for (const Photon& p : v) n += length(p.position - centre) < radius + 1e-3f;
        return n;
    };
    TraceOptions o;
    o.wanted[kGlobalMap] = o.wanted[kCausticMap] = true;
    o.target[kGlobalMap] = 20000;
    o.target[kCausticMap] = 5000;
    o.seed = 3;
    const TracedPhotons sharp = trace_photons(box.ps(100), o);
    ASSERT_TRUE(sharp.reached[kCausticMap]);
    EXPECT_EQ(on_sphere(sharp.photons[kGlobalMap]), 0u);
    EXPECT_EQ(on_sphere(sharp.photons[kCausticMap]), 0u);
    const double d = 1.1, psi_max = std::asin(radius / d);
    double cos_sum = 0, weight_sum = 0;
    for (int i = 0; i < 10000; ++i) {
        const double psi = (i + 0.5) / 10000 * psi_max, x = d * std::sin(psi) / radius;
        cos_sum += std::sqrt(std::max(0.0, 1 - x * x)) * std::sin(psi);
        weight_sum += std::sin(psi);
    }
    const double albedo = 0.9 * (202.0 / 201.0) * cos_sum / weight_sum;
    const double flux_on_sphere = 4 * kPi * I * (1 - std::cos(psi_max)) / 2;
    const double ratio = average(total_colour(sharp.photons[kCausticMap])) / (albedo * flux_on_sphere);
    const double tol =
        5 * std::sqrt((1 + grey_light_colour_noise().average) / double(sharp.photons[kCausticMap].size()));
    EXPECT_GT(ratio, 0.95 - tol);
    EXPECT_LT(ratio, 1.0 + tol);

    const TracedPhotons plain = trace_photons(box.ps(), o);
    EXPECT_TRUE(plain.photons[kCausticMap].empty());
    EXPECT_GT(on_sphere(plain.photons[kGlobalMap]), 0u);
}

TEST(PhotonTracer, BudgetsStopJustAfterTheTarget) {
    BoxScene box(0.5f, 1.0f, true);
    TraceOptions o;
    o.target[kGlobalMap] = 10000;
    o.target[kCausticMap] = 3000;
    o.caustic_projection = false;  // one stream: the caustic map's emissions compare with the global's
    const TracedPhotons t = trace_photons(box.ps(), o);
    for (int m : {kGlobalMap, kCausticMap}) {
        EXPECT_TRUE(t.reached[m]);
        // Only the photons of the emission that crossed the target are added beyond it.
        EXPECT_GE(t.photons[m].size(), o.target[m]);
        EXPECT_LE(t.photons[m].size(), o.target[m] + 17);
    }
    // The caustic map needs more emissions than the global one, and both were counted.
    EXPECT_GT(t.emitted[kCausticMap], t.emitted[kGlobalMap]);
    EXPECT_GE(t.total_emitted, t.emitted[kCausticMap]);
    // Every caustic photon is also a global photon of some path: the caustic map's power per
    // emission cannot exceed the global map's.
    EXPECT_LT(average(total_colour(t.photons[kCausticMap])), average(total_colour(t.photons[kGlobalMap])));
}

TEST(PhotonTracer, FixedEmissionCountFillsEveryWantedMap) {
    BoxScene box(0.5f, 1.0f, true);
    TraceOptions o;
    o.emit = 5000;
    o.wanted[kIndirectMap] = true;
    o.caustic_projection = false;  // one stream for every map
    const TracedPhotons t = trace_photons(box.ps(), o);
    EXPECT_EQ(t.total_emitted, 5000u);
    for (int m = 0; m < kMapCount; ++m) EXPECT_EQ(t.emitted[m], o.wanted[m] ? 5000u : 0u);
    // Direct photons are in the global map but not in the indirect one.
    EXPECT_GT(t.photons[kGlobalMap].size(), t.photons[kIndirectMap].size() + 4000);
    EXPECT_GT(t.photons[kCausticMap].size(), 0u);
}

// Targets for the global and caustic maps, filled in batches of 1024 emissions.
TraceOptions global_and_caustic(uint64_t global, uint64_t caustic) {
    TraceOptions o;
    o.target[kGlobalMap] = global;
    o.target[kCausticMap] = caustic;
    o.batch_size = 1024;
    return o;
}

TEST(PhotonTracer, IdenticalAtAnyThreadCount) {
    BoxScene box(0.6f, 1.0f, true);
    TraceOptions o = global_and_caustic(30000, 5000);
    // 8 threads keep up to 32 batches in flight, 1 and 2 threads up to 8: the batches traced past
    // a cut differ, the maps must not (about 20 batches of 1024 emissions here). With one stream
    // for both maps, the batches after the global map's cut store caustic photons only: which ones
    // do follows the batches in flight, never the timing.
    ASSERT_NE(batches_in_flight(1), batches_in_flight(8));
    for (bool projection : {true, false}) {
        o.caustic_projection = projection;
        TracedPhotons a, b, c, c2;
        tbb::task_arena(1).execute([&] { a = trace_photons(box.ps(), o); });
        tbb::task_arena(2).execute([&] { b = trace_photons(box.ps(), o); });
        tbb::task_arena(8).execute([&] { c = trace_photons(box.ps(), o); });
        tbb::task_arena(8).execute([&] { c2 = trace_photons(box.ps(), o); });
        for (const TracedPhotons* other : {&b, &c, &c2}) {
            // The emissions counted run to the end of the batch of the last cut, at any thread count.
            EXPECT_EQ(a.total_emitted, other->total_emitted);
            for (int m = 0; m < kMapCount; ++m) {
                ASSERT_EQ(a.photons[m].size(), other->photons[m].size());
                EXPECT_EQ(a.emitted[m], other->emitted[m]);
                if (a.photons[m].empty()) continue;  // memcmp on the null data() of empty maps is undefined
                EXPECT_EQ(0, std::memcmp(a.photons[m].data(), other->photons[m].data(),
                                         a.photons[m].size() * sizeof(Photon)));
            }
        }
        EXPECT_EQ(c.rays, c2.rays);  // the same threads: the same statistics
        EXPECT_TRUE(a.reached[kGlobalMap] && a.reached[kCausticMap]);
        if (!projection) {
            EXPECT_GT(a.emitted[kCausticMap], a.emitted[kGlobalMap] + 2 * o.batch_size);
        }
    }
}

// -v's "threads busy": the batches' time summed over the threads fits in threads x the pipeline's
// time, and on one thread the batches and the commits (one after another there) fit in it.
TEST(PhotonTracer, ThreadTimesFitThePipelines) {
    BoxScene box(0.6f, 1.0f, true);
    const TraceOptions o = global_and_caustic(20000, 3000);
    for (int threads : {1, 3}) {
        TracedPhotons t;
        int workers = 0;  // the arena's threads, at most the machine's
        tbb::task_arena(threads).execute([&] {
            workers = worker_threads();
            t = trace_photons(box.ps(), o);
        });
        ASSERT_EQ(workers, t.threads);
        EXPECT_GT(t.batch_seconds, 0.0);
        EXPECT_GT(t.commit_seconds, 0.0);
        EXPECT_LE(t.batch_seconds, workers * t.pipeline_seconds);
        EXPECT_LE(t.commit_seconds, t.pipeline_seconds);
        if (threads == 1) {
            EXPECT_LE(t.batch_seconds + t.commit_seconds, t.pipeline_seconds);
        }
    }
}

// The wavefront (16 photons per rtcIntersect16) must store exactly what the one-photon-at-a-time
// loop stores: the same photons in the same order in every map, the same emission counts and
// rays, with the caustic stream (projection maps), an analytic sphere, the box's triangles,
// bounce records and a depth limit that cuts paths; and a scene with an interface-only surface
// (which only the one-at-a-time walk steps through) gives the same maps with packets asked for.
TEST(PhotonTracer, PacketWavefrontStoresWhatTheLoopStores) {
    const auto expect_same = [](const PhotonScene& ps, TraceOptions o) {
        TraceOptions loop = o;
        loop.packets = false;
        o.packets = true;
        const TracedPhotons a = trace_photons(ps, o), b = trace_photons(ps, loop);
        EXPECT_EQ(a.rays, b.rays);
        EXPECT_EQ(a.total_emitted, b.total_emitted);
        size_t stored = 0;
        for (int m = 0; m < kMapCount; ++m) {
            ASSERT_EQ(a.photons[m].size(), b.photons[m].size()) << map_name(m);
            EXPECT_EQ(a.emitted[m], b.emitted[m]);
            EXPECT_EQ(a.bounces[m], b.bounces[m]);
            stored += a.photons[m].size();
            if (a.photons[m].empty()) continue;
            EXPECT_EQ(0, std::memcmp(a.photons[m].data(), b.photons[m].data(),
                                     a.photons[m].size() * sizeof(Photon)))
                << map_name(m);
        }
        EXPECT_GT(stored, 0u);
    };
    BoxScene box(0.7f, 1.0f, true);
    TraceOptions o;
    o.target[kGlobalMap] = 40000;
    o.target[kCausticMap] = 4000;
    o.batch_size = 1000;
    o.record_bounces = true;
    expect_same(box.ps(), o);
    o.max_depth = 2;
    o.record_bounces = false;
    expect_same(box.ps(), o);

    BoxScene walled(0.7f, 1.0f, true);
    scene::Material interface;
    interface.interface_only = true;
    walled.s.materials.push_back(interface);
    scene::Shape pane;
    pane.kind = scene::Shape::Kind::Sphere;
    pane.center = Vec3(0.5f, 0.0f, 0.0f);
    pane.radius = 0.2f;
    pane.material = int(walled.s.materials.size()) - 1;
    walled.s.shapes.push_back(pane);
    walled.accel = std::make_unique<accel::EmbreeScene>(walled.s);
    o.max_depth = 16;
    expect_same(walled.ps(), o);
}

TEST(PhotonTracer, RecordedBounceCountsFollowTheRouletteAndChangeNothing) {
    // In the closed box every emitted photon hits a wall first (bounce 0, stored in the global map)
    // and survives each bounce with probability rho, so the global map holds exactly N photons with
    // 0 bounces and about N rho^k with k bounces (binomial: 5 sigma). The indirect map has none
    // with 0. Recording changes no photon.
    const float rho = 0.5f;
    BoxScene box(rho, 1.0f, false);
    TraceOptions o;
    o.emit = 20000;
    o.wanted[kIndirectMap] = true;
    o.wanted[kCausticMap] = false;
    const TracedPhotons plain = trace_photons(box.ps(), o);
    o.record_bounces = true;
    const TracedPhotons t = trace_photons(box.ps(), o);
    for (int m = 0; m < kMapCount; ++m) {
        ASSERT_EQ(t.bounces[m].size(), t.photons[m].size()) << map_name(m);
        ASSERT_EQ(t.photons[m].size(), plain.photons[m].size());
        EXPECT_TRUE(plain.bounces[m].empty());
        if (t.photons[m].empty()) continue;
        EXPECT_EQ(0, std::memcmp(t.photons[m].data(), plain.photons[m].data(),
                                 t.photons[m].size() * sizeof(Photon)));
    }
    std::vector<double> count(8, 0.0);
    for (uint8_t b : t.bounces[kGlobalMap]) count[std::min<size_t>(b, 7)] += 1;
    const double N = double(t.emitted[kGlobalMap]);
    EXPECT_EQ(count[0], N);
    for (int k = 1; k < 5; ++k) {
        const double p = std::pow(double(rho), k);
        EXPECT_NEAR(count[size_t(k)] / N, p, 5 * std::sqrt(p * (1 - p) / N)) << k << " bounces";
    }
    for (uint8_t b : t.bounces[kIndirectMap]) ASSERT_GE(b, 1);

    // Caustic photons arrive after the mirror sphere: at least one bounce each.
    BoxScene mirror(rho, 1.0f, true);
    TraceOptions c;
    c.target[kCausticMap] = 2000;
    c.record_bounces = true;
    const TracedPhotons tc = trace_photons(mirror.ps(), c);
    ASSERT_EQ(tc.bounces[kCausticMap].size(), tc.photons[kCausticMap].size());
    ASSERT_FALSE(tc.bounces[kCausticMap].empty());
    for (uint8_t b : tc.bounces[kCausticMap]) ASSERT_GE(b, 1);
}

}  // namespace
}  // namespace phos::photon
