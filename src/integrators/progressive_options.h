// Options of the progressive photon-mapping integrators (--integrator ppm | sppm): the struct they
// read and its option table (progressive_options.cpp: flags, defaults, ranges, help, pbrt sppm
// parameters); documented in docs/progressive.md and docs/options.md. The hooks let the caller
// (app/lib/render_command.cpp) write previews and checkpoints and resume without the integrator
// knowing about files.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "core/option_table.h"
#include "film/film.h"
#include "integrators/progressive_checkpoint.h"

namespace phos::integrators {

struct ProgressiveOptions {
    float alpha = 0.7f;                  // fraction of new photons kept per iteration (radius reduction)
    uint64_t photons_per_iter = 200000;  // photons traced per iteration
    float radius = 0;                    // initial radius in scene units; 0 = automatic (pixel footprint)
    float radius_pixels = 4;             // automatic radius in pixel footprints at the hit distance
    double radius_photons = 64;          // sppm: photons a pixel's disc should hold, from a pilot photon
                                         // pass (per-pixel radius from density); 0 = off
    int direct_samples = 0;              // light samples per visible point per eye pass; 0 = the
                                         // integrator's own (direct_samples_for)
    int eye_samples = 1;                 // ppm: hit points per pixel (jittered inside the pixel)

    // Budgets: iterations come from RenderOptions::spp; `time` (seconds, 0 = none) stops at the end
    // of the iteration that crosses it.
    double time = 0;
    // When the time budget started (default: when rendering starts); the app sets it to its own
    // start so --time bounds the whole command.
    std::optional<std::chrono::steady_clock::time_point> clock_start;
    double write_every = 0;       // seconds between preview writes (0 = none)
    int checkpoint_every = 8;     // iterations between checkpoint saves (when a hook is set)
    int iterations = 0;           // --iterations (0 = not given; the app copies it to spp)
    std::string checkpoint_path;  // --checkpoint FILE (the app installs on_checkpoint)
    std::string resume_path;      // --resume FILE (the app loads it into `resume`)

    // Hooks (set by the application, not the CLI parser).
    std::function<void(const film::Film& film)> on_preview;            // every write_every seconds
    std::function<void(const ProgressiveState& state)> on_checkpoint;  // every checkpoint_every
    std::shared_ptr<const ProgressiveState> resume;                    // state to continue from
    // Filled by the application: the render's identity stored in checkpoints (scene hash...).
    // The app fills identity.options (the image-changing options by flag and value); the
    // integrator sets identity.options_hash from it.
    ProgressiveState identity;
    // Out: the number of iterations actually completed (for -v and tests).
    std::shared_ptr<uint64_t> iterations_done = std::make_shared<uint64_t>(0);
};

// Light samples per visible point: --direct-samples, else 4 per iteration for sppm (one leaves
// the direct light's noise dominant on area-lit scenes; 4 cost ~10 % more time per iteration and
// cut cornell-diffuse's relMSE at 60 iterations from 0.00095 to 0.00074), 16 once for ppm (it
// computes direct light only once).
inline int direct_samples_for(const ProgressiveOptions& o, bool ppm) {
    return o.direct_samples > 0 ? o.direct_samples : ppm ? 16 : 4;
}

// The "Progressive photon mapping" option table over ProgressiveOptions.
const options::Table& progressive_options();

}  // namespace phos::integrators
