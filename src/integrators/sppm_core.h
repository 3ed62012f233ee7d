// The parts PPM and SPPM share: the eye path to a visible point, the photon pass that splats
// photons into the hit points' integer accumulators, the progressive radius/flux update, the final
// pixel estimate, and the budget loop (iterations, time, previews, checkpoints).
//
// Estimator (Hachisuka & Jensen 2009, eq. 9-12): per hit point i, after an iteration with M_i new
// photons and flux sum Φ_i = Σ f(wo, wi_p) Φ_p,
//   N_{i+1} = N_i + α M_i,   R²_{i+1} = R²_i (N_i + α M_i) / (N_i + M_i),
//   τ_{i+1} = (τ_i + β_i Φ_i) R²_{i+1} / R²_i,
// and the indirect radiance is τ / (π R² N_emitted). Photon powers are flux × (photons emitted in
// a pass), so N_emitted counts every photon emitted over all iterations.
//
// Determinism: Φ_i and M_i are sums in 64-bit fixed point (integer atomics), exact and
// order-independent, so the result is bit-identical for any thread count.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "core/progress.h"
#include "core/rng.h"
#include "film/checkpoint.h"
#include "film/film.h"
#include "integrators/prepared.h"
#include "integrators/progressive_options.h"
#include "photon/hitpoint_grid.h"
#include "shading/bsdf.h"

