// Error metrics against a reference image, as defined in shared/bench/README.md: relMSE, mean
// ratio and the mean over a pixel window (used for caustics).
#pragma once

#include "core/image.h"

namespace phos::film {

// Mean over pixels and channels of (x - r)^2 / (r^2 + 0.01). InputError if the sizes differ.
double rel_mse(const Image& image, const Image& reference);
// mean(image) / mean(reference), means over pixels and channels. InputError if the sizes differ;
// +inf if only the reference is black, 1 if both are.
double mean_ratio(const Image& image, const Image& reference);
// Mean over the pixels x in [x0, x1), y in [y0, y1) (y from the top) of the channel average.
// InputError if the window is empty or not inside the image.
double window_mean(const Image& image, int x0, int x1, int y0, int y1);
// Mean over all pixels and channels (0 for an empty image).
double mean_value(const Image& image);

}  // namespace phos::film
