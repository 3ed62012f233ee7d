// Direct lighting at a surface point by light sampling with shadow rays, shared by the whitted,
// path and photon-map integrators.
#pragma once

#include "core/rng.h"
#include "core/stats.h"
#include "integrators/prepared.h"

namespace phos::integrators {

// One light chosen in proportion to its power, one point on it, one shadow ray. With `mis`, area
// and infinite lights are weighted against BSDF sampling by the power heuristic (the caller then
// adds BSDF-sampled emission with the complementary weight).
Rgb sample_one_light(const Prepared& P, const accel::SurfaceHit& hit, const shading::Bsdf& bsdf, Vec3 wo,
                     Sampler& sampler, RayCounts& rays, bool mis);

// Every light, one sample each (no MIS): the classic Whitted / photon-map direct term.
Rgb sample_all_lights(const Prepared& P, const accel::SurfaceHit& hit, const shading::Bsdf& bsdf, Vec3 wo,
                      Sampler& sampler, RayCounts& rays);

}  // namespace phos::integrators
