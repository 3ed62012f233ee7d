// SPPM's orchestration, one screen: per iteration an eye pass (visible points, direct light), the
// hit-point grid, a photon pass, and the per-pixel update of N, R², τ (Hachisuka & Jensen 2009,
// eq. 9-11, sppm_pixel_stats.h); the pixel value is eq. 12 plus the direct-light average.
#include "integrators/sppm.h"

#include <tbb/parallel_for.h>

#include "core/low_discrepancy.h"
#include "dist/ranks.h"
#include "film/tiles.h"
#include "integrators/sppm_core.h"
#include "render/path_recorder.h"
#include "render/progressive_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

RenderDone SppmIntegrator::render(const Prepared& P, film::Film& film, Progress& progress) {
    using namespace sppm;
    const RenderOptions& ro = P.options;
    const size_t pixels = size_t(ro.width) * size_t(ro.height);
    // With media each pixel has two slots, one for surface and one for volume visible points, so
    // each keeps statistics of one kernel dimension; the pixel is their sum.
    const size_t per_pixel = P.active_media() ? 2 : 1;
    ProgressiveState state = start_state(P.options, budget_, "sppm", uint32_t(per_pixel), "iterations",
                                         uint64_t(std::max(1, P.options.spp)));
    std::vector<uint8_t> volume_slot;
    if (per_pixel == 2) {
        volume_slot.assign(pixels * 2, 0);
        for (size_t i = 0; i < pixels; ++i) volume_slot[2 * i + 1] = 1;
    }

    const uint64_t photons = opt_.photons_per_iter;
    const int direct_samples = direct_samples_for(opt_, false);
    const float radius_pixels = opt_.radius_pixels;
    const InitialRadius initial{opt_.radius, radius_pixels, P.camera.pixel_footprint()};
    // The pilot refines the automatic (footprint) radius only; an explicit --radius is kept.
    PilotRadius pilot;
    if (opt_.radius <= 0) {
        pilot.k = opt_.radius_photons;
        const double lo = kPilotRadiusMinPixels / radius_pixels, hi = kPilotRadiusMaxPixels / radius_pixels;
        pilot.min_scale = std::min(1.0, lo * lo);
        pilot.max_scale = std::max(1.0, hi * hi);
    }
    std::vector<VisiblePoint> vps(pixels * per_pixel);
    PhotonAccumulator acc(pixels * per_pixel);
    photon::HitPointGrid grid;
    const auto tiles = film::make_tiles(ro.width, ro.height);
    EyePassExchange exchange;  // under MPI: the ranks' eye passes
    // Pixel (x, y)'s eye path of iteration `it`, keyed by (seed, pixel, iteration). Its position
    // in the pixel, on the lens and its light samples are points `it` (`it` × direct_samples + k)
    // of the pixel's padded stratified sequences (core/low_discrepancy.h): over the iterations
    // they cover the pixel, the lens and the lights evenly; the rest is independent random.
    const auto eye_path = [&](int x, int y, uint64_t it, VisiblePoint& vp, RayCounts& rays) {
        const uint64_t pixel = size_t(y) * size_t(ro.width) + size_t(x);
        Sampler sampler(ro.seed, 0x65796570617373ULL, pixel, it);
        const uint64_t key = Sampler(ro.seed, 0x6579657365717563ULL, pixel).next_bits();
        const Vec2 jitter = padded_point2(uint32_t(it), hash_combine(key, 1));
        const Vec2 lens = padded_point2(uint32_t(it), hash_combine(key, 2));
        const Ray ray = P.camera.generate_ray(float(x) + jitter.x, float(y) + jitter.y, lens);
        ++rays.camera;
        const LightSampleSequence lights{uint32_t(it), hash_combine(key, 3)};
        return trace_eye_path(P, ray, sampler, direct_samples, vp, rays, &lights);
    };
    // --trace-pixel: that pixel's eye paths run again, recorded, and its slots' photons.
    PathRecorder* trace = requested_trace();
    const size_t traced =
        trace ? (size_t(trace->y()) * size_t(ro.width) + size_t(trace->x())) * per_pixel : 0;
    acc.record(trace, traced, per_pixel);
    // Pixel = direct sum / iterations + τ / (π R² N_emitted).
    auto resolve_film = [&] {
        resolve(state.slots, int(per_pixel), 1.0, state.iterations > 0 ? 1.0 / double(state.iterations) : 0.0,
                state.photons_emitted, film, ro.layers, volume_slot);
    };

    ProgressiveBudget budget(ro, budget_, state, film, progress);
    while (budget.next()) {
        const uint64_t it = state.iterations;
        // Eye pass: one stochastic camera path per pixel, keyed by (seed, pixel, iteration); its
        // emission and direct light add to the pixel's direct sum.
        tbb::parallel_for(size_t(0), tiles.size(), [&](size_t t) {
            if (!dist::owns(t)) return;  // under MPI: another rank's tile (EyePassExchange)
            const film::Tile& tile = tiles[t];
            RayCounts rays;
            uint64_t dropped = 0;
            for (int y = tile.y0; y < tile.y1; ++y)
                for (int x = tile.x0; x < tile.x1; ++x) {
                    const size_t base = (size_t(y) * size_t(ro.width) + size_t(x)) * per_pixel;
                    VisiblePoint& vp = vps[base];
                    const Rgb L = eye_path(x, y, it, vp, rays);
                    if (per_pixel == 2) {  // the volume slot takes a volume point
                        VisiblePoint& vv = vps[base + 1];
                        vv.bsdf.reset();
                        vv.medium = -1;
                        if (vp.volume()) std::swap(vp, vv);
                    }
                    PixelStats& st = state.slots[base];
                    if (L.is_finite())
                        for (int c = 0; c < 3; ++c) st.direct[c] += double(L[c]);
                    else
                        ++dropped;  // counted for -v, never added
                    for (size_t s = base; s < base + per_pixel; ++s)
                        if (vps[s].present() && state.slots[s].r2 == 0)
                            state.slots[s].r2 = initial.r2(vps[s]);
                }
            P.stats.add_rays(rays);
            P.stats.add_dropped_samples(dropped);
        });
        exchange.share(tiles, ro.width, per_pixel, vps, state.slots);
        const bool is_pilot = it == 0 && pilot.k > 0;
        if (is_pilot)  // the pilot counts photons in the largest allowed disc (see PilotRadius)
            for (size_t i = 0; i < vps.size(); ++i)
                if (vps[i].present()) state.slots[i].r2 *= pilot.max_scale;
        if (trace) {
            record_eye_path(*trace, it, int64_t(it), traced, per_pixel == 2, [&](VisiblePoint& vp) {
                RayCounts uncounted;
                return eye_path(trace->x(), trace->y(), it, vp, uncounted);
            });
            trace->begin_pass(it, is_pilot, [&](size_t s) { return state.slots[s].r2; });
        }

        // Photon pass: photons within each visible point's radius add M_i and Φ_i.
        RayCounts prays;
        prays.photon = acc.photon_pass(P, vps, state.slots, grid, ro.seed, it, photons);
        P.stats.add_rays(prays);

        if (is_pilot) {
            // The pilot: its photons choose the radii, then are dropped (not in N_emitted either);
            // its direct light is kept. A resumed run has it behind it (r2 is in the checkpoint).
            acc.pilot(state.slots, vps, pilot);
            if (opt_.edge_aware_radius) bound_radii_at_edges(vps, state.slots, initial.footprint);
        } else {
            // Update: N ← N + αM, R² ← R² (N + αM)/(N + M), τ ← (τ + βΦ) R²_new/R²_old (eq. 9-11).
            state.photons_emitted += photons;
            acc.update(state.slots, vps, opt_.alpha);
        }
        if (trace) trace->end_pass(state.photons_emitted, [&](size_t s) { return state.slots[s]; });
        budget.after_iteration(resolve_film);
    }
    resolve_film();
    const RenderDone done = budget.finish();
    P.stats.add_value("sppm", std::to_string(state.iterations) + " iterations, " +
                                  std::to_string(state.photons_emitted) + " photons");
    return done;
}

}  // namespace phos::integrators
