// Walking a ray to the next event that scatters light: the one loop every integrator and the
// photon tracer use to find what a ray meets, passing straight through medium interfaces and
// sampling free flights in participating media.
#pragma once

#include <cstdint>

#include "accel/embree_scene.h"
#include "accel/ray.h"
#include "core/rng.h"
#include "shading/medium.h"
#include "shading/medium_tracking.h"

namespace phos::shading {

// One walker per path (camera path, gather ray or photon): it remembers what the path has crossed
// and which medium it travels in.
//
// A medium interface (Material::interface_only) is a surface that only separates two media: it
// neither reflects nor refracts, so the walk steps through it and keeps going. The medium changes
// where a ray crosses a surface that is a medium transition (MediumInterface::is_transition): it
// enters the side its direction points to (outside along the normal, inside against it). Surfaces
// that are no transition (walls without a MediumInterface) keep the medium on both sides, as in
// pbrt-v4. After a scattering surface, the caller says where the path goes on with leave().
class SurfaceWalk {
public:
    enum class Event {
        Surface,   // `hit` is a scattering surface (its material is not interface_only)
        Medium,    // a real scattering event in the current medium at medium_point()
        Escaped,   // nothing more along the ray: it leaves the scene in direction ray.dir
        Absorbed,  // the medium absorbed the path (its weight became 0)
        Lost,      // the path crossed more than kMaxCrossings interfaces (degenerate geometry)
    };
    // Crossings allowed per path: stacked or coincident interfaces cannot make a path loop forever.
    static constexpr int kMaxCrossings = 256;

    // `media` may be null (no media); `medium` is where the path starts (-1 = vacuum).
    explicit SurfaceWalk(const accel::EmbreeScene& accel, const MediaSet* media = nullptr, int medium = -1)
        : accel_(accel), media_(media && media->active() ? media : nullptr), medium_(medium) {}

    // Follows `ray` to the next scattering surface, stepping through interfaces (each step
    // continues from the interface along the same direction), ignoring the media's scattering and
    // absorption (only the medium index is followed). On return `ray` is the last segment's ray.
    Event next(Ray& ray, accel::SurfaceHit& hit);

    // The same with free-flight sampling in the media crossed (medium_tracking.h): returns Medium
    // when the path scatters in a medium, multiplies `beta` by the tracking weights, and adds to
    // `emitted` the medium emission met on the way (already multiplied by beta). Before each
    // stretch in a medium, calls on_stretch(const Medium&, Vec3 o, Vec3 d, float t_end) with the
    // whole stretch up to the next surface (as next_segments does) while `beta` still holds the
    // throughput before it: for estimators that integrate over the stretch (single scattering).
    // Wavelength-dependent coefficients are read at `lambda`.
    Event next(Ray& ray, accel::SurfaceHit& hit, Sampler& sampler, const Wavelengths& lambda, Spectrum& beta,
               Spectrum& emitted) {
        return next(ray, hit, sampler, lambda, beta, emitted, [](const Medium&, Vec3, Vec3, float) {});
    }
    template <class OnStretch>
    Event next(Ray& ray, accel::SurfaceHit& hit, Sampler& sampler, const Wavelengths& lambda, Spectrum& beta,
               Spectrum& emitted, OnStretch&& on_stretch);

    // The same without sampling: calls visit(const Medium&, Vec3 o, Vec3 d, float t_end) for
    // every stretch of the ray travelled in a medium before the returned event (d unit, t_end in
    // scene units, kInf for a ray that escapes), for estimators that integrate along the ray.
    template <class Visit>
    Event next_segments(Ray& ray, accel::SurfaceHit& hit, Visit&& visit);

