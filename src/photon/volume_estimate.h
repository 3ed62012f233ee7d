// Photon density estimates in participating media (Jensen & Christensen 1998, eq. 11): the k
// nearest volume photons within a maximum radius, each weighted by the phase function, divided by
// the volume of the sphere they fill:
//   (dL/dx)(x, wo) ~= sum_p p(wo, wi_p) Phi_p / (4/3 pi r^3)
// Volume photons are stored at real scattering events with their power already weighted by the
// scattering albedo (photon_path.h), so their density is sigma_s times the fluence and the sum is
// the in-scattered radiance per unit length, sigma_s * int p L_i: the radiance a camera ray gains
// per unit length before attenuation.
#pragma once

#include <cstdint>

#include "core/vec.h"
#include "photon/kdtree.h"
#include "shading/phase.h"

namespace phos::photon {

struct VolumeEstimateOptions {
    uint32_t k = 50;          // photons per estimate
    float max_radius = 0.1f;  // scene units; fewer than k photons within it use this radius
};

// In-scattered radiance per unit length at x towards wo (unit, back along the viewing ray).
Rgb volume_radiance_estimate(const PhotonKdTree& map, const VolumeEstimateOptions& o, Vec3 x, Vec3 wo,
                             const shading::PhaseFunction& phase, uint32_t* n_used = nullptr);

// The same with every photon within the fixed radius r (progressive estimates, where the radius
// schedule rather than k sets the bias): sum p Phi_p / (4/3 pi r^3).
Rgb volume_radiance_fixed_radius(const PhotonKdTree& map, float r, Vec3 x, Vec3 wo,
                                 const shading::PhaseFunction& phase);

}  // namespace phos::photon
