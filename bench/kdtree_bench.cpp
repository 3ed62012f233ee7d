// Photon k-d tree against nanoflann on the same Cornell-box photons and queries: build time (phos
// on 1 and 2 threads, nanoflann's serial build) and single-threaded query rate for "k nearest
// within a max radius" (k = 50, 200) and a fixed-radius range query, at 1 M and 10 M photons.
// The setup checks that both libraries return identical neighbour sets before timing anything.
// BM_BuildPhosInPlace times the in-place build (build(std::vector&&), the array copied outside
// the timing) at 10 M photons, and at 100 M too with PHOS_BENCH_BIG=1 (~6 GB of memory).
//
//   build/kdtree_bench                    (Google Benchmark flags apply, e.g. --benchmark_filter=Knn)
//   PHOS_BENCH_BIG=1 build/kdtree_bench --benchmark_filter=Build
// Rates are per CPU second of the querying thread (Google Benchmark's default), which keeps the
// comparison meaningful on a shared machine; build times are wall-clock. Build counters:
// photons/s (wall-clock), peak_RSS_MiB (getrusage ru_maxrss after the build; on Linux the
// high-water mark is reset just before each build through /proc/self/clear_refs, so this is the
// peak during the build, including the input and everything else alive) and extra_B/photon (that
// peak minus the resident size just before the build, per photon: the build's own memory).
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <nanoflann.hpp>
#include <vector>

#include "core/rng.h"
#include "core/stats.h"
#include "photon/kdtree.h"

namespace {

using namespace phos;
using namespace phos::photon;

constexpr float kMaxRadius = 0.1f;     // of the unit box: cuts few k-nearest queries
constexpr float kRangeRadius = 0.01f;  // range query: ~50 photons at 1 M, ~500 at 10 M
constexpr uint32_t kQueries = 1u << 17;
constexpr uint32_t kVerifyQueries = 4000;
// Leaf sizes. Query rates were flat within noise over 8..32 for phos and 5..20 for nanoflann on
// this data (10 is nanoflann's default); override with PHOS_LEAF / NANOFLANN_LEAF to re-tune.
uint32_t leaf_from_env(const char* name, uint32_t fallback) {
    const char* v = std::getenv(name);
    return v ? uint32_t(std::max(2, std::atoi(v))) : fallback;
}
const uint32_t kPhosLeaf = leaf_from_env("PHOS_LEAF", 16);
const size_t kNanoflannLeaf = leaf_from_env("NANOFLANN_LEAF", 10);

// ---- the scene: a unit Cornell box (floor, ceiling, back and side walls) with two rotated blocks ----

struct Rect {
    Vec3 o, u, v;  // points o + s u + t v, s, t in [0, 1]
    float area() const { return length(cross(u, v)); }
};

void add_block(std::vector<Rect>& rects, float cx, float cz, float half, float height, float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    const Vec3 a(c * half, 0, s * half), b(-s * half, 0, c * half);  // half-edge vectors
    const Vec3 centre(cx, 0, cz), up(0, height, 0);
    const Vec3 corners[4] = {centre - a - b, centre + a - b, centre + a + b, centre - a + b};
    for (int i = 0; i < 4; ++i) rects.push_back({corners[i], corners[(i + 1) % 4] - corners[i], up});
    rects.push_back({corners[0] + up, a * 2.0f, b * 2.0f});  // top
}

std::vector<Rect> cornell_box() {
    std::vector<Rect> r = {
        {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}},  // floor
        {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},  // ceiling
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  // back wall
        {{0, 0, 0}, {0, 1, 0}, {0, 0, 1}},  // left wall
        {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},  // right wall
    };
    add_block(r, 0.33f, 0.35f, 0.15f, 0.3f, -0.3f);  // short block
    add_block(r, 0.66f, 0.65f, 0.15f, 0.6f, 0.3f);   // tall block
    return r;
}

