// Hit-point lookup for SPPM: the hash grid (photon/hitpoint_grid.h) against a k-d tree
// (nanoflann) over the same visible points, on the real visible points of cornell-diffuse at
// 256x256 (first iteration, automatic radius) queried at real photon hits. Build + queries are
// timed separately. The faster is what sppm_core.cpp uses.
#include <benchmark/benchmark.h>

#include <nanoflann.hpp>

#include "core/stats.h"
#include "integrators/eye_path.h"
#include "integrators/progressive_options.h"
#include "io/load_scene.h"
#include "photon/hitpoint_grid.h"
#include "photon/photon_path.h"
#include "render/prepared.h"

namespace phos {
namespace {

struct Data {
    std::vector<Vec3> pos;
    std::vector<float> r2;
    std::vector<Vec3> queries;
};

const Data& data() {
    static const Data d = [] {
        Data d;
        static const scene::Scene s =
            io::load_scene(std::string(PHOS_SHARED_DIR) + "/bench/scn/cornell-diffuse.scn");
        render::RenderOptions opt;
        opt.width = opt.height = 256;
        static Stats stats;
        static render::Prepared P(s, opt, {}, stats);
        const render::CameraModel::Footprint fp = P.camera.pixel_footprint();
        RayCounts rays;
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) {
                Sampler sampler(1, uint64_t(y * 256 + x));
                integrators::VisiblePoint vp;
                const Ray ray = P.camera.generate_ray(x + 0.5f, y + 0.5f, {0.5f, 0.5f});
                integrators::trace_eye_path(P, ray, sampler, 1, vp, rays);
                if (!vp.bsdf) continue;
                const float r = integrators::ProgressiveOptions{}.radius_pixels * fp.at(vp.path_length);
                d.pos.push_back(vp.p);
                d.r2.push_back(r * r);
            }
        const photon::PhotonScene ps{P.scene, P.accel, P.lights, P.bsdfs};
        for (uint64_t i = 0; d.queries.size() < 200000; ++i)
            photon::trace_photon(ps, 1, 0, i, {15},
                                 [&](const photon::PhotonHit& h) { d.queries.push_back(h.hit.p); });
        return d;
    }();
    return d;
}

void BM_HashGrid(benchmark::State& state) {
    const Data& d = data();
    photon::HitPointGrid grid;
    uint64_t found = 0;
    for (auto _ : state) {
        grid.build(d.pos, d.r2);
        for (const Vec3& q : d.queries) grid.query(q, [&](uint32_t) { ++found; });
    }
    benchmark::DoNotOptimize(found);
    state.counters["hits/query"] = double(found) / double(state.iterations()) / double(d.queries.size());
}

struct Cloud {
    const std::vector<Vec3>* p;
    size_t kdtree_get_point_count() const { return p->size(); }
    float kdtree_get_pt(size_t i, size_t dim) const { return (*p)[i][int(dim)]; }
    template <class B>
    bool kdtree_get_bbox(B&) const {
        return false;
    }
};
using Tree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Cloud>, Cloud, 3, uint32_t>;

void BM_KdTree(benchmark::State& state) {
    const Data& d = data();
    Cloud cloud{&d.pos};
    float max_r2 = 0;
    for (float r : d.r2) max_r2 = std::max(max_r2, r);
    uint64_t found = 0;
    for (auto _ : state) {
        Tree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
        std::vector<std::pair<uint32_t, float>> res;
        for (const Vec3& q : d.queries) {
            const float qp[3] = {q.x, q.y, q.z};
            res.clear();
            tree.radiusSearch(qp, max_r2, res, nanoflann::SearchParams(32, 0, false));
            for (const auto& r : res)
                if (r.second <= d.r2[r.first]) ++found;
        }
    }
    benchmark::DoNotOptimize(found);
    state.counters["hits/query"] = double(found) / double(state.iterations()) / double(d.queries.size());
}

BENCHMARK(BM_HashGrid)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KdTree)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace phos

BENCHMARK_MAIN();
