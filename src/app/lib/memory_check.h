// phos render's memory check: the estimated peak memory of the render (integrators/
// memory_estimate.h) against --max-memory or the memory available (core/memory.h), before any
// work, and the estimate and measured peak in the -v statistics.
#pragma once

#include "app/lib/render_options.h"
#include "core/stats.h"
#include "scene/scene.h"

namespace phos::app {

// Estimates the render's peak memory and records it in `stats` ("memory estimate"); throws
// InputError (exit 2, nothing written) when it exceeds --max-memory or, without one, what this
// process can have: what it holds now plus what is still available.
void check_memory(const RenderCommand& cmd, const scene::Scene& scene, Stats& stats);

// Records the process's peak resident memory so far in `stats` ("peak memory").
void add_peak_memory(Stats& stats);

}  // namespace phos::app
