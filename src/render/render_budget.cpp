// The option table of render budgets, previews and checkpoints (see render_budget.h).
#include "render/render_budget.h"

#include <algorithm>
#include <cstdio>

#include "core/format.h"
#include "core/log.h"

namespace phos::render {

namespace {

// "2.40e6": a photon count for a message.
std::string photons_text(uint64_t n) {
    std::string s = printf_string("%.2e", double(n));
    const size_t e = s.find('e');
    size_t digits = e + 1;
    if (s[digits] == '+')
        s.erase(digits, 1);
    else if (s[digits] == '-')
        ++digits;
    while (s.size() > digits + 1 && s[digits] == '0') s.erase(digits, 1);
    return s;
}

}  // namespace

using options::at_least;
using options::between;
using options::Effect;

const options::Table& budget_options() {
    static const options::Table table = [] {
        options::TableBuilder<BudgetSettings> b(
            "Budgets and checkpoints",
            "time budget, previews, checkpoints and resuming, for every integrator (docs/progressive.md)");
        b.number("time", &BudgetSettings::time, "SECONDS", at_least(0),
                 "stop after the iteration or sample pass that crosses SECONDS of wall time (0 = no limit)")
            .effect = Effect::Budget;
        b.number("write-every", &BudgetSettings::write_every, "SECONDS", at_least(0),
                 "write the current image every SECONDS (0 = only at the end)")
            .effect = Effect::None;
        b.text("checkpoint", &BudgetSettings::checkpoint_path, "FILE",
               "save the render's state to FILE (atomically), also when interrupted")
            .effect = Effect::None;
        b.number("checkpoint-every", &BudgetSettings::checkpoint_every, "N", between(1, 1 << 30),
                 "iterations (ppm, sppm) or samples per pixel (other integrators) between checkpoints")
            .effect = Effect::None;
        auto& res = b.text("resume", &BudgetSettings::resume_path, "FILE",
                           "continue the render saved in checkpoint FILE (alone: replays its arguments)");
        res.effect = Effect::None;
        res.default_text = "none";
        return b.build();
    }();
    return table;
}

ProgressiveState render_identity(const RenderOptions& ro, const RenderBudget& budget,
                                 const std::string& integrator, uint32_t slots_per_pixel) {
    ProgressiveState state = budget.observers.identity;
    state.integrator = integrator;
    state.width = uint32_t(ro.width);
    state.height = uint32_t(ro.height);
    state.slots_per_pixel = slots_per_pixel;
    state.seed = ro.seed;
    if (!state.options.empty()) state.options_hash = hash_options(state.options);
    return state;
}

ProgressiveState start_state(const RenderOptions& ro, const RenderBudget& budget,
                             const std::string& integrator, uint32_t slots_per_pixel, const std::string& unit,
                             uint64_t target) {
    ProgressiveState state = render_identity(ro, budget, integrator, slots_per_pixel);
    if (const auto& resume = budget.observers.resume) {
        const std::string& path = budget.settings.resume_path;
        check_resumable(*resume, state, path);
        state = *resume;
        const std::string done = std::to_string(state.iterations);
        const bool counted = target < kUnboundedIterations && state.iterations <= target;
        log::info("resuming " + state.integrator + " render from " + path + ": " + done +
                  (counted ? " of " + std::to_string(target) : "") + " " + unit + " done" +
                  (state.photons_emitted > 0 ? ", " + photons_text(state.photons_emitted) + " photons" : ""));
        if (state.iterations > target)
            log::warn("checkpoint " + path + " already holds " + done + " " + unit + ", more than the " +
                      std::to_string(target) + " asked: the image is the " +
                      (slots_per_pixel > 0 ? done + "-iteration one (no further iterations run)"
                                           : "checkpoint's (no further samples taken)"));
    } else {
        state.slots.assign(size_t(ro.width) * size_t(ro.height) * slots_per_pixel, {});
    }
    state.target_iterations = target;
    return state;
}

}  // namespace phos::render
