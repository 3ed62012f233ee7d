// Volume photon density estimates (see volume_estimate.h).
#include "photon/volume_estimate.h"

#include <algorithm>
#include <vector>

namespace phos::photon {

Rgb volume_radiance_estimate(const PhotonKdTree& map, const VolumeEstimateOptions& o, Vec3 x, Vec3 wo,
                             const shading::PhaseFunction& phase, uint32_t* n_used) {
    if (n_used) *n_used = 0;
    if (map.empty() || o.k == 0) return Rgb(0.0f);
    thread_local std::vector<Neighbour> nb;
    nb.resize(o.k);
    const KnnResult r = map.knn(x, o.k, o.max_radius * o.max_radius, nb.data());
    if (r.count == 0) return Rgb(0.0f);
    // With fewer than k photons the estimate covers the whole search sphere.
    const float r2 = r.count < o.k ? o.max_radius * o.max_radius : r.max_dist2;
    if (!(r2 > 0)) return Rgb(0.0f);
    Rgb sum(0.0f);
    for (uint32_t i = 0; i < r.count; ++i) {
        const Photon& ph = map.photon(nb[i].index);
        sum += ph.power() * phase.eval(wo, ph.wi());
    }
    if (n_used) *n_used = r.count;
    return sum * (1.0f / (4.0f / 3.0f * kPi * r2 * std::sqrt(r2)));
}

Rgb volume_radiance_fixed_radius(const PhotonKdTree& map, float r, Vec3 x, Vec3 wo,
                                 const shading::PhaseFunction& phase) {
    if (map.empty() || !(r > 0)) return Rgb(0.0f);
    Rgb sum(0.0f);
    map.for_each_in_radius(x, r * r, [&](uint32_t i, float) {
        const Photon& ph = map.photon(i);
        sum += ph.power() * phase.eval(wo, ph.wi());
    });
    return sum * (1.0f / (4.0f / 3.0f * kPi * r * r * r));
}

}  // namespace phos::photon
