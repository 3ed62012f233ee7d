// The budget of a progressive render (PPM / SPPM), so that each integrator's loop stays visible:
//
//     ProgressiveBudget budget(P.options, budget_options, state, film, progress);
//     while (budget.next()) {
//         ... eye pass, photon pass, update of state.slots ...
//         budget.after_iteration(resolve_film);
//     }
//     resolve_film();
//     budget.finish();
//
// It owns the iteration count (state.iterations), the time budget (--time, counted from the
// command's start), interrupts (the loop ends after the current iteration), checkpoints every
// --checkpoint-every iterations and at the end, previews every --write-every seconds, the progress
// display, and what the render completed (RenderDone).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>

#include "core/progress.h"
#include "film/film.h"
#include "render/options.h"
#include "render/progressive_checkpoint.h"
#include "render/render_budget.h"

namespace phos::render {

class ProgressiveBudget {
public:
    // Starts the progress display; the target is ro.spp iterations (at least 1) and opt.settings.time
    // seconds (0 = none).
    ProgressiveBudget(const RenderOptions& ro, const RenderBudget& opt, ProgressiveState& state,
                      film::Film& film, Progress& progress);

    // Whether to run another iteration: fewer than the target are done, the time budget (when
    // there is one) was not crossed by the last iteration and no interrupt came. Iteration numbers
    // are state.iterations. Under MPI it is collective: an interrupt on any rank stops every rank,
    // and rank 0's clock decides the time budget (every rank holds the same state; rank 0 alone
    // writes checkpoints and previews).
    bool next();

    // Counts the iteration just run, saves a checkpoint every checkpoint_every iterations, checks
    // the clock, and writes a preview when one is due and the render goes on: `resolve_film()`
    // must then fill the film from the state.
    void after_iteration(const std::function<void()>& resolve_film);

    // Ends the render (call after resolving the final image): the progress line, a checkpoint of
    // the final state unless the last iteration's was saved; returns what the render completed.
    RenderDone finish();

    uint64_t target() const { return target_; }

private:
    const BudgetSettings& settings_;
    const RenderObservers& watch_;
    ProgressiveState& state_;
    film::Film& film_;
    Progress& progress_;
    uint64_t target_;
    std::chrono::steady_clock::time_point t0_, last_preview_;
    uint64_t last_checkpoint_;
    RenderDone done_;
    bool time_up_ = false;
    bool progress_started_ = false;
};

}  // namespace phos::render
