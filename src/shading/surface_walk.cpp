// The walk to the next scattering event through medium interfaces and media (see surface_walk.h).
#include "shading/surface_walk.h"

#include "shading/medium_tracking.h"

namespace phos::shading {

bool SurfaceWalk::cross(Ray& ray, const accel::SurfaceHit& hit) {
    if (++crossings_ > kMaxCrossings) return false;
    medium_ = medium_after(hit, ray.dir, medium_);
    ray = accel::spawn_ray(hit, ray.dir);
    return true;
}

SurfaceWalk::Event SurfaceWalk::next(Ray& ray, accel::SurfaceHit& hit) {
    return next_segments(ray, hit, [](const Medium&, Vec3, Vec3, float) {});
}

Spectrum shadow_transmittance(const accel::EmbreeScene& accel, const MediaSet* media, Ray ray, int medium,
                              Sampler& sampler, const Wavelengths& lambda) {
    if (!media || !media->active()) return accel.occluded(ray) ? Spectrum(0.0f) : Spectrum(1.0f);
    const scene::Scene& scene = accel.scene();
    Spectrum T(1.0f);
    for (int crossings = 0; crossings <= SurfaceWalk::kMaxCrossings; ++crossings) {
        accel::SurfaceHit hit;
        const bool found = accel.intersect(ray, hit);
        if (found && !scene.materials[size_t(hit.material)].interface_only) return Spectrum(0.0f);
        const float len = length(ray.dir);
        if (medium >= 0) {
            const float t_end = (found ? hit.t : std::fmin(ray.tmax, kInf)) * len;
            T *= transmittance((*media)[medium], ray.origin, ray.dir / len, t_end, sampler, lambda);
            if (T.is_black()) return T;
        }
        if (!found) return T;
        // Continue beyond the interface towards the same end point.
        medium = SurfaceWalk::medium_after(hit, ray.dir, medium);
        Ray next = accel::spawn_ray(hit, ray.dir);
        if (ray.tmax < kInf) {
            const Vec3 end = ray.origin + ray.dir * ray.tmax;
            next.tmax = dot(end - next.origin, ray.dir) / dot(ray.dir, ray.dir);
            if (!(next.tmax > next.tmin)) return T;
        }
        ray = next;
    }
    return Spectrum(0.0f);
}

}  // namespace phos::shading
