// The deterministic parallel pixel loop shared by sample-based integrators: fixed tiles rendered
// by oneTBB in any order, every pixel owned by one task, every random number keyed by
// (seed, pixel, sample), so the image is bit-identical for any thread count. Samples are taken in
// passes over the image (sample_passes.h): a time budget, an interrupt, previews and checkpoints
// act between passes or tiles, and since each pixel receives its samples in index order whatever
// the passes, a render stopped and resumed is bit-identical to one run straight through.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/low_discrepancy.h"
#include "core/progress.h"
#include "core/rng.h"
#include "core/stats.h"
#include "film/film.h"
#include "film/tiles.h"
#include "render/path_radiance.h"
#include "render/prepared.h"
#include "render/render_budget.h"

namespace phos::render {

// Radiance along one camera ray. `rays` counts the rays it traces (kept per task).
using RadianceFn = std::function<Rgb(const Ray& ray, Sampler& sampler, RayCounts& rays)>;

// Renders options.spp x options.dof_samples samples per pixel through `radiance`, within
// `budget` (time, interrupts, previews, checkpoints, resume); `integrator` names the render in
// checkpoints and progress. Returns what it completed.
RenderDone render_pixels(const Prepared& prepared, film::Film& film, const RenderBudget& budget,
                         const std::string& integrator, Progress& progress, const RadianceFn& radiance);

// One camera sample of pixel (x, y): the function traces `ray` and records the result itself
// (main image and any layers), multiplied by the sample's pixel-filter `weight` (mean 1; exactly 1
// for the default box filter, PixelFilterSampler). Only the task owning the pixel calls it.
using SampleFn =
    std::function<void(int x, int y, const Ray& ray, float weight, Sampler& sampler, RayCounts& rays)>;
// The same loop for integrators that record more than one value per sample into `film` (layers;
// every layer must exist before the call, and a resumed checkpoint must hold the same layers).
// `payload` (optional) adds the integrator's own data to each checkpoint (SamplePasses).
RenderDone render_samples(const Prepared& prepared, film::Film& film, const RenderBudget& budget,
                          const std::string& integrator, Progress& progress, const SampleFn& sample,
                          const std::function<void(std::string& payload)>& payload = {});
// One pass of `samples` camera samples per pixel (the first ones, as the render takes them), tile
// by tile in parallel, then tile_done (if set) with the tile's ray counts; no budget, progress or
// statistics. For passes beside the render (AOVs).
void for_each_sample(const Prepared& prepared, int samples, const SampleFn& sample,
                     const std::function<void(const RayCounts& rays)>& tile_done = {});
// The index (0, 1, ...) of the camera sample being traced in its pixel, set by
// render_tile_samples around each sample function call it makes (0 elsewhere): what schedules that
// change with the sample count read (path regularisation, integrators/path.cpp).
uint32_t current_sample_index();
// The wavelength sample (in [0, 1)) of that camera sample: sample s of a padded 1D dimension of
// its pixel (core/low_discrepancy.h), so a pixel's hero wavelengths over its samples are one
// stratified sequence and its colour noise falls faster than with independent wavelengths; -1
// outside render_tile_samples. render::camera_wavelengths reads it.
float current_wavelength_sample();
// Samples [s0, s1) of every pixel of `tile`, in pixel order, each sample's camera ray built here.
void render_tile_samples(const Prepared& prepared, const film::Tile& tile, uint32_t s0, uint32_t s1,
                         const SampleFn& sample, RayCounts& rays);

// One camera sample with its components (path_radiance.h): fills `parts` and returns the sample's
// radiance (which is parts.total() up to float rounding).
using PartsFn = std::function<Rgb(const Ray& ray, Sampler& sampler, RayCounts& rays, RadianceParts& parts)>;
// render_pixels that also records the components `layers` as film layers.
RenderDone render_layers(const Prepared& prepared, film::Film& film, const RenderBudget& budget,
                         const std::string& integrator, Progress& progress,
                         const std::vector<Component>& layers, const PartsFn& parts,
                         const std::function<void(std::string& payload)>& payload = {});

// Radiance along one camera ray; with `parts`, also its split into components.
using PathFn = std::function<Rgb(const Ray& ray, Sampler& sampler, RayCounts& rays, RadianceParts* parts)>;
// The whole render of an integrator that is a function of camera rays (whitted, path):
// render_pixels, or with --layers render_layers recording `layers`, then the --trace-pixel pixel
// again (pixel_trace.h).
RenderDone render_paths(const Prepared& prepared, film::Film& film, const RenderBudget& budget,
                        const std::string& integrator, Progress& progress,
                        const std::vector<Component>& layers, const PathFn& radiance);

// Position of camera sample `s` inside its pixel, in [0, 1)^2: point s of the (0,2)-sequence,
// scrambled by the pixel's own random `scramble` bits (core/low_discrepancy.h). Every first 2^k
// samples are stratified in each elementary interval of area 2^-k, and every prefix is evenly
// spread, so an image stopped after any number of samples (a time budget, an interrupt) is as well
// stratified as one planned for that count. Kollig & Keller 2002.
inline Vec2 pixel_sample_position(uint32_t s, uint64_t scramble) { return sobol02_point(s, scramble); }

// Film position of sample `s` of `n` in a square: jittered on a sqrt(n) x sqrt(n) grid for the
// first floor(sqrt(n))^2 samples, uniform for the rest (final-gather directions, PPM hit points).
inline Vec2 stratified_sample(int s, int n, Vec2 u) {
    const int m = int(std::sqrt(double(n)));
    if (s < m * m) return {(float(s % m) + u.x) / float(m), (float(s / m) + u.y) / float(m)};
    return u;
}

}  // namespace phos::render
