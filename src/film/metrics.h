// Error metrics against a reference image, as defined in shared/bench/README.md: relMSE, mean
// ratio and the mean over a pixel window (used for caustics); and two measures of an image's look:
// the share of isolated bright pixels (fireflies) and the block correlation with another image.
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

// Fraction of isolated bright pixels ("speckles", fireflies): pixels whose luminance exceeds
// kSpeckleRatio x the median luminance of their 5x5 neighbourhood (clipped at the border, the
// pixel included) + kSpeckleOffset. Luminance is Rec. 709 of the values given: pass the
// display-encoded image (sRGB, clamped to [0, 1], as `phos info` does) to count what a viewer sees;
// the offset keeps dark noise from counting.
inline constexpr double kSpeckleRatio = 3.0, kSpeckleOffset = 0.05;
double speckle_fraction(const Image& image);
// Pearson correlation over blocks of block x block pixels (partial blocks at the right and bottom
// edges left out) of the two images' mean luminance per block: 1 when one is an affine brightening
// of the other at that scale. The images may differ in size when one is an integer multiple of the
// other (the larger one's blocks are scaled accordingly). InputError if the sizes are not such
// multiples or no whole block fits; 0 if either image's block means are all equal.
double block_correlation(const Image& a, const Image& b, int block);

}  // namespace phos::film
