// The memory check before a render and the memory lines of -v (see memory_check.h).
#include "app/lib/memory_check.h"

#include "core/error.h"
#include "core/memory.h"
#include "integrators/memory_estimate.h"

namespace phos::app {

void check_memory(const RenderCommand& cmd, const scene::Scene& scene, Stats& stats) {
    integrators::MemoryEstimateInputs in;
    in.integrator = cmd.run.integrator;
    in.render = cmd.render;
    in.photon_map = cmd.photon_map;
    in.progressive = cmd.progressive;
    in.threads = cmd.run.threads;
    in.checkpoint = !cmd.budget.checkpoint_path.empty();
    const integrators::MemoryEstimate e = integrators::estimate_memory(scene, in);
    const std::string needed = memory::format_bytes(e.total);
    stats.add_value("memory estimate", needed + " (at the peak, " + e.phase + ": " + e.breakdown(8) + ")");

    if (cmd.run.max_memory > 0) {
        const double limit = double(cmd.run.max_memory) * 1e9;
        if (double(e.total) > limit)
            throw InputError("this render needs about " + needed + " (" + e.breakdown() +
                             ") but --max-memory " + "allows only " + memory::format_bytes(uint64_t(limit)));
        return;
    }
    const memory::Available a = memory::available();
    if (!a.bytes) return;  // unknown here: only --max-memory can refuse
    const uint64_t limit = *a.bytes + memory::current_rss().value_or(0);
    stats.add_value("memory available", memory::format_bytes(limit) + " (" + a.limited_by + ")");
    if (e.total > limit)
        throw InputError("this render needs about " + needed + " (" + e.breakdown() + ") but only " +
                         memory::format_bytes(limit) + " are available (" + a.limited_by +
                         "; --max-memory GB sets the limit)");
}

void add_peak_memory(Stats& stats) {
    if (const auto peak = memory::peak_rss()) stats.add_value("peak memory", memory::format_bytes(*peak));
}

}  // namespace phos::app
