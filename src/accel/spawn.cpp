// Robust ray spawning (pbrt-style): move the origin off the surface along the geometric normal by
// the hit's position-error bound, so new rays neither re-hit their own surface nor skip neighbours.
#include <cmath>

#include "accel/ray.h"

namespace phos::accel {

namespace {
// Shadow rays stop this fraction short of their target, so they do not hit the target surface.
constexpr float kShadowEpsilon = 1e-4f;
}  // namespace

Vec3 offset_origin(const SurfaceHit& hit, Vec3 dir) {
    // pbrt: distance = dot(|n|, error vector); with an isotropic bound that is error * |n|_1.
    const float d = hit.error * (std::fabs(hit.ng.x) + std::fabs(hit.ng.y) + std::fabs(hit.ng.z));
    Vec3 offset = hit.ng * d;
    if (dot(dir, hit.ng) < 0) offset = -offset;
    Vec3 po = hit.p + offset;
    // Round away from p so that the float addition cannot land back on the surface.
    for (int i = 0; i < 3; ++i) {
        if (offset[i] > 0)
            po[i] = std::nextafter(po[i], kInf);
        else if (offset[i] < 0)
            po[i] = std::nextafter(po[i], -kInf);
    }
    return po;
}

Ray spawn_ray(const SurfaceHit& hit, Vec3 dir) {
    Ray r;
    r.origin = offset_origin(hit, dir);
    r.dir = dir;
    return r;
}

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
