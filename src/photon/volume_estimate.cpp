// Volume photon density estimates (see volume_estimate.h).
#include "photon/volume_estimate.h"

#include <algorithm>
#include <vector>

namespace phos::photon {

Rgb volume_radiance_estimate(const PhotonKdTree& map, const VolumeEstimateOptions& o, Vec3 x, Vec3 wo,
                             const shading::PhaseFunction& phase, uint32_t* n_used) {
    Rgb sum(0.0f);
    const float inv_volume = volume_estimate_photons(
        map, o, x, [&](const Photon& ph) { sum += ph.power() * phase.eval(wo, ph.wi()); }, n_used);
    return sum * inv_volume;
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
