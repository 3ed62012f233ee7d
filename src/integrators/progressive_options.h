// Options of the progressive photon-mapping integrators (--integrator ppm | sppm). Filled by the
// CLI (app/lib/progressive_cli.cpp); documented in docs/progressive.md. The hooks let the caller
// (app/lib/render_command.cpp) write previews and checkpoints and resume without the integrator
// knowing about files.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "film/checkpoint.h"
#include "film/film.h"

namespace phos::integrators {

struct ProgressiveOptions {
    float alpha = 0.7f;             // fraction of new photons kept per iteration (radius reduction)
    uint64_t photons_per_iter = 0;  // 0 = default (kDefaultPhotonsPerIter)
    float radius = 0;               // initial radius in scene units; 0 = automatic (pixel footprint)
    float radius_pixels = 0;        // automatic radius in pixel footprints; 0 = default
    double radius_photons = -1;     // sppm: photons a pixel's disc should hold, from a pilot photon
                                    // pass (per-pixel radius from density); 0 = off, < 0 = default
    int direct_samples = 0;         // light samples per visible point per eye pass; 0 = default
                                    // (sppm 4 per iteration, ppm 16 once)
    int eye_samples = 1;            // ppm: hit points per pixel (jittered inside the pixel)

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
    std::function<void(const film::Film& film)> on_preview;                  // every write_every seconds
    std::function<void(const film::ProgressiveState& state)> on_checkpoint;  // every checkpoint_every
    std::shared_ptr<const film::ProgressiveState> resume;                    // state to continue from
    // Filled by the application: the render's identity stored in checkpoints (scene hash...).
    film::ProgressiveState identity;
    // Out: the number of iterations actually completed (for -v and tests).
    std::shared_ptr<uint64_t> iterations_done = std::make_shared<uint64_t>(0);
};

constexpr uint64_t kDefaultPhotonsPerIter = 200000;

inline uint64_t photons_per_iteration(const ProgressiveOptions& o) {
    return o.photons_per_iter > 0 ? o.photons_per_iter : kDefaultPhotonsPerIter;
}

}  // namespace phos::integrators