class SurfaceSampler {
public:
    SurfaceSampler() : rects_(cornell_box()) {
        float sum = 0;
        for (const Rect& r : rects_) cdf_.push_back(sum += r.area());
        for (float& c : cdf_) c /= sum;
    }
    // Uniform by area over all rectangles.
    Vec3 sample(Sampler& rng) const {
        const float u = rng.next();
        const size_t i =
            std::min<size_t>(std::lower_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin(), rects_.size() - 1);
        const Vec2 st = rng.next2();
        return rects_[i].o + rects_[i].u * st.x + rects_[i].v * st.y;
    }

private:
    std::vector<Rect> rects_;
    std::vector<float> cdf_;
};

// 85 % of the photons uniform on the surfaces, 15 % in a "caustic" on the floor whose density
// grows towards its centre (radius 0.08, density ~ 1/r).
// Each photon has its own random stream, so the set does not depend on the thread count.
std::vector<Photon> make_photons(size_t n, uint64_t seed) {
    const SurfaceSampler surfaces;
    std::vector<Photon> photons(n);
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
        Sampler rng(seed, i);
        Vec3 p;
        if (rng.next() < 0.15f) {
            const Vec2 u = rng.next2();
            const float r = 0.08f * u.x, phi = 2.0f * kPi * u.y;
            p = Vec3(0.3f + r * std::cos(phi), 0.0f, 0.78f + r * std::sin(phi));
        } else {
            p = surfaces.sample(rng);
        }
        photons[i] = Photon(p, Spectrum(1e-6f), Wavelengths::visible(0.5f), Vec3(0, 1, 0), Vec3(0, 1, 0));
    });
    return photons;
}

// The photon sets, made once per size.
const std::vector<Photon>& photon_set(size_t n) {
    static std::map<size_t, std::unique_ptr<std::vector<Photon>>> cache;
    auto& slot = cache[n];
    if (!slot) slot = std::make_unique<std::vector<Photon>>(make_photons(n, 1));
    return *slot;
}

// ---- nanoflann over a packed copy of the positions (its most favourable layout) ----

struct PointCloud {
    const float* xyz = nullptr;
    size_t n = 0;
    size_t kdtree_get_point_count() const { return n; }
    float kdtree_get_pt(uint32_t i, size_t dim) const { return xyz[3 * size_t(i) + dim]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
        return false;
    }
};
using NanoTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointCloud, float, uint32_t>,
                                        PointCloud, 3, uint32_t>;

// nanoflann's own sorted KNN result set, started with the radius bound as its "worst distance" so
// that it prunes with it from the first node (what later versions call RKNNResultSet). Its
// acceptance test is `dist < worst`, so nextafter(r^2) gives the same closed ball as phos.
struct NanoKnn {
    std::vector<uint32_t> idx;
    std::vector<float> dist;
    nanoflann::KNNResultSet<float, uint32_t, uint32_t> set;
    explicit NanoKnn(uint32_t k) : idx(k), dist(k), set(k) {}
    uint32_t run(const NanoTree& tree, Vec3 q, float r2) {
        set.init(idx.data(), dist.data());
        dist.back() = std::nextafter(r2, kInf);
        const float qv[3] = {q.x, q.y, q.z};
        tree.findNeighbors(set, qv, nanoflann::SearchParams());
        return set.size();
    }
};

// A counting range result set for nanoflann, the same work as phos's callback below (and, for
// the check, the indices found).
struct NanoRange {
    float radius2;
    uint32_t count = 0;
    float sum = 0;
    std::vector<uint32_t>* found = nullptr;
    size_t size() const { return count; }
    bool full() const { return true; }
    bool addPoint(float d2, uint32_t i) {
        ++count, sum += d2;
        if (found) found->push_back(i);
        return true;
    }
    float worstDist() const { return radius2; }
};

// ---- shared data, made once per size ----

struct Dataset {
    const std::vector<Photon>* photons = nullptr;
    std::vector<float> xyz;
    PointCloud cloud;
    std::vector<Vec3> queries;
    std::unique_ptr<PhotonKdTree> phos;
    std::unique_ptr<NanoTree> nano;
    std::string error;  // set if the two libraries disagree
};

