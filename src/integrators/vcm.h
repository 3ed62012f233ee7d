// Vertex connection and merging (--integrator vcm; Georgiev, Křivánek, Davidovič & Slusallek 2012;
// Hachisuka, Pantaleoni & Jensen 2012): each iteration gives every pixel one camera subpath and K
// light subpaths; the camera subpath takes bdpt's strategies with the pixel's first light subpath
// and also merges with the light vertices of the whole iteration within a radius that shrinks per
// iteration. --vcm-mode picks the strategies (vcm, bpt, ppm, lt). All weights are the power
// heuristic, computed recursively (vcm_mis.h); the camera side is the engine bdpt shares
// (camera_subpath.h). docs/bidirectional.md.
#pragma once

#include "integrators/integrator.h"
#include "integrators/progressive_options.h"
#include "render/render_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

class VcmIntegrator final : public Integrator {
public:
    VcmIntegrator(const ProgressiveOptions& options, const RenderBudget& budget)
        : opt_(options), budget_(budget) {}
    RenderDone render(const Prepared& prepared, film::Film& film, Progress& progress) override;

private:
    ProgressiveOptions opt_;
    RenderBudget budget_;
};

}  // namespace phos::integrators
