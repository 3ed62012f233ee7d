// Unidirectional path tracing with next-event estimation and multiple importance sampling
// (power heuristic) and Russian roulette: phos's own unbiased reference integrator.
#pragma once

#include "core/rng.h"
#include "integrators/integrator.h"
#include "render/render_budget.h"

namespace phos::render {
struct RadianceParts;  // pixel_loop.h
}  // namespace phos::render

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

class PathIntegrator : public Integrator {
public:
    explicit PathIntegrator(RenderBudget budget = {}) : budget_(std::move(budget)) {}
    void render(const Prepared& prepared, film::Film& film, Progress& progress) override;
    // Radiance arriving at the camera along `ray` (exposed for tests and other integrators). With
    // `parts`, also its split into components (pixel_loop.h) by the path's bounces: emission seen
    // through delta bounces from the camera (and all a surface seen that way sends) is specular;
    // at the first surface x seen directly, its emission, the light sampled at it and the emission
    // its BSDF sample finds are direct, light found after x through delta bounces only is caustic,
    // the rest indirect. --layers records them.
    static Rgb radiance(const Prepared& prepared, Ray ray, Sampler& sampler, RayCounts& rays,
                        RadianceParts* parts = nullptr);

private:
    RenderBudget budget_;
};

}  // namespace phos::integrators
