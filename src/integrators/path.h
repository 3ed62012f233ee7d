// Unidirectional path tracing with next-event estimation and multiple importance sampling
// (power heuristic) and Russian roulette: phos's own unbiased reference integrator.
#pragma once

#include "core/rng.h"
#include "integrators/integrator.h"

namespace phos::integrators {

class PathIntegrator : public Integrator {
public:
    void render(const Prepared& prepared, film::Film& film, Progress& progress) override;
    // Radiance arriving at the camera along `ray` (exposed for tests and other integrators).
    static Rgb radiance(const Prepared& prepared, accel::Ray ray, Sampler& sampler, RayCounts& rays);
};

}  // namespace phos::integrators
