// Exposure and the sRGB transfer function (IEC 61966-2-1), used to turn linear radiance into 8-bit
// PNG/BMP pixels and to decode 8-bit colour textures back to linear.
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"

namespace phos::io {

// Linear scale for `stops` of exposure: 2^stops.
float exposure_scale(float stops);

// The exact piecewise sRGB OETF (linear -> encoded) and its inverse. Inputs outside [0, 1] are
// clamped; NaN maps to 0.
float linear_to_srgb(float linear);
float srgb_to_linear(float encoded);

// Linear value -> 8-bit sRGB code, rounded to nearest, clamped to [0, 255]; NaN -> 0.
uint8_t linear_to_srgb8(float linear);
// 8-bit sRGB code -> linear value (table lookup, exact inverse of the OETF at the code).
float srgb8_to_linear(uint8_t code);

// Whole image -> interleaved 8-bit sRGB RGB, rows top to bottom, after 2^exposure scaling.
std::vector<uint8_t> to_srgb8(const Image& image, float exposure_stops);

}  // namespace phos::io
