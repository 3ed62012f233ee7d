// Bidirectional path tracing (--integrator bdpt; Veach 1997, "Robust Monte Carlo methods for light
// transport simulation", ch. 10): each iteration gives every pixel one camera subpath and one light
// subpath, traced side by side and connected with every strategy: light tracing onto the film
// (t = 1), direct light sampling (s = 1), emitters hit (s = 0) and every inner connection, weighted
// by the power heuristic (Veach 1997, sec. 9.2.4) computed recursively, as vertex connection
// without merging (vcm_mis.h). The camera side is the engine vcm shares (camera_subpath.h).
// docs/bidirectional.md.
#pragma once

#include "integrators/integrator.h"
#include "integrators/progressive_options.h"
#include "render/render_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

class BdptIntegrator final : public Integrator {
public:
    BdptIntegrator(const ProgressiveOptions& options, const RenderBudget& budget)
        : opt_(options), budget_(budget) {}
    RenderDone render(const Prepared& prepared, film::Film& film, Progress& progress) override;

private:
    ProgressiveOptions opt_;
    RenderBudget budget_;
};

}  // namespace phos::integrators