// Both libraries' neighbour sets, as indices into the input array, must be equal; only photons
// tied at exactly the k-th distance may differ.
std::string verify(const Dataset& d, uint32_t k) {
    std::vector<Neighbour> out(k);
    NanoKnn nano(k);
    const float r2 = kMaxRadius * kMaxRadius;
    size_t cut = 0;
    for (uint32_t qi = 0; qi < kVerifyQueries; ++qi) {
        const Vec3 q = d.queries[qi];
        const KnnResult r = d.phos->knn(q, k, r2, out.data());
        const uint32_t nn = nano.run(*d.nano, q, r2);
        if (r.count != nn) return "count differs at query " + std::to_string(qi);
        if (nn < k) ++cut;
        std::vector<std::pair<float, uint32_t>> a, b;
        for (uint32_t i = 0; i < nn; ++i) {
            a.push_back({out[i].dist2, d.phos->input_index(out[i].index)});
            b.push_back({nano.dist[i], nano.idx[i]});
        }
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        if (nn > 0 && (r.max_dist2 != b.back().first))
            return "max distance differs at query " + std::to_string(qi);
        for (uint32_t i = 0; i < nn; ++i) {
            if (a[i].first != b[i].first) return "distances differ at query " + std::to_string(qi);
            if (a[i].second != b[i].second && a[i].first != r.max_dist2)
                return "neighbour sets differ at query " + std::to_string(qi);
        }
    }
    std::fprintf(stderr, "  verified k=%u on %u queries: identical neighbour sets (%zu cut by the radius)\n",
                 k, kVerifyQueries, cut);
    return {};
}

std::string verify_range(const Dataset& d) {
    const float r2 = kRangeRadius * kRangeRadius;
    std::vector<uint32_t> a, b;
    for (uint32_t qi = 0; qi < kVerifyQueries; ++qi) {
        const Vec3 q = d.queries[qi];
        a.clear(), b.clear();
        d.phos->for_each_in_radius(q, r2, [&](uint32_t i, float) { a.push_back(d.phos->input_index(i)); });
        NanoRange set{std::nextafter(r2, kInf)};
        set.found = &b;
        const float qv[3] = {q.x, q.y, q.z};
        d.nano->findNeighbors(set, qv, nanoflann::SearchParams());
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        if (a != b) return "range query sets differ at query " + std::to_string(qi);
    }
    std::fprintf(stderr, "  verified range r=%g on %u queries: identical sets\n", kRangeRadius,
                 kVerifyQueries);
    return {};
}

Dataset& dataset(size_t n) {
    static std::map<size_t, std::unique_ptr<Dataset>> cache;
    auto& slot = cache[n];
    if (slot) return *slot;
    slot = std::make_unique<Dataset>();
    Dataset& d = *slot;
    std::fprintf(stderr, "setup: %zu photons\n", n);
    d.photons = &photon_set(n);
    d.xyz.resize(3 * n);
    for (size_t i = 0; i < n; ++i) {
        const Vec3 p = (*d.photons)[i].position;
        d.xyz[3 * i] = p.x;
        d.xyz[3 * i + 1] = p.y;
        d.xyz[3 * i + 2] = p.z;
    }
    d.cloud = {d.xyz.data(), n};
    const SurfaceSampler surfaces;
    Sampler rng(2);
    for (uint32_t i = 0; i < kQueries; ++i) d.queries.push_back(surfaces.sample(rng));

    auto t0 = std::chrono::steady_clock::now();
    KdTreeOptions options;
    options.leaf_size = kPhosLeaf;
    options.keep_input_index = true;
    tbb::task_arena(2).execute([&] { d.phos = std::make_unique<PhotonKdTree>(*d.photons, options); });
    std::fprintf(stderr, "  phos build (2 threads): %.3f s\n", seconds_since(t0));
    t0 = std::chrono::steady_clock::now();
    d.nano =
        std::make_unique<NanoTree>(3, d.cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kNanoflannLeaf));
    std::fprintf(stderr, "  nanoflann build: %.3f s\n", seconds_since(t0));
    for (uint32_t k : {50u, 200u}) {
        if (d.error.empty()) d.error = verify(d, k);
    }
    if (d.error.empty()) d.error = verify_range(d);
    if (!d.error.empty()) std::fprintf(stderr, "  VERIFICATION FAILED: %s\n", d.error.c_str());
    return d;
}

