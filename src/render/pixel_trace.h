// How the sample-based integrators (whitted, path, photonmap) trace the pixel --trace-pixel names:
// after the render, that pixel's camera samples run again with the recorder active. Every random
// number is keyed by (seed, pixel, sample) (pixel_loop.h), so they reproduce the film's samples
// exactly, and the film's pixel is the mean of the recorded contributions.
#pragma once

#include "film/film.h"
#include "render/pixel_loop.h"

namespace phos::render {

// With a trace requested (path_recorder.h), re-runs the traced pixel's samples through `radiance`
// (as the render took them, from sample 0 until as many finite ones as `film` holds there: the film
// drops non-finite samples), recording each. Does nothing otherwise.
void trace_pixel_samples(const Prepared& P, const film::Film& film, const RadianceFn& radiance);

}  // namespace phos::render
