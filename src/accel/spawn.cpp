// Robust ray spawning (pbrt-style): move the origin off the surface along the geometric normal by
// the hit's position-error bound, so new rays neither re-hit their own surface nor skip neighbours.
#include <cmath>

#include "accel/ray.h"

namespace phos::accel {

namespace {
// Shadow rays stop this fraction short of their target, so they do not hit the target surface.
constexpr float kShadowEpsilon = 1e-4f;
}  // namespace

Ray spawn_ray_to(const SurfaceHit& hit, Vec3 target) {
    Ray r;
    r.origin = offset_origin(hit, target - hit.p);
    r.dir = target - r.origin;
    r.tmax = 1.0f - kShadowEpsilon;
    return r;
}

Ray ray_to(Vec3 from, Vec3 target) {
    Ray r;
    r.origin = from;
    r.dir = target - from;
    r.tmax = 1.0f - kShadowEpsilon;
    return r;
}

Ray spawn_ray_between(const SurfaceHit& from, const SurfaceHit& to) {
    const Vec3 po = offset_origin(from, to.p - from.p);
    const Vec3 pt = offset_origin(to, po - to.p);
    Ray r;
    r.origin = po;
    r.dir = pt - po;
    r.tmax = 1.0f - kShadowEpsilon;
    return r;
}

}  // namespace phos::accel
