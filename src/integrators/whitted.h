// Whitted-style ray tracing: direct light from every light by shadow rays at diffuse and glossy
// surfaces, recursion through mirrors and glass, background for escaping rays.
#pragma once

#include <vector>

#include "core/rng.h"
#include "integrators/integrator.h"
#include "render/path_radiance.h"
#include "render/render_budget.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

class WhittedIntegrator : public Integrator {
public:
    // `layers`: the components recorded with --layers (the registry gives direct and specular).
    explicit WhittedIntegrator(RenderBudget budget = {}, std::vector<Component> layers = {})
        : budget_(std::move(budget)), layers_(std::move(layers)) {}
    RenderDone render(const Prepared& prepared, film::Film& film, Progress& progress) override;
    // Radiance arriving at the camera along `ray`. With `parts`, also its split into components
    // (path_radiance.h): the recursion counts as delta bounces, so what the first surface seen
    // sends by its own emission and light sampling is direct, everything found through mirrors and
    // glass specular.
    static Rgb radiance(const Prepared& prepared, Ray ray, Sampler& sampler, RayCounts& rays,
                        RadianceParts* parts = nullptr);

private:
    RenderBudget budget_;
    std::vector<Component> layers_;
};

}  // namespace phos::integrators
