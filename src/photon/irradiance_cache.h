// Precomputed irradiance (Christensen, "Faster Photon Map Global Illumination", JGT 1999): after
// photon tracing, the irradiance is estimated once at every M-th global photon (at its position,
// with its normal) and stored in a second k-d tree. A final-gather ray then needs one k = 1 lookup
// (nearest cached point with a compatible normal) times the diffuse reflectance at its own hit,
// instead of a full k-photon radiance estimate.
#pragma once

#include <cstdint>

#include "photon/estimate.h"
#include "photon/kdtree.h"

namespace phos::photon {

class IrradianceCache {
public:
    // Estimates the irradiance at photons 0, stride, 2 stride... of `map` (tree order, so the
    // result is deterministic) with `o`, in parallel. stride >= 1.
    void build(const PhotonKdTree& map, const EstimateOptions& o, uint32_t stride);

    // Irradiance of the nearest cached point within max_radius whose normal passes q's test
    // (cosine >= normal_cos); false if there is none.
    bool lookup(const SurfaceQuery& q, float max_radius, float normal_cos, Rgb& irradiance) const;

    // Saves and restores the cache exactly (checkpoints; see PhotonKdTree::save).
    void save(ByteWriter& out) const;
    void load(ByteReader& in);

    size_t size() const { return points_.size(); }
    bool empty() const { return points_.empty(); }

private:
    // Cache points as photon records: position, irradiance in the power field, normal.
    PhotonKdTree points_;
};

}  // namespace phos::photon
