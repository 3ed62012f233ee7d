// Orchestration of the two-pass photon mapper (see photon_map.h): option checks, pass 1 (tracing,
// k-d trees, irradiance cache, -v statistics) and pass 2's deterministic tile loop.
#include "integrators/photon_map.h"

#include <chrono>
#include <cstdio>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/log.h"
#include "core/stats.h"
#include "dist/ranks.h"
#include "integrators/photon_map_radiance.h"
#include "photon/beam_estimate.h"
#include "photon/projection_map.h"
#include "render/path_recorder.h"
#include "render/pixel_loop.h"
#include "render/pixel_trace.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

namespace {

std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

// "1 thread", "4 threads".
std::string threads_text(int n) { return std::to_string(n) + (n == 1 ? " thread" : " threads"); }

// Fills automatic radii from the scene's size.
PhotonMapOptions resolve(const PhotonMapOptions& o, const Prepared& P) {
    PhotonMapOptions r = o;
    const float scene_radius = shading::SceneSphere::from_bounds(P.accel.bounds()).radius;
    for (PhotonMapSettings* s : {&r.global, &r.caustic, &r.indirect, &r.volume, &r.volume_caustic})
        if (!(s->radius > 0)) s->radius = std::max(s->radius_fraction * scene_radius, 1e-6f);
    if (!(r.volume_step > 0)) r.volume_step = 0.5f * r.volume.radius;
    return r;
}

// True if some material has a delta lobe (mirror or smooth glass): only then can there be
// caustic photons (L S+ D), and only then is the caustic map worth tracing.
bool has_delta_materials(const scene::Scene& scene) {
    for (const scene::Material& m : scene.materials)
        if (photon::has_delta_lobe(m)) return true;
    return false;
}

}  // namespace

// The options arrive validated against their table (integrators/registry.cpp).
PhotonMapIntegrator::PhotonMapIntegrator(const PhotonMapOptions& options, RenderBudget budget,
                                         std::vector<Component> layers)
    : options_(options), budget_(std::move(budget)), layers_(std::move(layers)) {}

