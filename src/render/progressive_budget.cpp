// The budget loop's bookkeeping for PPM / SPPM (see progressive_budget.h).
#include "render/progressive_budget.h"

#include <algorithm>

#include "core/interrupt.h"
#include "dist/ranks.h"

namespace phos::render {

using clock = std::chrono::steady_clock;

ProgressiveBudget::ProgressiveBudget(const RenderOptions& ro, const RenderBudget& opt,
                                     ProgressiveState& state, film::Film& film, Progress& progress)
    : opt_(opt),
      state_(state),
      film_(film),
      progress_(progress),
      target_(uint64_t(std::max(1, ro.spp))),
      t0_(opt.clock_start.value_or(clock::now())),
      last_preview_(clock::now()),
      last_checkpoint_(state.iterations) {
    opt_.done->units = state_.iterations;
    opt_.done->target = target_;
    opt_.done->started = state_.iterations > 0;
    const uint64_t left = target_ > state_.iterations ? target_ - state_.iterations : 0;
    progress_started_ = left > 0;  // a resumed render that is already complete shows no progress
    if (!progress_started_) return;
    if (opt_.time > 0)
        progress_.start_timed(state_.integrator, opt_.time, t0_, target_ < kUnboundedIterations ? left : 0);
    else
        progress_.start(state_.integrator, left);
}

void ProgressiveBudget::after_iteration(const std::function<void()>& resolve_film) {
    ++state_.iterations;
    opt_.done->units = state_.iterations;
    opt_.done->started = true;
    progress_.advance();
    if (opt_.on_checkpoint && opt_.checkpoint_every > 0 &&
        state_.iterations % uint64_t(opt_.checkpoint_every) == 0) {
        opt_.on_checkpoint(state_);
        last_checkpoint_ = state_.iterations;
    }
    // The film is resolved at most once per iteration, for the watchers and the preview alike.
    const bool resolved = opt_.on_frame != nullptr;
    if (resolved) {
        resolve_film();
        opt_.on_frame(film_);
    }
    const auto now = clock::now();
    uint8_t time_up = opt_.time > 0 && std::chrono::duration<double>(now - t0_).count() >= opt_.time;
    dist::broadcast(&time_up, 1);  // rank 0's clock decides for all
    time_up_ = time_up != 0;
    const bool more = !time_up_ && !interrupt::requested() && state_.iterations < target_;
    if (more && opt_.on_preview && opt_.write_every > 0 &&
        std::chrono::duration<double>(now - last_preview_).count() >= opt_.write_every) {
        if (!resolved) resolve_film();
        opt_.on_preview(film_);
        last_preview_ = clock::now();
    }
}

bool ProgressiveBudget::next() {
    if (dist::any(interrupt::requested())) opt_.done->interrupted = true;
    return !time_up_ && !opt_.done->interrupted && state_.iterations < target_;
}

void ProgressiveBudget::finish() {
    if (progress_started_) progress_.finish();
    if (opt_.on_checkpoint && last_checkpoint_ != state_.iterations) opt_.on_checkpoint(state_);
    opt_.done->units = state_.iterations;
}

}  // namespace phos::render
