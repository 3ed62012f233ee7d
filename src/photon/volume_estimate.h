// Photon density estimates in participating media (Jensen & Christensen 1998, eq. 11): the k
// nearest volume photons within a maximum radius, each weighted by the phase function, divided by
// the volume of the sphere they fill:
//   (dL/dx)(x, wo) ~= sum_p p(wo, wi_p) Phi_p / (4/3 pi r^3)
// Volume photons are stored at real scattering events with their power already weighted by the
// scattering albedo (photon_path.h), so their density is sigma_s times the fluence and the sum is
// the in-scattered radiance per unit length, sigma_s * int p L_i: the radiance a camera ray gains
// per unit length before attenuation.
// Near a surface (a wall of a smoke-filled room, the medium's own boundary) part of the sphere
// lies where no photon can be; with `surfaces` set the sum is divided by the open part's volume
// instead (photon/open_ball.h), which removes the kernel's boundary loss to first order.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/vec.h"
#include "photon/kdtree.h"
#include "photon/open_ball.h"
#include "shading/phase.h"

namespace phos::photon {

struct VolumeEstimateOptions {
    uint32_t k = 50;          // photons per estimate
    float max_radius = 0.1f;  // scene units; fewer than k photons within it use this radius
    // The surfaces that bound the media: the estimate counts only the open part of its sphere
    // (nullptr: the whole sphere, as in an unbounded medium).
    const accel::EmbreeScene* surfaces = nullptr;
};

// The photons of the k-nearest estimate at x: calls visit(photon) for each and returns 1 / V, the
// inverse volume of the sphere they fill (the whole search sphere when fewer than k are found; 0
// when none are), of its open part with o.surfaces.
template <class Visit>
float volume_estimate_photons(const PhotonKdTree& map, const VolumeEstimateOptions& o, Vec3 x, Visit&& visit,
                              uint32_t* n_used = nullptr) {
    if (n_used) *n_used = 0;
    if (map.empty() || o.k == 0) return 0.0f;
    thread_local std::vector<Neighbour> nb;
    nb.resize(o.k);
    const KnnResult r = map.knn(x, o.k, o.max_radius * o.max_radius, nb.data());
    if (r.count == 0) return 0.0f;
    const float r2 = r.count < o.k ? o.max_radius * o.max_radius : r.max_dist2;
    if (!(r2 > 0)) return 0.0f;
    for (uint32_t i = 0; i < r.count; ++i) visit(map.photon(nb[i].index));
    if (n_used) *n_used = r.count;
    const float radius = std::sqrt(r2);
    const float open = o.surfaces ? open_ball_fraction(*o.surfaces, x, radius) : 1.0f;
    return 1.0f / (4.0f / 3.0f * kPi * r2 * radius * open);
}

// In-scattered radiance per unit length at x towards wo (unit, back along the viewing ray).
Rgb volume_radiance_estimate(const PhotonKdTree& map, const VolumeEstimateOptions& o, Vec3 x, Vec3 wo,
                             const shading::PhaseFunction& phase, uint32_t* n_used = nullptr);

}  // namespace phos::photon
