// Ray / bilinear patch intersection in double precision (Reshetov 2019, "Cool Patches: A Geometric
// Approach to Ray/Bilinear Patch Intersections", Ray Tracing Gems ch. 8, as pbrt-v4's
// IntersectBilinearPatch), for the exact non-planar patches of pbrt's `bilinearmesh`.
#pragma once

#include <array>

#include "accel/analytic.h"

namespace phos::accel::detail {

struct PatchHit {
    double t = 0, u = 0, v = 0;
};

// Closest hit of o + t d with t in (tmin, tmax) on the patch p(u, v) = lerp(v, lerp(u, p00, p10),
// lerp(u, p01, p11)), corners in pbrt's order p00, p10, p01, p11.
bool intersect_patch(const std::array<D3, 4>& p, D3 o, D3 d, double tmin, double tmax, PatchHit& hit);

}  // namespace phos::accel::detail
