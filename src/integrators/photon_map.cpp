// Orchestration of the two-pass photon mapper (see photon_map.h): option checks, pass 1 (tracing,
// k-d trees, beams and caches; its -v statistics in photon/map_report.h) and pass 2's tile loop.
#include "integrators/photon_map.h"

#include <chrono>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/stats.h"
#include "dist/ranks.h"
#include "integrators/photon_map_radiance.h"
#include "photon/beam_estimate.h"
#include "photon/map_report.h"
#include "photon/projection_map.h"
#include "render/path_recorder.h"
#include "render/pixel_loop.h"
#include "render/pixel_trace.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

namespace {

// Fills automatic radii from the scene's size.
PhotonMapOptions resolve(const PhotonMapOptions& o, const Prepared& P) {
    PhotonMapOptions r = o;
    const float scene_radius = shading::SceneSphere::from_bounds(P.accel.bounds()).radius;
    for (PhotonMapSettings* s : {&r.global, &r.caustic, &r.indirect, &r.volume, &r.volume_caustic})
        if (!(s->radius > 0)) s->radius = std::max(s->radius_fraction * scene_radius, 1e-6f);
    if (!(r.volume_step > 0)) r.volume_step = 0.5f * r.volume.radius;
    return r;
}

// What pass 1 traces: only the maps pass 2 will read, each to its target.
photon::TraceOptions trace_options(const PhotonMapOptions& o, const Prepared& P, bool record_bounces) {
    photon::TraceOptions to;
    to.wanted[photon::kGlobalMap] = o.photon_viz || (o.indirect_light && !o.fast_global);
    to.wanted[photon::kCausticMap] =
        !o.photon_viz && o.caustics && photon::has_caustic_casters(P.scene, P.options.sharp_glossy);
    to.wanted[photon::kIndirectMap] = !o.photon_viz && o.indirect_light && o.fast_global;
    to.target[photon::kGlobalMap] = o.global.photons;
    to.target[photon::kCausticMap] = o.caustic.photons;
    to.target[photon::kIndirectMap] = o.indirect.photons;
    // Media: multiple scattering and volume caustics (single scattering is sampled from the lights).
    const bool media = P.active_media() != nullptr && !o.photon_viz;
    to.wanted[photon::kVolumeMap] = media && o.indirect_light;
    to.wanted[photon::kVolumeCausticMap] =
        media && o.caustics && photon::has_caustic_casters(P.scene, P.options.sharp_glossy);
    to.target[photon::kVolumeMap] = o.volume.photons;
    to.target[photon::kVolumeCausticMap] = o.volume_caustic.photons;
    to.emit = o.photons;
    uint64_t largest = 0;
    for (int m = 0; m < photon::kMapCount; ++m)
        if (to.wanted[m]) largest = std::max(largest, to.target[m]);
    // Without --photons, a map whose photons are rare (a caustic from a small glass object) stops
    // after this many emissions rather than tracing forever.
    to.max_emit = o.max_emitted > 0 ? o.max_emitted : std::max<uint64_t>(200 * largest, 1000000);
    to.max_depth = o.max_photon_depth;
    to.seed = P.options.seed;
    to.caustic_projection = o.projection_maps;
    to.record_bounces = record_bounces;
    return to;
}

// The k-d trees over the traced photons, built in place (the traced array becomes the tree's: no
// second copy at the peak); with `record_bounces` each photon's bounce count in tree order.
// Returns the trees' thread time by level, summed.
photon::KdBuildStats build_trees(photon::TracedPhotons& traced, PhotonMaps& maps, bool record_bounces) {
    photon::KdBuildStats build_times;
    for (int m = 0; m < photon::kMapCount; ++m) {
        photon::KdTreeOptions ko;
        ko.keep_input_index = record_bounces;
        maps.map[m].build(std::move(traced.photons[m]), ko);
        build_times.top_seconds += maps.map[m].build_stats().top_seconds;
        build_times.below_seconds += maps.map[m].build_stats().below_seconds;
        maps.emitted[m] = traced.emitted[m];
        if (record_bounces) {
            maps.bounces[m].resize(maps.map[m].size());
            for (uint32_t i = 0; i < maps.map[m].size(); ++i)
                maps.bounces[m][i] = traced.bounces[m][maps.map[m].input_index(i)];
        }
        std::vector<photon::Photon>().swap(traced.photons[m]);
    }
    return build_times;
}

// --volume-estimate beam: each volume photon's kernel radius from its k nearest neighbours, then
// the spheres' BVH.
void build_beams(const PhotonMapOptions& o, const Prepared& P, PhotonMaps& maps) {
    if (o.volume_estimate != VolumeEstimate::Beam || (maps.volume().empty() && maps.volume_caustic().empty()))
        return;
    const auto t0 = std::chrono::steady_clock::now();
    maps.volume_beams.build(
        photon::photon_spheres(maps.volume(), o.volume.samples, o.volume.radius, &P.accel));
    maps.volume_caustic_beams.build(photon::photon_spheres(maps.volume_caustic(), o.volume_caustic.samples,
                                                           o.volume_caustic.radius, &P.accel));
    P.stats.add_time("beam BVH build", seconds_since(t0));
}

// --irradiance-cache: the irradiance cache over the global map, the volume cache over the volume
// maps.
void build_caches(const PhotonMapOptions& o, const photon::TraceOptions& to, const Prepared& P,
                  PhotonMaps& maps) {
    if (o.irradiance_cache && to.wanted[photon::kGlobalMap] && !o.photon_viz) {
        const auto t0 = std::chrono::steady_clock::now();
        PhotonMapRadiance R(P, o, maps);
        maps.cache.build(maps.global(), R.estimate_options(photon::kGlobalMap), o.cache_stride);
        P.stats.add_time("irradiance cache", seconds_since(t0));
        P.stats.add_value("irradiance cache points", std::to_string(maps.cache.size()));
    }
    if (o.irradiance_cache && to.wanted[photon::kVolumeMap] && !maps.volume().empty()) {
        const auto t0 = std::chrono::steady_clock::now();
        maps.volume_cache.build(
            maps.volume(), {o.volume.samples, o.volume.radius, &P.accel}, maps.volume_caustic(),
            {o.volume_caustic.samples, o.volume_caustic.radius, &P.accel}, o.cache_stride);
        P.stats.add_time("volume cache", seconds_since(t0));
        P.stats.add_value("volume cache points", std::to_string(maps.volume_cache.size()));
    }
}

}  // namespace

