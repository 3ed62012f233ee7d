// Progressive photon mapping (Hachisuka, Ogaki & Jensen 2008): one eye pass stores hit points
// (eye_samples per pixel) at the first non-specular surface, with direct light computed there once
// by `direct_samples` shadow-ray samples; then photon passes refine each hit point's radius and
// flux (see sppm_pixel_stats.h for the update). Photons carry only indirect light.
#pragma once

#include "integrators/integrator.h"
#include "integrators/progressive_options.h"
#include "render/render_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

class PpmIntegrator : public Integrator {
public:
    PpmIntegrator(ProgressiveOptions options, RenderBudget budget = {})
        : opt_(std::move(options)), budget_(std::move(budget)) {}
    RenderDone render(const Prepared& prepared, film::Film& film, Progress& progress) override;

private:
    ProgressiveOptions opt_;
    RenderBudget budget_;
};

}  // namespace phos::integrators
