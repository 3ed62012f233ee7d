// bdpt's render loop, one screen: per iteration the camera pass (each pixel's light subpath traced
// beside its camera subpath, nothing stored; camera_subpath.h), the sums over the ranks, and the
// budget's previews and checkpoints. Each pixel's value is the mean over iterations of its
// estimate plus the light-tracing splats that landed on it (fixed_film.h).
#include "integrators/bdpt.h"

#include "film/tiles.h"
#include "integrators/camera_subpath.h"
#include "integrators/fixed_film.h"
#include "render/progressive_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

RenderDone BdptIntegrator::render(const Prepared& P, film::Film& film, Progress& progress) {
    using namespace vcm;
    const RenderOptions& ro = P.options;
    ProgressiveState state = start_state(ro, budget_, "bdpt", 0, "iterations", uint64_t(std::max(1, ro.spp)));
    FixedFilm sums(ro.width, ro.height, ro.layers);  // this rank's image sums (all of them without MPI)
    sums.resume(state, "checkpoint '" + budget_.settings.resume_path + "': bdpt sums");
    const Iteration it = iteration_for(kBdptStrategies, opt_);
    const LightSubpathRules light_rules{std::max(1, ro.max_depth), it.factors};
    const auto tiles = film::make_tiles(ro.width, ro.height);
    const RenderBudget budget = sums.saving_sums(budget_);
    const auto resolve_film = [&] { sums.resolve(film, state.iterations); };

    ProgressiveBudget loop(ro, budget, state, film, progress);
    while (loop.next()) {
        const uint64_t iteration = state.iterations;
        camera_pass(P, it, nullptr, tiles, iteration, sums,
                    [&](size_t i, std::vector<Vertex>& light, RayCounts& rays) {
                        Sampler sampler(ro.seed, kLightSubpathStream, i, iteration);
                        trace_light_path(P, light_rules, sampler, subpath_wavelengths(ro.seed, i, iteration),
                                         light, rays);
                    });
        sums.sum_over_ranks();
        loop.after_iteration(resolve_film);
    }
    resolve_film();
    const RenderDone done = loop.finish();
    P.stats.add_dropped_samples(sums.rejected());
    P.stats.add_value("bdpt", std::to_string(state.iterations) + " iterations");
    return done;
}

}  // namespace phos::integrators