// The options arrive validated against their table (integrators/registry.cpp).
PhotonMapIntegrator::PhotonMapIntegrator(const PhotonMapOptions& options, RenderBudget budget,
                                         std::vector<Component> layers)
    : options_(options), budget_(std::move(budget)), layers_(std::move(layers)) {}

// Pass 1 (Jensen 1996): trace the photons, build the k-d trees, then what pass 2 reads besides.
PhotonMaps PhotonMapIntegrator::build_maps(const Prepared& P, bool record_bounces) const {
    const PhotonMapOptions o = resolve(options_, P);
    const photon::TraceOptions to = trace_options(o, P, record_bounces);
    const photon::PhotonScene ps{P.scene, P.accel,          P.lights,
                                 P.bsdfs, P.active_media(), P.options.sharp_glossy};
    photon::MapBuildTimes times;
    auto t0 = std::chrono::steady_clock::now();
    photon::TracedPhotons traced = photon::trace_photons(ps, to);
    times.trace_seconds = seconds_since(t0);
    P.stats.add_time("photon trace", times.trace_seconds);
    RayCounts rc;
    rc.photon = traced.rays;
    P.stats.add_rays(rc);

    PhotonMaps maps;
    t0 = std::chrono::steady_clock::now();
    times.stored = traced.stored();
    times.build = build_trees(traced, maps, record_bounces);
    times.build_seconds = seconds_since(t0);
    P.stats.add_time("photon map build", times.build_seconds);
    build_beams(o, P, maps);
    photon::report_map_build(P.stats, to, traced, maps, times, P.lights.size() > 0);
    build_caches(o, to, P, maps);
    return maps;
}

RenderDone PhotonMapIntegrator::render_with(const Prepared& P, const PhotonMaps& maps, film::Film& film,
                                            Progress& progress, bool store_maps) const {
    const PhotonMapOptions o = resolve(options_, P);
    const PhotonMapRadiance R(P, o, maps);
    std::function<void(std::string&)> payload;
    if (store_maps) payload = [&maps](std::string& out) { out = maps.save(); };
    if (P.options.layers)
        return render_layers(
            P, film, budget_, "photonmap", progress, layers_,
            [&](const Ray& ray, Sampler& sampler, RayCounts& rays, RadianceParts& parts) {
                parts = R.camera_ray(ray, sampler, rays);
                return parts.total();
            },
            payload);
    return render_samples(
        P, film, budget_, "photonmap", progress,
        [&](int x, int y, const Ray& ray, float weight, Sampler& sampler, RayCounts& rays) {
            // Weight 0 (a ray the camera's lenses blocked) is a black sample, not traced.
            film.add_sample(x, y,
                            weight != 0 ? R.camera_ray(ray, sampler, rays).total() * weight : Rgb(0.0f));
        },
        payload);
}

// Resuming reads the maps from the checkpoint (after checking it is this render's): on
// cornell-glass-mirror with 400 k photons, tracing, building and caching them again took 2.3 s,
// reading them 0.02 s (docs/photon-mapping.md).
RenderDone PhotonMapIntegrator::render(const Prepared& P, film::Film& film, Progress& progress) {
    // Below 9 samples per pixel the caustic kernel widens with fewer samples (photon_map_radiance.cpp),
    // so there every sample depends on the count: such a checkpoint resumes only to the same count.
    const int64_t n = int64_t(std::max(1, P.options.spp)) * std::max(1, P.options.dof_samples);
    if (n < 9)
        budget_.observers.identity.options.emplace_back(
            "--spp (the caustic kernel depends on it below 9 samples)", std::to_string(n));
    PhotonMaps maps;
    const ProgressiveState* saved = budget_.observers.resume.get();
    if (saved && !saved->payload.empty()) {
        const std::string& path = budget_.settings.resume_path;
        check_resumable(*saved, render_identity(P.options, budget_, "photonmap", 0), path);
        const auto t0 = std::chrono::steady_clock::now();
        maps = PhotonMaps::load(saved->payload, "checkpoint '" + path + "': photon maps");
        P.stats.add_time("photon maps read from the checkpoint", seconds_since(t0));
    } else {
        maps = build_maps(P);
        if (dist::any(interrupt::requested()))  // the maps are incomplete (on some rank): no samples
            return RenderDone{.interrupted = true};
    }
    const auto t0 = std::chrono::steady_clock::now();
    const RenderDone done = render_with(P, maps, film, progress, budget_.observers.on_checkpoint != nullptr);
    P.stats.add_time("photon map render pass", seconds_since(t0));
    // --trace-pixel: that pixel's samples again, from the same maps (pixel_trace.h).
    if (requested_trace()) {
        const PhotonMapOptions o = resolve(options_, P);
        const PhotonMapRadiance R(P, o, maps);
        trace_pixel_samples(P, film, [&](const Ray& ray, Sampler& sampler, RayCounts& rays) {
            return R.camera_ray(ray, sampler, rays).total();
        });
    }
    return done;
}

}  // namespace phos::integrators
