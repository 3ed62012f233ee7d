// libFuzzer harness for the photon maps stored in photonmap checkpoints (photon/photon_maps.h). The
// payload sits behind the checkpoint's checksum, but load() must still refuse whatever is not a
// consistent set of maps: every map that loads is queried as a render would (k nearest photons,
// fixed-radius gathers, irradiance estimates, the caches, segments through the volume beams), so a
// structure that makes a query loop, overflow or read outside its arrays is a finding, and it must
// save to exactly the bytes it came from.
#include <string>

#include "fuzz/fuzz_support.h"
#include "photon/estimate.h"
#include "photon/photon_maps.h"
#include "photon/volume_estimate.h"

namespace {

using namespace phos;
using namespace phos::photon;

// Query points: the origin, a far point, and the first photons of each map (where queries find
// something).
std::vector<Vec3> query_points(const PhotonMaps& maps) {
    std::vector<Vec3> q{Vec3(0.0f), Vec3(1e3f, -2e3f, 5e2f)};
    for (const PhotonKdTree& m : maps.map)
        for (uint32_t i = 0; i < m.size() && i < 3; ++i) q.push_back(m.photon(i).position);
    return q;
}

void query(const PhotonMaps& maps) {
    float sink = 0;  // keeps the decoded values alive
    const auto take = [&](const Photon& p) {
        sink += p.power()[0] + p.wavelengths()[0] + p.wi().x + p.normal().y + float(p.split_axis());
    };
    EstimateOptions eo;
    eo.k = 8;
    VolumeEstimateOptions vo;
    vo.k = 8;
    Neighbour nb[8];
    for (const Vec3 q : query_points(maps)) {
        for (const PhotonKdTree& m : maps.map) {
            const KnnResult r = m.knn(q, 8, kInf, nb);
            if (r.count > 8) fuzz::invariant_failed("knn returned more than k neighbours");
            for (uint32_t i = 0; i < r.count; ++i) take(m.photon(nb[i].index));
            m.for_each_in_radius(q, 0.25f, [&](uint32_t i, float) { take(m.photon(i)); });
            SurfaceQuery sq;
            sq.p = q;
            sq.n = Vec3(0, 0, 1);
            const Rgb e = irradiance_estimate(m, eo, sq);
            sink += e.g;
            sink += volume_estimate_photons(m, vo, q, take);
        }
        Rgb e;
        if (maps.cache.lookup(SurfaceQuery{q, Vec3(0, 1, 0)}, 1.0f, 0.5f, e)) sink += e.b;
        if (maps.volume_cache.lookup(q, 1.0f, Vec3(0, 0, -1), 0.3f, e)) sink += e.r;
        for (const BeamBvh* b : {&maps.volume_beams, &maps.volume_caustic_beams}) {
            const Vec3 d = normalize(Vec3(0.3f, -0.5f, 0.8f));
            b->for_each_hit(q - 2.0f * d, d, 4.0f,
                            [&](uint32_t k, const SphereHit&) { sink += b->spheres()[k].power.g; });
        }
    }
    volatile float keep = sink;
    (void)keep;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    phos::fuzz::expect_reader_errors([&] {
        const PhotonMaps maps = PhotonMaps::load(bytes, "'fuzz'");
        query(maps);
        if (maps.save() != bytes) phos::fuzz::invariant_failed("load/save round trip");
    });
    return 0;
}
