// Stochastic progressive photon mapping (Hachisuka & Jensen 2009): every iteration a new
// stochastic eye pass (random position in the pixel, lens sample, random specular choices) finds
// one visible point per pixel, direct light is sampled there by shadow rays, then a photon pass
// adds photons to the visible points within the pixel's shrinking radius. Per-pixel statistics
// (N, R, τ, direct sum) are shared by all iterations; see sppm_pixel_stats.h for the estimator.
#pragma once

#include "integrators/integrator.h"
#include "integrators/progressive_options.h"

namespace phos::integrators {

class SppmIntegrator : public Integrator {
public:
    explicit SppmIntegrator(ProgressiveOptions options) : opt_(std::move(options)) {}
    void render(const Prepared& prepared, film::Film& film, Progress& progress) override;

private:
    ProgressiveOptions opt_;
};

// Initial radius multiplier of the automatic radius, in pixel footprints at the hit distance.
constexpr float kDefaultRadiusPixels = 4.0f;
// Photons a pixel's disc should hold after the pilot pass (--radius-photons, see PilotRadius in
// sppm_pixel_stats.h), and the bounds of that per-pixel radius in pixel footprints.
constexpr double kDefaultRadiusPhotons = 64;
constexpr double kPilotRadiusMinPixels = 1, kPilotRadiusMaxPixels = 8;
// Light samples per visible point per iteration (--direct-samples). One leaves the direct light's
// noise dominant on area-lit scenes; 4 cost ~10 % more time per iteration and cut cornell-diffuse's
// relMSE at 60 iterations from 0.00095 to 0.00074 (8: 0.00071 for +25 %).
constexpr int kSppmDirectSamples = 4;
// PPM computes direct light once, so it takes many more samples.
constexpr int kPpmDirectSamples = 16;

}  // namespace phos::integrators
