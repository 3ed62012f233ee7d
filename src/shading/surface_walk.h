// Walking a ray to the next surface that scatters light: the one loop every integrator and the
// photon tracer use to find what a ray meets, passing straight through medium interfaces.
#pragma once

#include <cstdint>

#include "accel/embree_scene.h"
#include "accel/ray.h"

namespace phos::shading {

// One walker per path (camera path, gather ray or photon): it remembers what the path has crossed.
//
// A medium interface (Material::interface_only) is a surface that only separates two media: it
// neither reflects nor refracts, so next() steps through it and keeps going. The medium a ray
// travels through changes exactly there (and where a ray refracts through a scattering surface), so
// this is THE place where participating media hook in: the walker will hold the current medium
// (from SurfaceHit::media at each crossing, set by the caller after a refraction), sample a
// free-flight distance in it over each segment, and report a medium interaction as another Event;
// the segment lengths it already sums are the distances that transmittance needs. Until then every
// ray travels through vacuum.
class SurfaceWalk {
public:
    enum class Event {
        Surface,  // `hit` is a scattering surface (its material is not interface_only)
        Escaped,  // nothing more along the ray: it leaves the scene in direction ray.dir
        Lost,     // the path crossed more than kMaxCrossings interfaces (degenerate geometry)
    };
    // Crossings allowed per path: stacked or coincident interfaces cannot make a path loop forever.
    static constexpr int kMaxCrossings = 256;

    explicit SurfaceWalk(const accel::EmbreeScene& accel) : accel_(accel) {}

    // Follows `ray` to the next scattering surface, stepping through interfaces (each step
    // continues from the interface along the same direction). On return `ray` is the last segment's
    // ray: the one that hit `hit` (Surface) or that escaped (Escaped).
    Event next(accel::Ray& ray, accel::SurfaceHit& hit);

    // Distance travelled along the whole walk so far (every segment that ended at a surface,
    // interfaces included), in scene units.
    float distance() const { return distance_; }
    // Interfaces crossed so far.
    int crossings() const { return crossings_; }
    // Closest-hit queries made so far (interface crossings and the final miss included).
    uint32_t rays() const { return rays_; }

private:
    const accel::EmbreeScene& accel_;
    float distance_ = 0;
    int crossings_ = 0;
    uint32_t rays_ = 0;
};

}  // namespace phos::shading