namespace phos::integrators::sppm {

// Where a camera path met its first non-specular surface (after following specular bounces).
struct VisiblePoint {
    Vec3 p;
    Vec3 wo;
    Rgb beta;       // camera-path throughput (over the path's selection probabilities)
    int depth = 0;  // specular bounces before it (limits photon bounces: total ≤ max_depth)
    float path_length = 0;
    std::optional<shading::Bsdf> bsdf;  // empty: no visible point this iteration
};

// Traces a camera ray: adds emission seen along the specular chain, and at the first non-specular
// hit stores `vp` and adds the average of `direct_samples` light samples. Mixed materials choose
// between their non-specular part (visible point) and specular part (continue) at random, in
// proportion to the lobes' albedos. Returns emission + direct light (throughput included).
Rgb trace_eye_path(const Prepared& P, accel::Ray ray, Sampler& sampler, int direct_samples, VisiblePoint& vp,
                   RayCounts& rays);

// Film footprint model for the automatic initial radius: the camera's (camera.h).
struct PixelFootprint : CameraModel::Footprint {
    explicit PixelFootprint(const Prepared& P) : CameraModel::Footprint(P.camera.pixel_footprint()) {}
};

// The automatic or explicit initial radius of a visible point, before any photon pass: `radius`
// (--radius) when > 0, else `radius_pixels` pixel footprints at the point's path length.
struct InitialRadius {
    float radius;
    float radius_pixels;
    PixelFootprint footprint;
    double r2(const VisiblePoint& vp) const {
        const float r = radius > 0 ? radius : radius_pixels * footprint.at(vp.path_length);
        return double(r) * double(r);
    }
};

// The state a progressive render starts from: a fresh one (`slots_per_pixel` slots per pixel) for
// `integrator`, or the checkpoint being resumed after checking it is the same render. Also
// validates --alpha and records the requested iteration count.
film::ProgressiveState start_state(const Prepared& P, const ProgressiveOptions& opt, const char* integrator,
                                   uint32_t slots_per_pixel);

// Per-pixel initial radius from a pilot photon pass (--radius-photons): the first iteration's
// photons only count how many fall in each visible point's largest allowed disc, R₀² max_scale
// (M_p; R₀ the automatic radius); the point's radius becomes the disc that would hold ~k photons,
// R² = R₀² max_scale clamp(k / M_p) within [min_scale, max_scale] R₀² (M_p = 0: R₀ kept). Counting
// in the largest disc keeps a dim point next to a caustic from choosing a disc that reaches into
// it. The pilot's photons are then discarded (N = τ = 0, not counted in N_emitted): the radius is
// independent of the photons the estimate uses, so choosing it adds no bias of its own (reusing
// them, with a radius picked so they number ~k, inflated sparse caustics by ~20 %). Bright
// caustics get small discs (less blur), dim diffuse regions large ones (less noise).
struct PilotRadius {
    double k = 0;                         // target photons per disc (0 = no pilot)
    double min_scale = 1, max_scale = 1;  // bounds on R²/R₀²
};

// The radius a point keeps after the pilot: r2 is the pilot's gathering disc (R₀² max_scale) and
// m the photons it held.
inline double pilot_r2(const PilotRadius& a, double r2, uint64_t m) {
    if (m == 0) return r2 / a.max_scale;
    return r2 * std::clamp(a.k / double(m), a.min_scale / a.max_scale, 1.0);
}

// What the photon pass reads of a visible point, compact (44 bytes) so the per-photon loop touches
// one cache line per matched point instead of a whole VisiblePoint with its Bsdf.
struct GatherPoint {
    Vec3 ng;               // geometric normal turned to wo's side (zero: no visible point)
    int max_bounces = -1;  // photons that bounced more often would make the path exceed max_depth
    Vec3 ns;               // shading normal turned like ng
    uint32_t lambert = 0;  // 1: the BSDF is one Lambert lobe, f = kd_pi when wi is above ng and ns
    Rgb kd_pi;             // kd / π of a Lambert-only point
};

// Per-hit-point photon statistics of one iteration, summed in 64-bit fixed point: per-thread
// arrays reduced in update() (no atomics in the photon loop), or integer atomics when per-thread
// copies would take too much memory. Integer sums are exact, so both are order-independent.
class PhotonAccumulator {
public:
    explicit PhotonAccumulator(size_t slots);
    ~PhotonAccumulator();
    // Traces photons [0, count) of pass `pass` on all cores, adding f(wo, wi) × power to each hit
    // point within its radius (photons straight from a light excluded: direct light is computed by
    // shadow rays). Returns the number of photon rays traced.
    uint64_t photon_pass(const Prepared& P, const std::vector<VisiblePoint>& vps,
                         const photon::HitPointGrid& grid, uint64_t seed, uint64_t pass, uint64_t count);
    // Applies the progressive update to `stats` (one per visible point) and clears the sums.
    void update(std::vector<film::SlotStats>& stats, const std::vector<VisiblePoint>& vps, float alpha);
    // The pilot pass instead of update(): sets each visible point's r2 (the pilot's gathering disc)
    // by pilot_r2 from the photon count alone and clears the sums; N and τ stay 0 (see PilotRadius).
    void pilot(std::vector<film::SlotStats>& stats, const std::vector<VisiblePoint>& vps,
               const PilotRadius& a);

private:
    template <class F>
    void drain(F&& f);  // defined in sppm_core.cpp, its only user
    struct Slot {
        std::atomic<int64_t> phi[3];
        std::atomic<uint64_t> m;
    };
    struct LocalSlot {
        int64_t phi[3] = {0, 0, 0};
        uint64_t m = 0;
    };
    struct Locals;  // per-thread LocalSlot arrays (tbb::enumerable_thread_specific)
    std::unique_ptr<Slot[]> slots_;
    std::unique_ptr<Locals> locals_;  // null: atomics
    std::vector<GatherPoint> gather_;
    size_t count_;
    double scale_ = 1;  // fixed-point units per unit of flux contribution
};

// Builds the grid over the visible points with their current radii.
void build_grid(photon::HitPointGrid& grid, const std::vector<VisiblePoint>& vps,
                const std::vector<film::SlotStats>& stats);

// Final radiance of each pixel: mean over its `slots_per_pixel` slots of
// direct × direct_scale + τ / (π R² N_emitted).
void resolve(const std::vector<film::SlotStats>& stats, int slots_per_pixel, double direct_scale,
             uint64_t photons_emitted, film::Film& film);

// Runs iterations state.iterations+1 ... until P.options.spp are done or `opt.time` has passed,
// calling iterate(i) for iteration i (0-based), resolve_fn(film) for previews and at the end, and
// the checkpoint hook every opt.checkpoint_every iterations and at the end.
void run_loop(const Prepared& P, const ProgressiveOptions& opt, film::ProgressiveState& state,
              film::Film& film, Progress& progress, const std::function<void(uint64_t)>& iterate,
              const std::function<void(film::Film&)>& resolve_fn);

}  // namespace phos::integrators::sppm
