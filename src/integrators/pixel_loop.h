// The deterministic parallel pixel loop shared by sample-based integrators: fixed tiles rendered
// by oneTBB in any order, every pixel owned by one task, every random number keyed by
// (seed, pixel, sample), so the image is bit-identical for any thread count.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/progress.h"
#include "core/rng.h"
#include "core/stats.h"
#include "film/film.h"
#include "integrators/prepared.h"

namespace phos::integrators {

// Radiance along one camera ray. `rays` counts the rays it traces (kept per task).
using RadianceFn = std::function<Rgb(const accel::Ray& ray, Sampler& sampler, RayCounts& rays)>;

// Renders options.spp x options.dof_samples stratified samples per pixel through `radiance`.
void render_pixels(const Prepared& prepared, film::Film& film, Progress& progress,
                   const RadianceFn& radiance);

// One camera sample of pixel (x, y): the function traces `ray` and records the result itself
// (main image and any layers). Only the task owning the pixel calls it.
using SampleFn = std::function<void(int x, int y, const accel::Ray& ray, Sampler& sampler, RayCounts& rays)>;
// The same loop for integrators that record more than one value per sample (layers).
void render_samples(const Prepared& prepared, const std::string& label, Progress& progress,
                    const SampleFn& sample);
// The loop itself, without progress or statistics: every camera sample of every pixel, tile by tile,
// then tile_done (if set) with the tile's ray counts. For passes beside the render (AOVs).
void for_each_sample(const Prepared& prepared, const SampleFn& sample,
                     const std::function<void(const RayCounts& rays)>& tile_done = {});

// Radiance along a camera ray split by component, for --layers (film layers "direct", "caustic",
// "indirect", "specular" summing to the image). `specular` holds everything that reached the
// camera after at least one mirror/glass (delta) bounce from it; the other three are what the
// first surface x seen directly sends: direct = its emission, light sampled at it and emission
// found by its BSDF samples (the light sampling's MIS partner), caustic = light reaching x through
// one or more delta bounces after it (x S+ L), indirect = the rest.
struct RadianceParts {
    Rgb direct{0.0f}, caustic{0.0f}, indirect{0.0f}, specular{0.0f};
    Rgb total() const { return direct + caustic + indirect + specular; }
};

// One camera sample with its components: fills `parts` and returns the sample's radiance (which
// is parts.total() up to float rounding).
using PartsFn =
    std::function<Rgb(const accel::Ray& ray, Sampler& sampler, RayCounts& rays, RadianceParts& parts)>;
// render_pixels that also records the components named in `layers` (a subset of "direct",
// "caustic", "indirect", "specular") as film layers.
void render_layers(const Prepared& prepared, film::Film& film, Progress& progress, const std::string& label,
                   const std::vector<std::string>& layers, const PartsFn& parts);

// Film position of sample `s` of `n` in the pixel: jittered on a sqrt(n) x sqrt(n) grid for the
// first floor(sqrt(n))^2 samples, uniform for the rest.
inline Vec2 stratified_sample(int s, int n, Vec2 u) {
    const int m = int(std::sqrt(double(n)));
    if (s < m * m) return {(float(s % m) + u.x) / float(m), (float(s / m) + u.y) / float(m)};
    return u;
}

}  // namespace phos::integrators
