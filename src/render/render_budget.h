// How much work a render does and how it is kept: the time budget, previews written while it
// runs, checkpoints and resuming, for every integrator (iterations for ppm / sppm, samples per
// pixel for the others): the settings its option table "Budgets and checkpoints" (render_budget.cpp)
// fills, the observers through which the caller (app/lib/render_command.cpp) writes previews and
// checkpoints without the integrators knowing about files, and what the render completed. Interrupts
// (core/interrupt.h) end a render through the same path as a crossed time budget: the work so far is
// resolved, checkpointed and written.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "core/option_table.h"
#include "film/film.h"
#include "film/tiles.h"
#include "render/options.h"
#include "render/progressive_checkpoint.h"

namespace phos::render {

// Sample / iteration counts from here up mean "no count given" (the app's sentinel for a --time
// budget alone): progress then shows time, not a count.
constexpr uint64_t kUnboundedIterations = uint64_t(1) << 30;

// What the "Budgets and checkpoints" option table fills (render_budget.cpp).
struct BudgetSettings {
    // Seconds of wall time (0 = none): stop at the end of the iteration or sample pass that crosses
    // it. Counted from `clock_start` (the app sets it to the command's start, so loading counts).
    double time = 0;
    std::optional<std::chrono::steady_clock::time_point> clock_start;
    double write_every = 0;       // seconds between preview writes (0 = none)
    int checkpoint_every = 8;     // iterations (ppm, sppm) or samples per pixel (others) between saves
    std::string checkpoint_path;  // --checkpoint FILE (the app installs on_checkpoint)
    std::string resume_path;      // --resume FILE (the app loads it into `resume`)
};

// What the application installs to keep and watch a render (none of it is an option).
struct RenderObservers {
    std::function<void(const film::Film& film)> on_preview;            // every write_every seconds
    std::function<void(const ProgressiveState& state)> on_checkpoint;  // every checkpoint_every
    std::shared_ptr<const ProgressiveState> resume;                    // state to continue from
    // Watchers of the image as it converges (--preview, --tev). `on_tile` runs on a rendering
    // thread when a tile has taken its samples of a pass (nothing writes the tile meanwhile: copy
    // its pixels and return); `on_frame` after each pass or iteration with the whole film.
    std::function<void(const film::Film& film, const film::Tile& tile)> on_tile;
    std::function<void(const film::Film& film)> on_frame;
    // The render's identity stored in checkpoints: the app fills the scene hash, the image-changing
    // options by flag and value and the command line; the integrator sets the rest.
    ProgressiveState identity;
};

// What every integrator renders within besides its own options: the settings and the observers.
struct RenderBudget {
    BudgetSettings settings;
    RenderObservers observers;
};

// What a render completed (Integrator::render returns it; for -v, messages and tests):
// iterations (ppm, sppm) or the samples per pixel every pixel received (others), and whether it
// stopped on an interrupt.
struct RenderDone {
    uint64_t units = 0;        // iterations, or samples per pixel in every pixel
    uint64_t target = 0;       // what was asked (kUnboundedIterations and up: a time budget)
    uint64_t samples = 0;      // pixel samples taken in all (sample-based integrators)
    bool interrupted = false;  // stopped early by an interrupt
    bool started = false;      // at least one iteration or sample pass ran or was resumed
};

// The "Budgets and checkpoints" option table over BudgetSettings.
const options::Table& budget_options();

// The identity of this render as a checkpoint records it (integrator, size, seed, options...), to
// compare with a checkpoint before trusting anything in it (check_resumable).
ProgressiveState render_identity(const RenderOptions& ro, const RenderBudget& budget,
                                 const std::string& integrator, uint32_t slots_per_pixel);

// The state a render starts from: a fresh one for `integrator` (`slots_per_pixel` progressive
// statistics per pixel; 0 for the sample-based integrators, whose film the caller adds), or the
// checkpoint being resumed after checking it is the same render (saying what is resumed; a warning
// when it already holds more than asked). Records the requested count `target` and the options
// hash. `unit` names the count in messages ("iterations", "samples per pixel").
ProgressiveState start_state(const RenderOptions& ro, const RenderBudget& budget,
                             const std::string& integrator, uint32_t slots_per_pixel, const std::string& unit,
                             uint64_t target);

}  // namespace phos::render
