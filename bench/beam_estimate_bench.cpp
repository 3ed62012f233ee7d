// The beam radiance estimate against ray marching with the k-nearest volume estimate, per camera
// ray, on the same volume photons: 200 k photons uniformly in a unit box of grey fog (sigma_t
// 0.22, as ../shared/bench/media/fog-caustic), k = 60, maximum radius 0.087 and a march step of
// half of it (photonmap's defaults for that scene). Rays cross the box from random points on its
// front face. Also the preprocessing the beam estimate needs: the per-photon radii (one k-nearest
// query per photon) and the BVH build. The two estimates of one ray agree to a few per cent (they
// are both consistent estimates of the same integral); the setup prints their ratio over all rays.
//
//   build/beam_estimate_bench                (Google Benchmark flags apply; PHOS_BEAM_LEAF=N)
// Rates are per CPU second of the querying thread.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/rng.h"
#include "photon/beam_estimate.h"
#include "photon/volume_estimate.h"
#include "scene/medium.h"

namespace {

using namespace phos;
using namespace phos::photon;

constexpr int kPhotons = 200000;
constexpr uint32_t kK = 60;
constexpr float kMaxRadius = 0.087f;
constexpr float kStep = 0.5f * kMaxRadius;
constexpr int kRays = 4096;

// BVH leaf size: BeamBvh's default, or PHOS_BEAM_LEAF to re-tune (4: 72 us per ray, 16: 57, 32: 63
// on this machine).
uint32_t leaf_size() {
    const char* v = std::getenv("PHOS_BEAM_LEAF");
    return v ? uint32_t(std::max(1, std::atoi(v))) : BeamBvh::kDefaultLeafSize;
}

struct Setup {
    PhotonKdTree map;
    BeamBvh bvh;
    shading::Medium medium;
    std::vector<Vec3> o, d;

    static scene::Medium fog() {
        scene::Medium m;
        m.sigma_a = Rgb(0.02f);
        m.sigma_s = Rgb(0.2f);
        m.g = 0.3f;
        return m;
    }
    Setup() : medium(fog()) {
        Sampler rng(1);
        std::vector<Photon> photons;
        for (int i = 0; i < kPhotons; ++i) {
            const Vec3 p(rng.next(), rng.next(), rng.next());
            const Vec3 wi(rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f);
            photons.push_back(
                Photon(p, Spectrum(1.0f / kPhotons), Wavelengths::visible(rng.next()), wi, Vec3(0.0f)));
        }
        map.build(photons);
        bvh.build(photon_spheres(map, kK, kMaxRadius), leaf_size());
        for (int i = 0; i < kRays; ++i) {
            o.push_back(Vec3(rng.next(), rng.next(), 1.0f));
            d.push_back(normalize(Vec3(rng.next() - 0.5f, rng.next() - 0.5f, -1.0f)));
        }
    }
    // Where ray i leaves the unit box.
    float t_end(int i) const {
        float t = kInf;
        for (int a = 0; a < 3; ++a) {
            if (d[i][a] > 0) t = std::min(t, (1.0f - o[i][a]) / d[i][a]);
            if (d[i][a] < 0) t = std::min(t, -o[i][a] / d[i][a]);
        }
        return t;
    }
    Rgb beam(int i) const {
        const StretchTransmittance T(medium, o[i], d[i], t_end(i), kStep, 0.5f);
        return beam_radiance_estimate(bvh, o[i], d[i], T, medium.phase());
    }
    // photonmap's march: T(t) dt times the k-nearest estimate at jittered steps.
    Rgb march(int i, float jitter) const {
        const float t_end_i = t_end(i);
        const int n = std::max(1, int(std::ceil(t_end_i / kStep)));
        const float dt = t_end_i / float(n);
        const VolumeEstimateOptions opt{kK, kMaxRadius};
        Rgb sum(0.0f);
        for (int k = 0; k < n; ++k) {
            const float t = (float(k) + jitter) * dt;
            sum += exp(medium.sigma_t_rgb() * -t) * dt *
                   volume_radiance_estimate(map, opt, o[i] + d[i] * t, -d[i], medium.phase());
        }
        return sum;
    }
};

const Setup& setup() {
    static const Setup s = [] {
        Setup x;
        double b = 0, m = 0;
        for (int i = 0; i < kRays; ++i) b += x.beam(i).g, m += x.march(i, 0.5f).g;
        std::printf("beam / march over %d rays: %.4f\n", kRays, b / m);
        return x;
    }();
    return s;
}

void BM_Beam(benchmark::State& state) {
    const Setup& s = setup();
    int i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(s.beam(i));
        i = (i + 1) % kRays;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Beam);

void BM_March(benchmark::State& state) {
    const Setup& s = setup();
    int i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(s.march(i, 0.5f));
        i = (i + 1) % kRays;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_March);

void BM_PhotonRadii(benchmark::State& state) {
    const Setup& s = setup();
    for (auto _ : state) benchmark::DoNotOptimize(photon_spheres(s.map, kK, kMaxRadius));
    state.SetItemsProcessed(state.iterations() * kPhotons);
}
BENCHMARK(BM_PhotonRadii)->Unit(benchmark::kMillisecond);

void BM_BeamBvhBuild(benchmark::State& state) {
    const Setup& s = setup();
    const std::vector<PhotonSphere> spheres(s.bvh.spheres().begin(), s.bvh.spheres().end());
    for (auto _ : state) {
        BeamBvh b;
        b.build(spheres);
        benchmark::DoNotOptimize(b.size());
    }
    state.SetItemsProcessed(state.iterations() * kPhotons);
}
BENCHMARK(BM_BeamBvhBuild)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
