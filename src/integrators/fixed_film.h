// The image of bdpt and vcm: each pixel's sums over iterations (r, g, b; with --layers also per
// Part) as 2^-30 fixed-point integers, so that camera subpaths and the splats of light tracing
// (which land on any pixel, from any thread) add up to the same bits in any order; summed exactly
// over the ranks under MPI, resolved into the film as the mean per iteration, saved in checkpoints.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec.h"
#include "film/film.h"
#include "render/path_radiance.h"
#include "render/progressive_checkpoint.h"
#include "render/render_budget.h"

namespace phos::integrators::vcm {
using namespace render;  // the render support the algorithms are written over (src/render/)

// The component a contribution belongs to with --layers (render/path_radiance.h's Component, in
// its order, whose names the layers take): what reached the camera after a delta bounce at its first vertex
// x1 (specular), else light reaching x1 straight from the light (direct, x1's own emission too), through
// delta bounces only (caustic), or through a diffuse or glossy vertex (indirect).
enum Part { kDirect, kCaustic, kIndirect, kSpecular, kParts };

// Rounding to 2^-30 per contribution is far below a float's resolution of the pixel values phos
// writes. Plane 0 is the image; with layers, planes 1.. are the Parts.
class FixedFilm {
public:
    FixedFilm(int width, int height, bool layers);
    // Resumes from the sums a checkpoint saved in state.payload (none: a fresh render); `what`
    // names them in errors.
    void resume(const ProgressiveState& state, const std::string& what);
    // Adds v to the pixel's image and to its `part` layer (thread-safe); a sum that is not finite
    // is rejected (counted).
    void add(size_t pixel, Rgb v, Part part);
    // Under MPI: every rank's sums added up (integers: exact), which resolve() and checkpoints
    // then read. No-op with one rank.
    void sum_over_ranks();
    // Pixel = sum / iterations, for the image and each layer.
    void resolve(film::Film& film, uint64_t iterations) const;
    // `budget` whose checkpoints also save the sums (in ProgressiveState::payload); `budget` must
    // outlive the copy.
    RenderBudget saving_sums(const RenderBudget& budget) const;
    uint64_t rejected() const { return rejected_.load(); }

private:
    std::vector<int64_t> values() const;  // this rank's sums
    int width_, height_;
    size_t pixels_, planes_;
    std::vector<std::atomic<int64_t>> sums_;  // this rank's (all of them without MPI)
    std::vector<int64_t> total_;              // under MPI: every rank's sums added up
    std::atomic<uint64_t> rejected_{0};
};

}  // namespace phos::integrators::vcm
