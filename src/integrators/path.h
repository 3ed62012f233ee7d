// Unidirectional path tracing with next-event estimation and multiple importance sampling
// (power heuristic) and Russian roulette: phos's own unbiased reference integrator.
#pragma once

#include <vector>

#include "core/rng.h"
#include "integrators/integrator.h"
#include "render/path_radiance.h"
#include "render/render_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

class PathIntegrator : public Integrator {
public:
    // `layers`: the components recorded with --layers (the registry gives all four).
    explicit PathIntegrator(RenderBudget budget = {}, std::vector<Component> layers = {})
        : budget_(std::move(budget)), layers_(std::move(layers)) {}
    RenderDone render(const Prepared& prepared, film::Film& film, Progress& progress) override;
    // Radiance arriving at the camera along `ray` (exposed for tests and other integrators). With
    // `parts`, also its split into components by the path's bounces (path_radiance.h).
    static Rgb radiance(const Prepared& prepared, Ray ray, Sampler& sampler, RayCounts& rays,
                        RadianceParts* parts = nullptr);

private:
    RenderBudget budget_;
    std::vector<Component> layers_;
};

}  // namespace phos::integrators
