// SPPM's orchestration, one screen (Hachisuka & Jensen 2009): per iteration an eye pass
// (visible points, direct light), the hit-point grid, a photon pass, and the per-pixel update of N,
// R², τ (eq. 9-11, sppm_pixel_stats.h); the pixel value is eq. 12 plus the direct-light average.
// The first iteration is a pilot with --radius-photons (pilot_radius.h).
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

namespace {

using sppm::PixelStats;

// The pilot's rule (pilot_radius.h) for --radius-photons: none with an explicit --radius, which is
// kept; else its bounds in pixel footprints as bounds on R²/R₀².
PilotRadius pilot_for(const ProgressiveOptions& o) {
    PilotRadius pilot;
    if (o.radius <= 0) {
        pilot.k = o.radius_photons;
        const double lo = kPilotRadiusMinPixels / o.radius_pixels,
                     hi = kPilotRadiusMaxPixels / o.radius_pixels;
        pilot.min_scale = std::min(1.0, lo * lo);
        pilot.max_scale = std::max(1.0, hi * hi);
    }
    return pilot;
}

// Pixel (x, y)'s eye path of iteration `it`, keyed by (seed, pixel, iteration). Its position in the
// pixel, on the lens, its wavelengths and its light samples are points `it` (`it` × direct_samples
// + k) of the pixel's padded stratified sequences (core/low_discrepancy.h): over the iterations they
// cover the pixel, the lens, the spectrum and the lights evenly; the rest is independent random.
Rgb pixel_eye_path(const Prepared& P, int x, int y, uint64_t it, int direct_samples, VisiblePoint& vp,
                   RayCounts& rays) {
    const RenderOptions& ro = P.options;
    const uint64_t pixel = size_t(y) * size_t(ro.width) + size_t(x);
    Sampler sampler(ro.seed, 0x65796570617373ULL, pixel, it);
    const uint64_t key = Sampler(ro.seed, 0x6579657365717563ULL, pixel).next_bits();
    const PixelFilterSampler::FilmSample at =
        P.filter.sample(padded_point2(uint32_t(it), hash_combine(key, 1)));
    const Vec2 lens = padded_point2(uint32_t(it), hash_combine(key, 2));
    float camera_weight = 1;
    const Ray ray =
        P.camera.generate_ray(float(x) + at.position.x, float(y) + at.position.y, lens, camera_weight);
    ++rays.camera;
    if (camera_weight == 0) {  // the camera's lenses blocked the ray: no visible point, black
        vp.bsdf.reset();
        vp.medium = -1;
        return Rgb(0.0f);
    }
    const PixelSequences sequences{uint32_t(it), hash_combine(key, 3)};
    const Rgb L = trace_eye_path(P, ray, sampler, direct_samples, vp, rays, &sequences);
    const float weight = at.weight * camera_weight;
    if (weight == 1) return L;
    vp.beta *= weight;  // the photons this visible point gathers count with the sample's weight
    return L * weight;
}

// The eye pass of iteration `it`: one stochastic camera path per pixel of this rank's
// tiles; its emission and direct light add to the pixel's direct sum, its visible point replaces
// the last iteration's (with media, a volume point goes to the pixel's second slot), and a slot's
// first visible point takes the initial radius.
void eye_pass(const Prepared& P, const std::vector<film::Tile>& tiles, uint64_t it, int direct_samples,
              size_t per_pixel, const sppm::InitialRadius& initial, std::vector<VisiblePoint>& vps,
              std::vector<PixelStats>& slots) {
    const RenderOptions& ro = P.options;
    tbb::parallel_for(size_t(0), tiles.size(), [&](size_t t) {
        if (!dist::owns(t)) return;  // under MPI: another rank's tile (EyePassExchange)
        const film::Tile& tile = tiles[t];
        RayCounts rays;
        uint64_t dropped = 0;
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) {
                const size_t base = (size_t(y) * size_t(ro.width) + size_t(x)) * per_pixel;
                VisiblePoint& vp = vps[base];
                const Rgb L = pixel_eye_path(P, x, y, it, direct_samples, vp, rays);
                if (per_pixel == 2) {  // the volume slot takes a volume point
                    VisiblePoint& vv = vps[base + 1];
                    vv.bsdf.reset();
                    vv.medium = -1;
                    if (vp.volume()) std::swap(vp, vv);
                }
                PixelStats& st = slots[base];
                if (L.is_finite())
                    for (int c = 0; c < 3; ++c) st.direct[c] += double(L[c]);
                else
                    ++dropped;  // counted for -v, never added
                for (size_t s = base; s < base + per_pixel; ++s)
                    if (vps[s].present() && slots[s].r2 == 0) slots[s].r2 = initial.r2(vps[s]);
            }
        P.stats.add_rays(rays);
        P.stats.add_dropped_samples(dropped);
    });
}

}  // namespace

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
    const int direct_samples = direct_samples_for(opt_, false);
    const InitialRadius initial{opt_.radius, opt_.radius_pixels, P.camera.pixel_footprint()};
    const PilotRadius pilot = pilot_for(opt_);
    std::vector<VisiblePoint> vps(pixels * per_pixel);
    PhotonAccumulator acc(pixels * per_pixel);
    photon::HitPointGrid grid;
    const auto tiles = film::make_tiles(ro.width, ro.height);
    EyePassExchange exchange;  // under MPI: the ranks' eye passes
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
        eye_pass(P, tiles, it, direct_samples, per_pixel, initial, vps, state.slots);
        exchange.share(P.scene, tiles, ro.width, per_pixel, vps, state.slots);
        const bool is_pilot = it == 0 && pilot.k > 0;
        if (is_pilot)  // the pilot counts photons in the largest allowed disc (see PilotRadius)
            for (size_t i = 0; i < vps.size(); ++i)
                if (vps[i].present()) state.slots[i].r2 *= pilot.max_scale;
        if (trace) {
            record_eye_path(*trace, it, int64_t(it), traced, per_pixel == 2, [&](VisiblePoint& vp) {
                RayCounts uncounted;
                return pixel_eye_path(P, trace->x(), trace->y(), it, direct_samples, vp, uncounted);
            });
            trace->begin_pass(it, is_pilot, [&](size_t s) { return state.slots[s].r2; });
        }
        // Photon pass and update (eq. 9-11). The pilot: its photons choose the radii, then are
        // dropped (not in N_emitted either); its direct light is kept. A resumed run has it behind
        // it (r2 is in the checkpoint).
        photon_iteration(P, acc, vps, state, grid, it, opt_.photons_per_iter, opt_.alpha,
                         is_pilot ? &pilot : nullptr);
        if (is_pilot && opt_.edge_aware_radius) bound_radii_at_edges(vps, state.slots, initial.footprint);
        end_iteration(trace, state, budget, resolve_film);
    }
    return finish_progressive(P, "sppm", state, budget, resolve_film);
}

}  // namespace phos::integrators
