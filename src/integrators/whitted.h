// Whitted-style ray tracing: direct light from every light by shadow rays at diffuse and glossy
// surfaces, recursion through mirrors and glass, background for escaping rays.
#pragma once

#include "core/rng.h"
#include "integrators/integrator.h"
#include "render/render_budget.h"

namespace phos::render {
struct RadianceParts;  // pixel_loop.h
}  // namespace phos::render

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)

class WhittedIntegrator : public Integrator {
public:
    explicit WhittedIntegrator(RenderBudget budget = {}) : budget_(std::move(budget)) {}
    void render(const Prepared& prepared, film::Film& film, Progress& progress) override;
    // Radiance arriving at the camera along `ray`. With `parts`, also its split into components
    // (pixel_loop.h): what the first surface seen sends by its own emission and light sampling is
    // direct, everything found through the recursion (mirrors and glass) specular.
    static Rgb radiance(const Prepared& prepared, Ray ray, Sampler& sampler, RayCounts& rays,
                        RadianceParts* parts = nullptr);

private:
    RenderBudget budget_;
};

}  // namespace phos::integrators
