// The budget loop's bookkeeping for PPM / SPPM (see progressive_budget.h).
#include "render/progressive_budget.h"

#include <algorithm>

#include "core/interrupt.h"
#include "dist/ranks.h"

namespace phos::render {

using clock = std::chrono::steady_clock;

ProgressiveBudget::ProgressiveBudget(const RenderOptions& ro, const RenderBudget& opt,
                                     ProgressiveState& state, film::Film& film, Progress& progress)
    : settings_(opt.settings),
      watch_(opt.observers),
      state_(state),
      film_(film),
      progress_(progress),
      target_(uint64_t(std::max(1, ro.spp))),
      t0_(opt.settings.clock_start.value_or(clock::now())),
      last_preview_(clock::now()),
      last_checkpoint_(state.iterations) {
    done_.units = state_.iterations;
    done_.target = target_;
    done_.started = state_.iterations > 0;
    const uint64_t left = target_ > state_.iterations ? target_ - state_.iterations : 0;
    progress_started_ = left > 0;  // a resumed render that is already complete shows no progress
    if (!progress_started_) return;
    if (settings_.time > 0)
        progress_.start_timed(state_.integrator, settings_.time, t0_,
                              target_ < kUnboundedIterations ? left : 0);
    else
        progress_.start(state_.integrator, left);
}

void ProgressiveBudget::after_iteration(const std::function<void()>& resolve_film) {
    ++state_.iterations;
    done_.units = state_.iterations;
    done_.started = true;
    progress_.advance();
    if (watch_.on_checkpoint && settings_.checkpoint_every > 0 &&
        state_.iterations % uint64_t(settings_.checkpoint_every) == 0) {
        watch_.on_checkpoint(state_);
        last_checkpoint_ = state_.iterations;
    }
    // The film is resolved at most once per iteration, for the watchers and the preview alike.
    const bool resolved = watch_.on_frame != nullptr;
    if (resolved) {
        resolve_film();
        watch_.on_frame(film_);
    }
    const auto now = clock::now();
    uint8_t time_up =
        settings_.time > 0 && std::chrono::duration<double>(now - t0_).count() >= settings_.time;
    dist::broadcast(&time_up, 1);  // rank 0's clock decides for all
    time_up_ = time_up != 0;
    const bool more = !time_up_ && !interrupt::requested() && state_.iterations < target_;
    if (more && watch_.on_preview && settings_.write_every > 0 &&
        std::chrono::duration<double>(now - last_preview_).count() >= settings_.write_every) {
        if (!resolved) resolve_film();
        watch_.on_preview(film_);
        last_preview_ = clock::now();
    }
}

bool ProgressiveBudget::next() {
    if (dist::any(interrupt::requested())) done_.interrupted = true;
    return !time_up_ && !done_.interrupted && state_.iterations < target_;
}

RenderDone ProgressiveBudget::finish() {
    if (progress_started_) progress_.finish();
    if (watch_.on_checkpoint && last_checkpoint_ != state_.iterations) watch_.on_checkpoint(state_);
    done_.units = state_.iterations;
    return done_;
}

}  // namespace phos::render
