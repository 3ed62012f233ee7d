// One photon's random walk from a light through the scene (Jensen's photon tracing): emission by a
// power-chosen light, Russian roulette on the material's lobe albedos with per-channel power
// rescaling, and a callback at every non-specular surface hit where photon maps / SPPM store or
// splat it. In participating media (Jensen & Christensen 1998) the photon takes free flights
// (delta tracking, shading/medium_tracking.h), and at every real scattering event the visitor sees
// a volume hit; the photon then survives with probability = the albedo (Russian roulette) and
// scatters by the phase function. Each photon carries its own four wavelengths (hero-wavelength
// sampling, drawn first from its sampler) and its power at them; a photon that crosses a smooth
// dispersive interface keeps its hero wavelength alone. Shared by the photon-map, PPM and SPPM
// integrators.
#pragma once

#include <cstdint>
#include <type_traits>

#include "accel/embree_scene.h"
#include "core/rng.h"
#include "scene/scene.h"
#include "shading/bsdf.h"
#include "shading/lights.h"
#include "shading/material_bsdfs.h"
#include "shading/surface_walk.h"

namespace phos::photon {

// What photon tracing needs from the prepared scene.
struct PhotonScene {
    const scene::Scene& scene;
    const accel::EmbreeScene& accel;
    const shading::LightSet& lights;
    const shading::MaterialBsdfs& bsdfs;       // the BSDF at each hit
    const shading::MediaSet* media = nullptr;  // null or inactive: every ray travels in vacuum
    // Glossy lobes at least this sharp (a Phong exponent, Bsdf::split_lobes) scatter like delta
    // lobes: photons are not stored on them alone, and a path through them stays a caustic path.
    float sharp_exponent = kInf;
};

// A photon arriving at a surface whose BSDF has lobes the photon estimates read (diffuse or glossy
// lobes not as sharp as PhotonScene::sharp_exponent).
struct PhotonHit {
    const accel::SurfaceHit& hit;
    bool followed_lobes;        // the BSDF also has delta or sharp glossy lobes (a caustic path goes on)
    Vec3 wi;                    // unit direction towards where the photon came from
    Spectrum power;             // flux in W times the number of photons emitted (divide by N emitted)
    const Wavelengths& lambda;  // the wavelengths `power` is at
    int bounces;                // scattering events before this hit (0 = straight from the light)
    bool after_diffuse;         // some earlier bounce was non-specular (path L{S|D}*D D...)
    bool after_specular;        // the bounces so far were all specular and there was at least one (L S+ D)
};

// A photon scattering in a participating medium (a real collision chosen by delta tracking).
struct PhotonVolumeHit {
    Vec3 p;
    Vec3 wi;         // unit direction towards where the photon came from
    Spectrum power;  // as PhotonHit::power, already weighted by the scattering albedo at p
    const Wavelengths& lambda;
    int medium;  // index into the scene's media
    int bounces;
    bool after_diffuse;   // some earlier scattering was non-specular (surface or medium)
    bool after_specular;  // every earlier scattering was specular and there was one (L S+ V)
};

// A visitor made of one lambda per kind of hit: Visitor{on_surface, on_volume}.
template <class... F>
struct Visitor : F... {
    using F::operator()...;
};
template <class... F>
Visitor(F...) -> Visitor<F...>;

class ProjectionMap;  // photon/projection_map.h

struct PhotonPathOptions {
    int max_bounces = 16;  // scattering events after emission
    // Non-null: emit only towards the specular objects this projection map marks (caustic photons).
    const ProjectionMap* projection = nullptr;
};

// Traces photon `index` of pass `pass` (random numbers keyed by (seed, pass, index)), calling
// `visit(const PhotonHit&)` at every surface hit that has a non-specular component, before the
// photon scatters on (a visitor that returns bool ends the path by returning false), and, if the
// visitor accepts one, `visit(const PhotonVolumeHit&)` at every scattering event in a medium.
// Returns the number of rays traced.
template <class Visitor>
uint32_t trace_photon(const PhotonScene& ps, uint64_t seed, uint64_t pass, uint64_t index,
                      const PhotonPathOptions& options, Visitor&& visit);

// Whether photons can travel 16 at a time (trace_photons' packets): only surfaces stop them (no
// active media, no interface-only surfaces), so a photon's walk is one closest hit per event.
bool packets_possible(const PhotonScene& ps);

// Traces photons first + j, j in [0, count), of pass `pass`, each as trace_photon does, with
// visitor_of(j) as photon first + j's visitor; returns the rays traced. With `packets` (only where
// packets_possible) 16 photons are in flight, one rtcIntersect16 per step for all of them, and a
// finished photon's lane is refilled with the next emission: each photon's random numbers and
// events are those of trace_photon (the same helpers, and packet hits equal single hits), only
// the interleaving of different photons' visits differs.
template <class VisitorOf>
uint64_t trace_photons(const PhotonScene& ps, uint64_t seed, uint64_t pass, uint64_t first, uint64_t count,
                       const PhotonPathOptions& options, bool packets, VisitorOf&& visitor_of);

// ---- implementation ----

namespace detail {
// Emits the photon: picks a light by power and samples a ray from it. Returns false when the
// scene has no light with power. `power` is the sample weight divided by the light's pmf;
// `medium` is the light's medium.
bool emit_photon(const PhotonScene& ps, Sampler& sampler, const Wavelengths& lambda, Ray& ray,
                 Spectrum& power, int& medium);
// The same through a projection map (defined in projection_map.cpp).
bool emit_projected(const ProjectionMap& map, const PhotonScene& ps, Sampler& sampler,
                    const Wavelengths& lambda, Ray& ray, Spectrum& power, int& medium);
// Calls the visitor and tells whether the path goes on (visitors returning void always go on).
template <class Visitor, class Hit>
bool visit_hit(Visitor& visit, const Hit& h) {
    if constexpr (std::is_same_v<std::invoke_result_t<Visitor&, const Hit&>, bool>) {
        return visit(h);
    } else {
        visit(h);
        return true;
    }
}
// Russian roulette on the lobe kinds at a hit, then sampling of the chosen kind in Importance
// mode. Returns false when the photon is absorbed; otherwise updates `power` (per-channel exact
// expectation) and sets `wi_out` and whether the chosen lobe was specular: a delta lobe, or a
// glossy lobe at least as sharp as `sharp_exponent` (Bsdf::sharp_lobes). Crossing a smooth
// dispersive interface terminates the secondary wavelengths of `lambda` (and their power).
bool scatter_photon(const shading::Bsdf& bsdf, Vec3 wo, Sampler& sampler, Wavelengths& lambda,
                    Spectrum& power, Vec3& wi_out, bool& specular, float sharp_exponent = kInf);
// The same for a BSDF made of `lobe` alone (what scatter_photon does for it, to the bit); the
// scattering is diffuse.
bool scatter_photon(const shading::LambertLobe& lobe, Vec3 wo, Sampler& sampler, const Wavelengths& lambda,
                    Spectrum& power, Vec3& wi_out);

// A photon between events: what trace_photon carries from one bounce to the next (also the
// state of each lane of the photon tracer's wavefront, tracer.cpp).
struct PhotonState {
    Sampler sampler;
    Ray ray;
    Wavelengths lambda;
    Spectrum power;
    int medium = -1;
    int bounces = 0;
    bool after_diffuse = false, after_specular = false;
};
// Photon `index` of pass `pass`: its sampler, then its emission. False when no light emits it.
inline bool start_photon(const PhotonScene& ps, uint64_t seed, uint64_t pass, uint64_t index,
                         const PhotonPathOptions& options, PhotonState& st) {
    // Field by field: assigning a whole PhotonState{} went through a stack temporary whose
    // overlapping partial stores stalled the copy (5 % of the tracer's time).
    st.sampler = Sampler(seed, 0x70686f746f6eULL ^ pass, index);
    st.medium = -1;
    st.bounces = 0;
    st.after_diffuse = st.after_specular = false;
    st.lambda = Wavelengths::visible(st.sampler.next());
    return options.projection
               ? emit_projected(*options.projection, ps, st.sampler, st.lambda, st.ray, st.power, st.medium)
               : emit_photon(ps, st.sampler, st.lambda, st.ray, st.power, st.medium);
}
// The photon has reached scattering surface `hit` along st.ray: the visitor sees it (if it has a
// non-specular component), then Russian roulette and BSDF sampling. Returns false when the path
// ends; otherwise st.ray leaves the surface and `wi` is its direction (for SurfaceWalk::leave).
template <class Visitor>
bool surface_step(const PhotonScene& ps, const PhotonPathOptions& options, const accel::SurfaceHit& hit,
                  PhotonState& st, Visitor& visit, Vec3& wi) {
    const Vec3 wo = -normalize(st.ray.dir);
    // The visitor sees the hit if the BSDF has lobes the estimates read (`stores`); then, unless
    // the path ends there, scatter() does the Russian roulette and samples the BSDF.
    const auto visit_and_scatter = [&](bool stores, bool followed, auto&& scatter) {
        if (stores) {
            const PhotonHit ph{
                hit, followed, wo, st.power, st.lambda, st.bounces, st.after_diffuse, st.after_specular};
            // A visitor returning bool may end the path (false): e.g. once no map it fills can
            // take this photon any more.
            if (!visit_hit(visit, ph)) return false;
        }
        return st.bounces != options.max_bounces && scatter();
    };
    bool specular = false;
    // A lone Lambert lobe (most surfaces) scatters without a copy of the whole BSDF.
    shading::LambertLobe lambert;
    if (ps.bsdfs.lambert_at(hit, lambert)) {
        if (!visit_and_scatter(true, false, [&] {
                return scatter_photon(lambert, wo, st.sampler, st.lambda, st.power, wi);
            }))
            return false;
    } else {
        const shading::Bsdf bsdf = ps.bsdfs.at(hit);
        if (!visit_and_scatter(bsdf.has_estimated(ps.sharp_exponent), bsdf.has_followed(ps.sharp_exponent),
                               [&] {
                                   return scatter_photon(bsdf, wo, st.sampler, st.lambda, st.power, wi,
                                                         specular, ps.sharp_exponent);
                               }))
            return false;
    }
    if (specular) {
        st.after_specular = !st.after_diffuse;
    } else {
        st.after_diffuse = true;
        st.after_specular = false;
    }
    // spawn_ray's ray, written in place: a Ray temporary assembled by narrow stores and copied
    // with wide loads stalled on store forwarding (1.4 % of the tracer's time).
    st.ray.origin = accel::offset_origin(hit, wi);
    st.ray.dir = wi;
    st.ray.tmin = 0.0f;
    st.ray.tmax = kInf;
    ++st.bounces;
    return true;
}
}  // namespace detail

template <class Visitor>
uint32_t trace_photon(const PhotonScene& ps, uint64_t seed, uint64_t pass, uint64_t index,
                      const PhotonPathOptions& options, Visitor&& visit) {
    detail::PhotonState st;
    if (!detail::start_photon(ps, seed, pass, index, options, st)) return 0;
    if (options.max_bounces < 0) return 0;
    const shading::MediaSet* media = ps.media && ps.media->active() ? ps.media : nullptr;
    shading::SurfaceWalk walk(ps.accel, media, st.medium);
    while (true) {
        accel::SurfaceHit hit;
        const Spectrum power_before = st.power;
        Spectrum emitted;  // media emission is not traced from the camera side only; photons ignore it
        const shading::SurfaceWalk::Event event =
            media ? walk.next(st.ray, hit, st.sampler, st.lambda, st.power, emitted) : walk.next(st.ray, hit);
        if (event == shading::SurfaceWalk::Event::Medium) {
            const PhotonVolumeHit vh{walk.medium_point(), walk.medium_wo(), st.power,
                                     st.lambda,           walk.medium(),    st.bounces,
                                     st.after_diffuse,    st.after_specular};
            if constexpr (std::is_invocable_v<Visitor&, const PhotonVolumeHit&>) {
                if (!detail::visit_hit(visit, vh)) break;
            }
            if (st.bounces == options.max_bounces) break;
            // Russian roulette on the albedo the tracking weight applied: keep the power of a
            // grey medium's photon constant (Jensen & Christensen 1998).
            const float q = std::min(1.0f, st.power.average() / std::max(power_before.average(), 1e-30f));
            if (!(st.sampler.next() < q)) break;
            st.power *= 1.0f / q;
            Vec3 wi;
            ps.media->operator[](walk.medium()).phase().sample(walk.medium_wo(), st.sampler.next2(), wi);
            st.ray = Ray{walk.medium_point(), wi};
            st.after_diffuse = true;
            st.after_specular = false;
            ++st.bounces;
            continue;
        }
        if (event != shading::SurfaceWalk::Event::Surface) break;
        Vec3 wi;
        if (!detail::surface_step(ps, options, hit, st, visit, wi)) break;
        walk.leave(hit, wi);
    }
    return walk.rays();
}

template <class VisitorOf>
uint64_t trace_photons(const PhotonScene& ps, uint64_t seed, uint64_t pass, uint64_t first, uint64_t count,
                       const PhotonPathOptions& options, bool packets, VisitorOf&& visitor_of) {
    uint64_t total = 0;
    if (!packets || options.max_bounces < 0) {
        for (uint64_t j = 0; j < count; ++j)
            total += trace_photon(ps, seed, pass, first + j, options, visitor_of(j));
        return total;
    }
    detail::PhotonState lane[16];
    uint64_t photon[16];
    uint32_t rays[16] = {};
    bool live[16] = {};
    Ray ray[16];
    accel::SurfaceHit hit[16];
    bool found[16];
    uint64_t next = 0;
    while (true) {
        int n_live = 0;
        for (int k = 0; k < 16; ++k) {
            while (!live[k] && next < count) {
                photon[k] = next++;
                rays[k] = 0;
                live[k] = detail::start_photon(ps, seed, pass, first + photon[k], options, lane[k]);
            }
            n_live += live[k];
        }
        if (n_live == 0) break;
        int n = 16;
        while (n > 0 && !live[n - 1]) --n;
        for (int k = 0; k < n; ++k)
            ray[k] = live[k] ? lane[k].ray : Ray{Vec3(0.0f), Vec3(0.0f), 0.0f, 0.0f};  // not traced
        ps.accel.intersect16(ray, n, hit, found);
        for (int k = 0; k < n; ++k) {
            if (!live[k]) continue;
            ++rays[k];
            Vec3 wi;
            auto visit = visitor_of(photon[k]);
            if (found[k] && detail::surface_step(ps, options, hit[k], lane[k], visit, wi)) continue;
            total += rays[k];  // escaped, absorbed or stopped
            live[k] = false;
        }
    }
    return total;
}

}  // namespace phos::photon
