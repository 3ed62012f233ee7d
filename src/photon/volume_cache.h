// Precomputed in-scattered light for final-gather rays that scatter in a medium: the volume
// analogue of the irradiance cache (Christensen, JGT 1999). At every stride-th volume photon, the
// volume maps' k-nearest estimates (volume_estimate.h) are reduced to the first two angular
// moments of the photons found,
//   F0 = sum Phi_p / V,   F1 = sum Phi_p wi_p / V   (per colour channel),
// from which the estimate for any Henyey-Greenstein medium follows to first order in its Legendre
// expansion p(mu) = (1 + 3 g mu + 5 g^2 P2(mu) + ...) / (4 pi), mu = cos(-wo, wi):
//   sum p(wo, wi_p) Phi_p / V  ~=  (F0 - 3 g wo . F1) / (4 pi)      (clamped at 0).
// Exact for isotropic scattering (g = 0); for g != 0 the higher orders are dropped, which only
// smooths the angular detail of light that has already been through a final-gather bounce. A
// gather ray then needs one nearest-point lookup instead of two k-nearest estimates.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/vec.h"
#include "photon/kdtree.h"
#include "photon/volume_estimate.h"

namespace phos::photon {

// F0 and F1 of one estimate (F1[c] is the moment of channel c).
struct VolumeMoments {
    Rgb f0{0.0f};
    std::array<Vec3, 3> f1{Vec3(0.0f), Vec3(0.0f), Vec3(0.0f)};
    VolumeMoments& operator+=(const VolumeMoments& o) {
        f0 += o.f0;
        for (int c = 0; c < 3; ++c) f1[size_t(c)] += o.f1[size_t(c)];
        return *this;
    }
    // The estimate for outgoing direction wo in a medium of asymmetry g (see above).
    Rgb estimate(Vec3 wo, float g) const;
};

// The moments of the k-nearest volume estimate at x (same photons and volume as
// volume_radiance_estimate).
VolumeMoments volume_moments(const PhotonKdTree& map, const VolumeEstimateOptions& o, Vec3 x);

class VolumeCache {
public:
    // Cache points at photons 0, stride, 2 stride... of `volume` (tree order: deterministic), each
    // holding the sum of both maps' moments; built in parallel. stride >= 1.
    void build(const PhotonKdTree& volume, const VolumeEstimateOptions& volume_options,
               const PhotonKdTree& volume_caustic, const VolumeEstimateOptions& caustic_options,
               uint32_t stride);

    // The estimate of the nearest cache point within max_radius of x; false if there is none.
    bool lookup(Vec3 x, float max_radius, Vec3 wo, float g, Rgb& estimate) const;

    // Saves and restores the cache exactly (checkpoints; see PhotonKdTree::save).
    void save(ByteWriter& out) const;
    void load(ByteReader& in);

    size_t size() const { return points_.size(); }
    bool empty() const { return points_.empty(); }

private:
    PhotonKdTree points_;                 // positions only
    std::vector<VolumeMoments> moments_;  // in the tree's order
};

}  // namespace phos::photon
