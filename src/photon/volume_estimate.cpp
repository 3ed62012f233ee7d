// Volume photon density estimates (see volume_estimate.h).
#include "photon/volume_estimate.h"

#include <algorithm>
#include <vector>

namespace phos::photon {

Rgb volume_radiance_estimate(const PhotonKdTree& map, const VolumeEstimateOptions& o, Vec3 x, Vec3 wo,
                             const shading::PhaseFunction& phase, uint32_t* n_used) {
    Rgb sum(0.0f);
    const float inv_volume = volume_estimate_photons(
        map, o, x, [&](const Photon& ph) { sum += ph.colour() * phase.eval(wo, ph.wi()); }, n_used);
    return sum * inv_volume;
}

}  // namespace phos::photon
