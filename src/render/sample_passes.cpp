// The pass bookkeeping of sample-based renders (see sample_passes.h).
#include "render/sample_passes.h"

#include <algorithm>

#include "core/error.h"
#include "core/interrupt.h"
#include "dist/ranks.h"

namespace phos::render {

using clock = std::chrono::steady_clock;

namespace {

constexpr uint64_t kMaxSamples = 0xffffffffu;  // per pixel (tile counts are 32-bit)

double seconds(clock::time_point a, clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

// The film layers a checkpoint of `film` holds: "" (the image), then the layers by name.
std::vector<std::string> film_layer_names(const film::Film& film) {
    std::vector<std::string> names{""};
    for (const std::string& n : film.layer_names()) names.push_back(n);
    return names;
}

}  // namespace

SamplePasses::SamplePasses(const Prepared& P, film::Film& film, const RenderBudget& budget,
                           const std::string& integrator, Progress& progress,
                           std::function<void(std::string& payload)> payload)
    : P_(P),
      film_(film),
      settings_(budget.settings),
      watch_(budget.observers),
      progress_(progress),
      payload_(std::move(payload)),
      tiles_(film::make_tiles(P.options.width, P.options.height)),
      t0_(budget.settings.clock_start.value_or(clock::now())),
      last_preview_(clock::now()) {
    const RenderOptions& ro = P.options;
    const uint64_t spp = uint64_t(std::max(1, ro.spp));
    target_ = spp >= kUnboundedIterations
                  ? kMaxSamples
                  : std::min(kMaxSamples, spp * uint64_t(std::max(1, ro.dof_samples)));
    state_ = start_state(ro, budget, integrator, 0, "samples per pixel", target_);
    if (budget.observers.resume) {
        const std::string what = "checkpoint '" + budget.settings.resume_path + "'";
        if (state_.tile_samples.size() != tiles_.size())
            throw InputError(what + ": its tile count does not match the image (" +
                             std::to_string(state_.tile_samples.size()) + ", now " +
                             std::to_string(tiles_.size()) + ")");
        std::vector<std::string> saved;
        for (const auto& [name, sums] : state_.film) saved.push_back(name);
        if (saved != film_layer_names(film_))
            throw InputError(what + ": it holds other image layers than this render writes");
        for (const auto& [name, sums] : state_.film) {
            film::Layer& layer = name.empty() ? film_.main() : film_.layer(name);
            if (sums.size() != size_t(layer.width()) * size_t(layer.height()) * 4)
                throw InputError(what + ": layer size does not match the image");
            layer.set_sums(sums, name.empty() ? state_.rejected_samples : 0);
        }
        state_.film.clear();
        state_.payload.clear();
    } else {
        state_.tile_samples.assign(tiles_.size(), 0);
    }
    gather_.start(film_);
    last_checkpoint_ = state_.iterations = min_done();
    checkpoint_samples_ = taken();
    done_.target = target_;
    done_.units = state_.iterations;
    done_.started = budget.observers.resume != nullptr;

    uint64_t left = 0;  // pixel samples still to take
    for (size_t t = 0; t < tiles_.size(); ++t)
        left += uint64_t(tiles_[t].pixel_count()) *
                (target_ - std::min<uint64_t>(target_, state_.tile_samples[t]));
    progress_started_ = left > 0;
    timed_ = budget.settings.time > 0;
    if (!progress_started_) return;
    if (timed_)
        progress_.start_timed(integrator, budget.settings.time, t0_,
                              spp < kUnboundedIterations ? target_ - state_.iterations : 0,
                              "samples per pixel");
    else
        progress_.start(integrator, left);
}

uint32_t SamplePasses::min_done() const {
    uint32_t m = uint32_t(kMaxSamples);
    for (uint32_t s : state_.tile_samples) m = std::min(m, s);
    return tiles_.empty() ? uint32_t(target_) : m;
}

bool SamplePasses::next() {
    // Collective: an interrupt on any rank stops every rank.
    if (dist::any(interrupt::requested())) done_.interrupted = true;
    if (time_up_ || done_.interrupted || min_done() >= target_) return false;
    pass_end_ = uint32_t(std::min<uint64_t>(target_, uint64_t(min_done()) + pass_));
    pass_start_ = clock::now();
    return true;
}

std::pair<uint32_t, uint32_t> SamplePasses::range(size_t t) const {
    const uint32_t first = state_.tile_samples[t];
    if (!dist::owns(t)) return {first, first};  // another rank's tile
    return {first, std::max(first, pass_end_)};
}

bool SamplePasses::stopped() const { return interrupt::requested(); }

void SamplePasses::tile_done(size_t t, const RayCounts& rays) {
    if (!dist::owns(t)) return;
    const auto [first, last] = range(t);
    state_.tile_samples[t] = last;
    P_.stats.add_rays(rays);
    if (watch_.on_tile) watch_.on_tile(film_, tiles_[t]);
    if (!timed_) progress_.advance(uint64_t(tiles_[t].pixel_count()) * (last - first));
}

void SamplePasses::after_pass() {
    const auto now = clock::now();
    if (dist::distributed()) {  // every rank learns the counts of the other ranks' tiles
        const std::vector<uint32_t> mine = state_.tile_samples;
        dist::max(state_.tile_samples.data(), state_.tile_samples.size());
        uint64_t others = 0;
        for (size_t t = 0; t < tiles_.size(); ++t)
            others += uint64_t(tiles_[t].pixel_count()) * (state_.tile_samples[t] - mine[t]);
        if (!timed_ && progress_started_) progress_.advance(others);
    }
    const uint32_t before = uint32_t(state_.iterations);
    state_.iterations = min_done();
    done_.started = true;
    done_.units = state_.iterations;
    if (timed_) progress_.advance(state_.iterations - before);
    // What to do now, decided by rank 0 (its clock, its outputs) and followed by every rank.
    struct Decision {
        uint8_t frame = 0, checkpoint = 0, preview = 0, time_up = 0;
        uint32_t pass = 1;
    } d;
    d.frame = watch_.on_frame != nullptr;
    d.checkpoint = watch_.on_checkpoint && settings_.checkpoint_every > 0 &&
                   state_.iterations >= last_checkpoint_ + uint64_t(settings_.checkpoint_every) && !stopped();
    d.time_up = settings_.time > 0 && seconds(t0_, now) >= settings_.time;
    const bool more = !d.time_up && !stopped() && state_.iterations < target_;
    d.preview = more && watch_.on_preview && settings_.write_every > 0 &&
                seconds(last_preview_, now) >= settings_.write_every;
    // Passes of about half a second: often enough for --time and previews, long enough that the
    // wait for a pass's last tiles costs nothing.
    const double took = seconds(pass_start_, now);
    d.pass = pass_;
    if (took < 0.25)
        d.pass = std::min<uint32_t>(pass_ * 2, 1u << 16);
    else if (took > 1.0 && pass_ > 1)
        d.pass = pass_ / 2;
    dist::broadcast(&d, sizeof d);
    time_up_ = d.time_up;
    pass_ = d.pass;
    if (d.frame || d.checkpoint || d.preview) gather_.gather(film_);
    if (d.frame && watch_.on_frame) watch_.on_frame(film_);
    if (d.checkpoint) save_checkpoint();
    if (d.preview) {
        if (watch_.on_preview) watch_.on_preview(film_);
        last_preview_ = clock::now();
    }
}

void SamplePasses::save_checkpoint() {
    state_.iterations = min_done();
    if (watch_.on_checkpoint) {  // rank 0 (the other ranks only keep count)
        state_.rejected_samples = film_.main().rejected();
        state_.film.clear();
        state_.film.emplace_back("", film_.main().sums());
        for (const std::string& name : film_.layer_names())
            state_.film.emplace_back(name, film_.layer(name).sums());
        if (payload_) payload_(state_.payload);
        watch_.on_checkpoint(state_);
        state_.film.clear();
        state_.film.shrink_to_fit();
        std::string().swap(state_.payload);
    }
    last_checkpoint_ = state_.iterations;
    checkpoint_samples_ = taken();
}

uint64_t SamplePasses::taken() const {
    uint64_t n = 0;
    for (size_t t = 0; t < tiles_.size(); ++t)
        n += uint64_t(tiles_[t].pixel_count()) * state_.tile_samples[t];
    return n;
}

RenderDone SamplePasses::finish() {
    if (progress_started_) progress_.finish();
    state_.iterations = min_done();
    const uint64_t samples = taken();
    gather_.gather(film_);  // rank 0 holds the whole image
    if (watch_.on_checkpoint && samples != checkpoint_samples_) save_checkpoint();
    done_.units = state_.iterations;
    done_.samples = samples;
    done_.started = samples > 0;
    return done_;
}

}  // namespace phos::render
