// Options of the progressive photon-mapping integrators (--integrator ppm | sppm): the struct they
// read and its option table (progressive_options.cpp: flags, defaults, ranges, help, pbrt sppm
// parameters); documented in docs/progressive.md and docs/options.md. Budgets and checkpoints,
// shared by every integrator, are in render_budget.h.
#pragma once

#include <cstdint>

#include "core/option_table.h"

namespace phos::integrators {

// The strategies vcm uses (--vcm-mode): connections only (Bpt), merging only (Ppm), both (Vcm),
// light tracing alone (Lt).
enum class VcmMode { Bpt, Ppm, Vcm, Lt };
// Where vcm's camera subpaths merge (--vcm-merge): at their first non-delta vertex, or at every one.
enum class VcmMerge { First, Every };

struct ProgressiveOptions {
    float alpha = 0.7f;                  // fraction of new photons kept per iteration (radius reduction)
    uint64_t photons_per_iter = 200000;  // photons traced per iteration
    float radius = 0;                    // initial radius in scene units; 0 = automatic (pixel footprint)
    float radius_pixels = 4;             // automatic radius in pixel footprints at the hit distance
    double radius_photons = 64;          // sppm: photons a pixel's disc should hold, from a pilot photon
                                         // pass (per-pixel radius from density); 0 = off
    bool edge_aware_radius = true;       // sppm: bound the pilot's radii at geometric edges
    int direct_samples = 0;              // light samples per visible point per eye pass; 0 = the
                                         // integrator's own (direct_samples_for)
    int eye_samples = 1;                 // ppm: hit points per pixel (jittered inside the pixel)
    VcmMode vcm_mode = VcmMode::Vcm;     // vcm: the strategies used
    int vcm_camera_samples = 2;          // vcm: camera samples per pixel per iteration (first-vertex merging)
    float vcm_continue = 0;              // vcm: probability a camera subpath goes on past a Lambert x_f
    int vcm_light_paths = 0;             // vcm: light subpaths per pixel per iteration for merging
                                         // (0 = automatic, vcm_pilot.cpp light_paths_per_pixel)
    VcmMerge vcm_merge = VcmMerge::First;  // vcm: merge at the camera's first non-delta vertex or every one
    float vcm_rr_weight = 0.1f;            // bdpt, vcm: Russian roulette on shadow rays of strategies whose
                                           // MIS weight is below this (0 = off)
    float direct_mis_scale = 8;            // bdpt, vcm: the MIS weights count the light samples at the
                                           // first non-delta vertex this many times over

    // The iteration count (--iterations, the same as --spp; 0 = not given: the app copies it to
    // RenderOptions::spp). Time budgets, previews and checkpoints are in RenderBudget.
    int iterations = 0;
};

// Light samples per visible point: --direct-samples, else 2 per iteration for sppm, 16 once for
// ppm (it computes direct light only once). SPPM's light samples are stratified over the
// iterations (sppm.cpp), so its direct light converges faster than the photon estimate: at the
// bench budgets 2 samples gave lower error than 4 on all three bench scenes (cornell-diffuse
// 0.00039 against 0.00040, cornell-glass-mirror 0.00075 against 0.00078, caustic-point 0.00132
// against 0.00142), the time going to more iterations.
inline int direct_samples_for(const ProgressiveOptions& o, bool ppm) {
    return o.direct_samples > 0 ? o.direct_samples : ppm ? 16 : 2;
}
// bdpt and vcm: light samples at the camera subpath's first non-delta vertex per iteration
// (deeper vertices take one), stratified over the iterations like SPPM's (camera_subpath.cpp).
inline int bidirectional_direct_samples(const ProgressiveOptions& o) {
    return o.direct_samples > 0 ? o.direct_samples : 2;
}

// The "Progressive photon mapping" option table over ProgressiveOptions.
const options::Table& progressive_options();

}  // namespace phos::integrators