// ---- memory ----

// Resets the process's peak resident size (Linux >= 4.0; elsewhere ru_maxrss stays the lifetime peak).
void reset_peak_rss() { std::ofstream("/proc/self/clear_refs") << "5"; }

double peak_rss_bytes() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) * 1024.0;  // KiB on Linux
}

double current_rss_bytes() {
    std::ifstream statm("/proc/self/statm");
    double pages = 0, resident = 0;
    statm >> pages >> resident;
    return resident * 4096.0;
}

// Times `build` (wall-clock, manual time) and reports the build counters described at the top.
template <class Prepare, class Build>
void time_builds(benchmark::State& state, size_t n, Prepare&& prepare, Build&& build) {
    double seconds = 0, peak = 0, extra = 0;
    for (auto _ : state) {
        state.PauseTiming();
        prepare();
        const double before = current_rss_bytes();
        reset_peak_rss();
        state.ResumeTiming();
        const auto t0 = std::chrono::steady_clock::now();
        build();
        const double t = seconds_since(t0);
        state.SetIterationTime(t);
        seconds += t;
        peak = std::max(peak, peak_rss_bytes());
        extra = std::max(extra, peak_rss_bytes() - before);
    }
    state.counters["threads"] = double(state.range(1));
    state.counters["photons/s"] = double(n) * double(state.iterations()) / seconds;
    state.counters["peak_RSS_MiB"] = peak / (1024.0 * 1024.0);
    state.counters["extra_B/photon"] = extra / double(n);
}

// ---- benchmarks ----

// The build from a span (a copy of the caller's photons, then the in-place build), or in place:
// the tree takes over a fresh copy of the photons (made untimed).
void build_phos(benchmark::State& state, bool in_place) {
    const size_t n = size_t(state.range(0));
    const std::vector<Photon>& photons = photon_set(n);
    tbb::task_arena arena(int(state.range(1)));
    KdTreeOptions options;
    options.leaf_size = kPhosLeaf;
    std::unique_ptr<PhotonKdTree> tree;
    std::vector<Photon> copy;
    time_builds(
        state, n,
        [&] {
            tree.reset();
            if (in_place) copy = photons;
            tree = std::make_unique<PhotonKdTree>();
        },
        [&] {
            arena.execute([&] {
                if (in_place)
                    tree->build(std::move(copy), options);
                else
                    tree->build(photons, options);
            });
            benchmark::DoNotOptimize(tree->photons().data());
        });
}

void BM_BuildPhos(benchmark::State& state) { build_phos(state, false); }
void BM_BuildPhosInPlace(benchmark::State& state) { build_phos(state, true); }

void BM_BuildNanoflann(benchmark::State& state) {
    const Dataset& d = dataset(size_t(state.range(0)));
    for (auto _ : state) {
        NanoTree tree(3, d.cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kNanoflannLeaf));
        benchmark::DoNotOptimize(&tree);
    }
}

void BM_KnnPhos(benchmark::State& state) {
    const Dataset& d = dataset(size_t(state.range(0)));
    if (!d.error.empty()) return state.SkipWithError(d.error.c_str());
    const uint32_t k = uint32_t(state.range(1));
    std::vector<Neighbour> out(k);
    const float r2 = kMaxRadius * kMaxRadius;
    uint32_t qi = 0;
    for (auto _ : state) {
        const KnnResult r = d.phos->knn(d.queries[qi++ % kQueries], k, r2, out.data());
        benchmark::DoNotOptimize(r);
    }
    state.SetItemsProcessed(int64_t(state.iterations()));
}

