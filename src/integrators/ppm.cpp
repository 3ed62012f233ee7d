// PPM's orchestration, one screen (Hachisuka, Ogaki & Jensen 2008): a single eye pass stores hit
// points with their direct light (the paper's ray tracing pass), then each iteration is a photon
// tracing pass over the hit-point grid (rebuilt as the radii shrink) and the per-point update of N,
// R², τ (its radius reduction and flux correction, sppm_pixel_stats.h); the pixel value is the mean
// over its hit points of direct light + τ / (π R² N_emitted) (its radiance evaluation).
#include "integrators/ppm.h"

#include <tbb/parallel_for.h>

#include "integrators/sppm_core.h"
#include "render/path_recorder.h"
#include "render/pixel_loop.h"
#include "render/progressive_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

namespace {

using sppm::PixelStats;

// Hit point s of pixel (x, y), one of `eye` per pixel: its eye path, keyed by (seed, slot),
// jittered inside the pixel.
Rgb hit_point_path(const Prepared& P, int x, int y, int s, int eye, int direct_samples, VisiblePoint& vp,
                   RayCounts& rays) {
    const RenderOptions& ro = P.options;
    const size_t i = (size_t(y) * size_t(ro.width) + size_t(x)) * size_t(eye) + size_t(s);
    Sampler sampler(ro.seed, 0x70706d657965ULL, i);
    // One hit point per pixel is the pixel's centre; several are spread by the pixel filter.
    const PixelFilterSampler::FilmSample at =
        eye == 1 ? PixelFilterSampler::FilmSample{Vec2{0.5f, 0.5f}, 1.0f}
                 : P.filter.sample(stratified_sample(s, eye, sampler.next2()));
    const Vec2 lens = sampler.next2();
    float camera_weight = 1;
    const Ray ray =
        P.camera.generate_ray(float(x) + at.position.x, float(y) + at.position.y, lens, camera_weight);
    ++rays.camera;
    if (camera_weight == 0) {  // the camera's lenses blocked the ray: no hit point, black
        vp.bsdf.reset();
        vp.medium = -1;
        return Rgb(0.0f);
    }
    const Rgb L = trace_eye_path(P, ray, sampler, direct_samples, vp, rays);
    const float weight = at.weight * camera_weight;
    if (weight == 1) return L;
    vp.beta *= weight;
    return L * weight;
}

// The ray tracing pass, deterministic in the seed, so a resumed render recomputes the
// same hit points: each slot's hit point, its direct light, and its initial radius.
void ray_tracing_pass(const Prepared& P, int eye, int direct_samples, const sppm::InitialRadius& initial,
                      std::vector<VisiblePoint>& vps, std::vector<PixelStats>& slots) {
    const RenderOptions& ro = P.options;
    tbb::parallel_for(0, ro.height, [&](int y) {
        RayCounts rays;
        for (int x = 0; x < ro.width; ++x)
            for (int s = 0; s < eye; ++s) {
                const size_t i = (size_t(y) * size_t(ro.width) + size_t(x)) * size_t(eye) + size_t(s);
                const Rgb L = hit_point_path(P, x, y, s, eye, direct_samples, vps[i], rays);
                PixelStats& st = slots[i];
                for (int c = 0; c < 3; ++c) st.direct[c] = L.is_finite() ? double(L[c]) : 0.0;
                if (!L.is_finite()) P.stats.add_dropped_samples(1);  // counted for -v, never added
                if (vps[i].present() && st.r2 == 0) st.r2 = initial.r2(vps[i]);
            }
        P.stats.add_rays(rays);
    });
}

}  // namespace

RenderDone PpmIntegrator::render(const Prepared& P, film::Film& film, Progress& progress) {
    using namespace sppm;
    const RenderOptions& ro = P.options;
    const int eye = std::max(1, opt_.eye_samples);
    const size_t slots = size_t(ro.width) * size_t(ro.height) * size_t(eye);
    ProgressiveState state = start_state(P.options, budget_, "ppm", uint32_t(eye), "iterations",
                                         uint64_t(std::max(1, P.options.spp)));
    const int direct_samples = direct_samples_for(opt_, true);
    std::vector<VisiblePoint> vps(slots);
    ray_tracing_pass(P, eye, direct_samples, {opt_.radius, opt_.radius_pixels, P.camera.pixel_footprint()},
                     vps, state.slots);

    PhotonAccumulator acc(slots);
    // --trace-pixel: that pixel's eye paths run again, recorded, and its hit points' photons.
    PathRecorder* const trace = requested_trace();
    if (trace) {
        const size_t first = (size_t(trace->y()) * size_t(ro.width) + size_t(trace->x())) * size_t(eye);
        acc.record(trace, first, size_t(eye));
        for (int s = 0; s < eye; ++s)
            record_eye_path(*trace, uint64_t(s), -1, first + size_t(s), false, [&](VisiblePoint& vp) {
                RayCounts uncounted;
                return hit_point_path(P, trace->x(), trace->y(), s, eye, direct_samples, vp, uncounted);
            });
    }
    photon::HitPointGrid grid;
    // Hit points in media (free flights of the eye pass) take the 3D estimate.
    std::vector<uint8_t> volume_slot(slots, 0);
    for (size_t i = 0; i < slots; ++i) volume_slot[i] = vps[i].volume() ? 1 : 0;
    auto resolve_film = [&] {
        resolve(state.slots, eye, 1.0 / eye, 1.0, state.photons_emitted, film, ro.layers, volume_slot);
    };

    ProgressiveBudget budget(ro, budget_, state, film, progress);
    while (budget.next()) {
        if (trace) trace->begin_pass(state.iterations, false, [&](size_t s) { return state.slots[s].r2; });
        // The photon tracing pass and the update: N ← N + αM, R² ← R² (N + αM)/(N + M),
        // τ ← (τ + Φ) R²_new/R²_old.
        photon_iteration(P, acc, vps, state, grid, state.iterations, opt_.photons_per_iter, opt_.alpha);
        end_iteration(trace, state, budget, resolve_film);
    }
    return finish_progressive(P, "ppm", state, budget, resolve_film);
}

}  // namespace phos::integrators
