// The walk to the next scattering surface through medium interfaces (see surface_walk.h).
#include "shading/surface_walk.h"

namespace phos::shading {

SurfaceWalk::Event SurfaceWalk::next(accel::Ray& ray, accel::SurfaceHit& hit) {
    const scene::Scene& scene = accel_.scene();
    while (true) {
        ++rays_;
        if (!accel_.intersect(ray, hit)) return Event::Escaped;
        distance_ += hit.t * length(ray.dir);
        if (!scene.materials[size_t(hit.material)].interface_only) return Event::Surface;
        // Media: the ray enters hit.media.inside or .outside here (by the side of ng it leaves to).
        if (++crossings_ > kMaxCrossings) return Event::Lost;
        ray = accel::spawn_ray(hit, ray.dir);
    }
}

}  // namespace phos::shading