void BM_KnnNanoflann(benchmark::State& state) {
    const Dataset& d = dataset(size_t(state.range(0)));
    if (!d.error.empty()) return state.SkipWithError(d.error.c_str());
    NanoKnn nano(uint32_t(state.range(1)));
    const float r2 = kMaxRadius * kMaxRadius;
    uint32_t qi = 0;
    for (auto _ : state) benchmark::DoNotOptimize(nano.run(*d.nano, d.queries[qi++ % kQueries], r2));
    state.SetItemsProcessed(int64_t(state.iterations()));
}

void BM_RangePhos(benchmark::State& state) {
    const Dataset& d = dataset(size_t(state.range(0)));
    if (!d.error.empty()) return state.SkipWithError(d.error.c_str());
    const float r2 = kRangeRadius * kRangeRadius;
    uint32_t qi = 0;
    size_t found = 0;
    for (auto _ : state) {
        uint32_t count = 0;
        float sum = 0;
        d.phos->for_each_in_radius(d.queries[qi++ % kQueries], r2,
                                   [&](uint32_t, float d2) { ++count, sum += d2; });
        benchmark::DoNotOptimize(sum);
        found += count;
    }
    state.SetItemsProcessed(int64_t(state.iterations()));
    state.counters["photons/query"] = double(found) / double(state.iterations());
}

void BM_RangeNanoflann(benchmark::State& state) {
    const Dataset& d = dataset(size_t(state.range(0)));
    if (!d.error.empty()) return state.SkipWithError(d.error.c_str());
    const float r2 = std::nextafter(kRangeRadius * kRangeRadius, kInf);
    uint32_t qi = 0;
    size_t found = 0;
    for (auto _ : state) {
        NanoRange set{r2};
        const Vec3 q = d.queries[qi++ % kQueries];
        const float qv[3] = {q.x, q.y, q.z};
        d.nano->findNeighbors(set, qv, nanoflann::SearchParams());
        benchmark::DoNotOptimize(set.sum);
        found += set.count;
    }
    state.SetItemsProcessed(int64_t(state.iterations()));
    state.counters["photons/query"] = double(found) / double(state.iterations());
}

constexpr int64_t kSizes[] = {1'000'000, 10'000'000};

void build_args(benchmark::internal::Benchmark* b) {
    for (int64_t n : kSizes) b->Args({n, 1})->Args({n, 2});
}
void size_args(benchmark::internal::Benchmark* b) {
    for (int64_t n : kSizes) b->Args({n});
}
void knn_args(benchmark::internal::Benchmark* b) {
    for (int64_t n : kSizes) b->Args({n, 50})->Args({n, 200});
}

void in_place_args(benchmark::internal::Benchmark* b) { b->Args({10'000'000, 1})->Args({10'000'000, 2}); }

BENCHMARK(BM_BuildPhos)->Apply(build_args)->Unit(benchmark::kMillisecond)->Iterations(3)->UseManualTime();
BENCHMARK(BM_BuildPhosInPlace)
    ->Apply(in_place_args)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->UseManualTime();
// 100 M photons only with PHOS_BENCH_BIG=1 (registered at start-up, after the ones above).
[[maybe_unused]] const bool kBigRegistered = [] {
    const char* big = std::getenv("PHOS_BENCH_BIG");
    if (big && std::atoi(big) != 0) {
        benchmark::RegisterBenchmark("BM_BuildPhosInPlace", BM_BuildPhosInPlace)
            ->Args({100'000'000, 1})
            ->Args({100'000'000, 2})
            ->Unit(benchmark::kMillisecond)
            ->Iterations(2)
            ->UseManualTime();
    }
    return true;
}();
BENCHMARK(BM_BuildNanoflann)->Apply(size_args)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_KnnPhos)->Apply(knn_args)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_KnnNanoflann)->Apply(knn_args)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RangePhos)->Apply(size_args)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RangeNanoflann)->Apply(size_args)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
