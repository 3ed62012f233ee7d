// Bidirectional path tracing (--integrator bdpt, Veach 1997) and vertex connection and merging
// (--integrator vcm, Georgiev, Křivánek, Davidovič & Slusallek 2012; Hachisuka, Pantaleoni &
// Jensen 2012): one engine. Each iteration gives every pixel one camera subpath and one light
// subpath; bdpt connects them with every strategy (light tracing onto the film, t = 1; direct
// light sampling, s = 1; emitters hit, s = 0; every inner connection), vcm also merges each camera
// vertex with all light vertices of the iteration within a radius that shrinks per iteration.
// All weights are the power heuristic, computed recursively (vcm_mis.h). docs/bidirectional.md.
#pragma once

#include "integrators/integrator.h"
#include "integrators/progressive_options.h"
#include "render/render_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

class VcmIntegrator final : public Integrator {
public:
    // `bdpt`: the bdpt integrator (connections only, no light-vertex storage); else the strategies
    // --vcm-mode names.
    VcmIntegrator(bool bdpt, const ProgressiveOptions& options, const RenderBudget& budget)
        : bdpt_(bdpt), opt_(options), budget_(budget) {}
    RenderDone render(const Prepared& prepared, film::Film& film, Progress& progress) override;

private:
    bool bdpt_;
    ProgressiveOptions opt_;
    RenderBudget budget_;
};

}  // namespace phos::integrators
