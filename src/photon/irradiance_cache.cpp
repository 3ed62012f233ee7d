// Precomputed irradiance at photon positions (see irradiance_cache.h).
#include "photon/irradiance_cache.h"

#include <tbb/parallel_for.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "dist/ranks.h"

namespace phos::photon {

void IrradianceCache::save(ByteWriter& out) const { points_.save(out); }

void IrradianceCache::load(ByteReader& in) { points_.load(in); }

void IrradianceCache::build(const PhotonKdTree& map, const EstimateOptions& o, uint32_t stride) {
    stride = std::max<uint32_t>(stride, 1);
    const size_t n = (map.size() + stride - 1) / stride;
    std::vector<Photon> pts(n);
    // Under MPI each rank estimates a contiguous share of the points and every rank receives all.
    const auto [lo, hi] = dist::share(n);
    tbb::parallel_for(tbb::blocked_range<size_t>(lo, hi, 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
            const Photon& ph = map.photon(uint32_t(i * stride));
            SurfaceQuery q;
            q.p = ph.position;
            q.n = ph.normal();
            const Rgb E = ph.has_normal() ? irradiance_estimate(map, o, q) : Rgb(0.0f);
            pts[i] = Photon(ph.position, Spectrum(0.0f), Wavelengths(), q.n, q.n);
            set_stored_colour(pts[i], E);
        }
    });
    if (dist::distributed()) {
        pts = dist::all_gather(std::span<const Photon>(pts.data() + lo, hi - lo));
        if (pts.size() != n) throw std::runtime_error("irradiance cache: ranks disagree on its size");
    }
    points_.build(std::move(pts));  // in place: no second copy of the points
}

bool IrradianceCache::lookup(const SurfaceQuery& q, float max_radius, float normal_cos,
                             Rgb& irradiance) const {
    Neighbour nb;
    const KnnResult r = points_.knn_if(q.p, 1, max_radius * max_radius, &nb,
                                       [&](const Photon& ph) { return dot(ph.normal(), q.n) >= normal_cos; });
    if (r.count == 0) return false;
    irradiance = stored_colour(points_.photon(nb.index));
    return true;
}

}  // namespace phos::photon
