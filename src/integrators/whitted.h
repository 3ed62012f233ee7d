// Whitted-style ray tracing: direct light from every light by shadow rays at diffuse and glossy
// surfaces, recursion through mirrors and glass, background for escaping rays.
#pragma once

#include "core/rng.h"
#include "integrators/integrator.h"

namespace phos::integrators {

class WhittedIntegrator : public Integrator {
public:
    void render(const Prepared& prepared, film::Film& film, Progress& progress) override;
    static Rgb radiance(const Prepared& prepared, accel::Ray ray, Sampler& sampler, RayCounts& rays);
};

}  // namespace phos::integrators