PhotonMaps PhotonMapIntegrator::build_maps(const Prepared& P, bool record_bounces) const {
    const PhotonMapOptions o = resolve(options_, P);
    PhotonMaps maps;
    photon::TraceOptions to;
    // Only the maps pass 2 will read are traced.
    to.wanted[photon::kGlobalMap] = o.photon_viz || (o.indirect_light && !o.fast_global);
    to.wanted[photon::kCausticMap] = !o.photon_viz && o.caustics && has_delta_materials(P.scene);
    to.wanted[photon::kIndirectMap] = !o.photon_viz && o.indirect_light && o.fast_global;
    to.target[photon::kGlobalMap] = o.global.photons;
    to.target[photon::kCausticMap] = o.caustic.photons;
    to.target[photon::kIndirectMap] = o.indirect.photons;
    // Media: multiple scattering and volume caustics (single scattering is sampled from the lights).
    const bool media = P.active_media() != nullptr && !o.photon_viz;
    to.wanted[photon::kVolumeMap] = media && o.indirect_light;
    to.wanted[photon::kVolumeCausticMap] = media && o.caustics && has_delta_materials(P.scene);
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

    const photon::PhotonScene ps{P.scene, P.accel, P.lights, P.bsdfs, P.active_media()};
    auto t0 = std::chrono::steady_clock::now();
    photon::TracedPhotons traced = photon::trace_photons(ps, to);
    const double trace_s = seconds_since(t0);
    P.stats.add_time("photon trace", trace_s);
    RayCounts rc;
    rc.photon = traced.rays;
    P.stats.add_rays(rc);

    t0 = std::chrono::steady_clock::now();
    const uint64_t stored = traced.stored();
    photon::KdBuildStats build_times;
    for (int m = 0; m < photon::kMapCount; ++m) {
        photon::KdTreeOptions ko;
        ko.keep_input_index = record_bounces;
        // In place: the traced array becomes the tree's (no second copy at the peak).
        maps.map[m].build(std::move(traced.photons[m]), ko);
        build_times.top_seconds += maps.map[m].build_stats().top_seconds;
        build_times.below_seconds += maps.map[m].build_stats().below_seconds;
        maps.emitted[m] = traced.emitted[m];
        if (record_bounces) {  // into tree order
            maps.bounces[m].resize(maps.map[m].size());
            for (uint32_t i = 0; i < maps.map[m].size(); ++i)
                maps.bounces[m][i] = traced.bounces[m][maps.map[m].input_index(i)];
        }
        std::vector<photon::Photon>().swap(traced.photons[m]);
    }
    const double build_s = seconds_since(t0);
    P.stats.add_time("photon map build", build_s);
    if (o.volume_estimate == VolumeEstimate::Beam &&
        (!maps.volume().empty() || !maps.volume_caustic().empty())) {
        // Each volume photon's kernel radius from its k nearest neighbours, then the spheres' BVH.
        t0 = std::chrono::steady_clock::now();
        maps.volume_beams.build(photon::photon_spheres(maps.volume(), o.volume.samples, o.volume.radius));
        maps.volume_caustic_beams.build(
            photon::photon_spheres(maps.volume_caustic(), o.volume_caustic.samples, o.volume_caustic.radius));
        P.stats.add_time("beam BVH build", seconds_since(t0));
        P.stats.add_value(
            "beam BVH memory",
            fmt("%.3g MB",
                double(maps.volume_beams.memory_bytes() + maps.volume_caustic_beams.memory_bytes()) / 1e6));
    }

    P.stats.add_value("photons emitted", std::to_string(traced.total_emitted));
    for (int m = 0; m < photon::kMapCount; ++m) {
        if (!to.wanted[m]) continue;
        P.stats.add_value(std::string(photon::map_name(m)) + " map",
                          std::to_string(maps.map[m].size()) + " photons from " +
                              std::to_string(maps.emitted[m]) + " emitted" +
                              (traced.reached[m]      ? ""
                               : P.lights.size() == 0 ? " (no lights)"
                                                      : " (emission cap reached before the budget)"));
        // Without lights nothing is emitted: the app's no-lights warning says so, not --max-emitted.
        if (!traced.reached[m] && to.target[m] > 0 && P.lights.size() > 0)
            log::warn_once(std::string("pm-cap-") + photon::map_name(m),
                           std::string("photon map: the ") + photon::map_name(m) + " map got " +
                               std::to_string(maps.map[m].size()) + " of " + std::to_string(to.target[m]) +
                               " photons before the emission cap (--max-emitted)");
    }
    if (to.wanted[photon::kCausticMap] && o.projection_maps)
        P.stats.add_value(
            "caustic projection maps",
            fmt("%.3g %% of the emitted power aimed at specular objects", 100.0 * traced.caustic_fraction) +
                fmt(", built in %.3f s", traced.projection_seconds) +
                fmt(", caustic tracing %.3g stored photons/s",
                    traced.caustic_seconds > 0 ? double(maps.caustic().size()) / traced.caustic_seconds
                                               : 0.0));
    P.stats.add_value("bytes per photon", std::to_string(sizeof(photon::Photon)));
    if (dist::distributed())  // each rank traced its batches; all received every batch
        P.stats.add_value("photon batches exchanged (MPI)",
                          fmt("%.3g MB", double(traced.exchanged_bytes) * 1e-6) +
                              fmt(" in %.3f s", traced.exchange_seconds));
    P.stats.add_value("photon map pages faulted in",
                      fmt("%.3g MB", double(traced.faulted_bytes) * 1e-6) +
                          fmt(" in %.3f s of the trace", traced.fault_in_seconds));
    // How busy the tracing threads were: below ~95 % the pipeline waits (commits, the last
    // batches); at ~100 % a rate that grows less than the thread count is the cores' own speed.
    if (traced.pipeline_seconds > 0 && traced.threads > 0)
        P.stats.add_value(
            "photon tracing threads busy",
            fmt("%.1f %%", 100.0 * traced.batch_seconds / (traced.threads * traced.pipeline_seconds)) +
                fmt(" (batches %.3f s on ", traced.batch_seconds) + threads_text(traced.threads) +
                fmt(" in %.3f s;", traced.pipeline_seconds) +
                fmt(" commits %.3f s, serial)", traced.commit_seconds));
    P.stats.add_value("photon tracing rate",
                      fmt("%.3g stored photons/s", trace_s > 0 ? double(stored) / trace_s : 0.0));
    // The build's thread time by level: on many cores, a top-level share that grows with the
    // thread count means those passes over the whole map wait for memory.
    P.stats.add_value("photon map build thread time",
                      fmt("top levels %.3f s, ", build_times.top_seconds) +
                          fmt("below them %.3f s", build_times.below_seconds) + fmt(" in %.3f s", build_s) +
                          (traced.threads > 0 ? " on " + threads_text(traced.threads) : std::string()));
    P.stats.add_value("photon map build rate",
                      fmt("%.3g photons/s", build_s > 0 ? double(stored) / build_s : 0.0));

    if (o.irradiance_cache && to.wanted[photon::kGlobalMap] && !o.photon_viz) {
        t0 = std::chrono::steady_clock::now();
        PhotonMapRadiance R(P, o, maps);
        maps.cache.build(maps.global(), R.estimate_options(photon::kGlobalMap), o.cache_stride);
        P.stats.add_time("irradiance cache", seconds_since(t0));
        P.stats.add_value("irradiance cache points", std::to_string(maps.cache.size()));
    }
    if (o.irradiance_cache && to.wanted[photon::kVolumeMap] && !maps.volume().empty()) {
        t0 = std::chrono::steady_clock::now();
        maps.volume_cache.build(maps.volume(), {o.volume.samples, o.volume.radius}, maps.volume_caustic(),
                                {o.volume_caustic.samples, o.volume_caustic.radius}, o.cache_stride);
        P.stats.add_time("volume cache", seconds_since(t0));
        P.stats.add_value("volume cache points", std::to_string(maps.volume_cache.size()));
    }
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
        [&](int x, int y, const Ray& ray, Sampler& sampler, RayCounts& rays) {
            film.add_sample(x, y, R.camera_ray(ray, sampler, rays).total());
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
