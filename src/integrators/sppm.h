// Stochastic progressive photon mapping (Hachisuka & Jensen 2009): every iteration a new
// stochastic eye pass (random position in the pixel, lens sample, random specular choices) finds
// one visible point per pixel, direct light is sampled there by shadow rays, then a photon pass
// adds photons to the visible points within the pixel's shrinking radius. Per-pixel statistics
// (N, R, τ, direct sum) are shared by all iterations; see sppm_pixel_stats.h for the estimator.
#pragma once

#include "integrators/integrator.h"
#include "integrators/progressive_options.h"
#include "render/render_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

class SppmIntegrator : public Integrator {
public:
    SppmIntegrator(ProgressiveOptions options, RenderBudget budget = {})
        : opt_(std::move(options)), budget_(std::move(budget)) {}
    RenderDone render(const Prepared& prepared, film::Film& film, Progress& progress) override;

private:
    ProgressiveOptions opt_;
    RenderBudget budget_;
};

}  // namespace phos::integrators