    // The path scatters at surface `hit` into direction `dir`: sets the medium it travels in next.
    void leave(const accel::SurfaceHit& hit, Vec3 dir) { medium_ = medium_after(hit, dir, medium_); }
    // The medium a ray leaving `hit` in direction `dir` travels in, coming from `current`.
    static int medium_after(const accel::SurfaceHit& hit, Vec3 dir, int current) {
        if (!hit.media.is_transition()) return current;
        return dot(dir, hit.ng) > 0 ? hit.media.outside : hit.media.inside;
    }

    int medium() const { return medium_; }
    // The scattering point of the last Medium event and the unit direction back along the ray.
    Vec3 medium_point() const { return medium_p_; }
    Vec3 medium_wo() const { return medium_wo_; }

    // Distance travelled along the whole walk so far (every segment that ended at a surface,
    // interfaces included, and free flights up to medium events), in scene units.
    float distance() const { return distance_; }
    // Interfaces crossed so far.
    int crossings() const { return crossings_; }
    // Closest-hit queries made so far (interface crossings and the final miss included).
    uint32_t rays() const { return rays_; }

private:
    // Steps through interface `hit` (updating the medium); false when too many were crossed.
    bool cross(Ray& ray, const accel::SurfaceHit& hit);

    const accel::EmbreeScene& accel_;
    const MediaSet* media_;
    int medium_;
    Vec3 medium_p_, medium_wo_;
    float distance_ = 0;
    int crossings_ = 0;
    uint32_t rays_ = 0;
};

// Transmittance along a shadow ray that travels in `medium` (-1 = vacuum) from ray.origin to
// ray.tmax: 0 if a scattering surface blocks it, else the product of the media's transmittances
// over the stretches between the interfaces it crosses. Without active media this is a plain
// occlusion test.
Spectrum shadow_transmittance(const accel::EmbreeScene& accel, const MediaSet* media, Ray ray, int medium,
                              Sampler& sampler, const Wavelengths& lambda);

// ---- implementation ----

template <class OnStretch>
SurfaceWalk::Event SurfaceWalk::next(Ray& ray, accel::SurfaceHit& hit, Sampler& sampler,
                                     const Wavelengths& lambda, Spectrum& beta, Spectrum& emitted,
                                     OnStretch&& on_stretch) {
    const scene::Scene& scene = accel_.scene();
    while (true) {
        ++rays_;
        const bool found = accel_.intersect(ray, hit);
        const float len = length(ray.dir);
        if (media_ && medium_ >= 0) {
            const Vec3 d = ray.dir / len;
            const float t_end = found ? hit.t * len : kInf;
            const Medium& medium = (*media_)[medium_];
            on_stretch(medium, ray.origin, d, t_end);
            const FreeFlight f = sample_free_flight(medium, ray.origin, d, t_end, sampler, lambda, beta);
            emitted += beta * f.emitted;
            beta *= f.weight;
            if (f.scattered) {
                medium_p_ = ray.origin + d * f.t;
                medium_wo_ = -d;
                distance_ += f.t;
                return Event::Medium;
            }
            if (beta.is_black()) return Event::Absorbed;
        }
        if (!found) return Event::Escaped;
        distance_ += hit.t * len;
        if (!scene.materials[size_t(hit.material)].interface_only) return Event::Surface;
        if (!cross(ray, hit)) return Event::Lost;
    }
}

template <class Visit>
SurfaceWalk::Event SurfaceWalk::next_segments(Ray& ray, accel::SurfaceHit& hit, Visit&& visit) {
    const scene::Scene& scene = accel_.scene();
    while (true) {
        ++rays_;
        const bool found = accel_.intersect(ray, hit);
        const float len = length(ray.dir);
        if (media_ && medium_ >= 0)
            visit((*media_)[medium_], ray.origin, ray.dir / len, found ? hit.t * len : kInf);
        if (!found) return Event::Escaped;
        distance_ += hit.t * len;
        if (!scene.materials[size_t(hit.material)].interface_only) return Event::Surface;
        if (!cross(ray, hit)) return Event::Lost;
    }
}

}  // namespace phos::shading
