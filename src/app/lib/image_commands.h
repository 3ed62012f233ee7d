// `phos info IMAGE...` (per image: size, mean, fraction of black pixels, non-finite values) and
// `phos montage OUT IMAGE...` (a contact sheet: every image scaled into a grid cell), used by
// bench/seed_scenes.sh to survey a folder of renders.
#pragma once

#include <string>
#include <vector>

#include "core/image.h"

namespace phos::app {

struct ImageInfo {
    int width = 0, height = 0;
    double mean = 0;            // mean of the finite channel values
    double black_fraction = 0;  // pixels whose three channels are exactly 0
    uint64_t non_finite = 0;    // channel values that are NaN or infinite
    double speckle = 0;         // film::speckle_fraction of the sRGB-encoded image (fireflies)
    double speckle_linear = 0;  // the same on the linear values (finds dots on bright surfaces too)
};
ImageInfo image_info(const Image& image);

// Mean Rec. 709 luminance over the half-open pixel window [x0, x1) x [y0, y1) (y from the top),
// clipped to the image (0 when empty).
double window_luminance(const Image& image, int x0, int x1, int y0, int y1);

// Prints one line per image: "path WxH mean M black B nonfinite N speckle S
// speckle_linear L", then for each window
// (x0 x1 y0 y1, four numbers each) "  window x0 x1 y0 y1 luminance L". Throws InputError.
void run_info(const std::vector<std::string>& paths, const std::vector<int>& windows = {});

// The contact sheet: ceil(sqrt(n)) columns of `cell` x `cell` pixel cells, each image scaled
// (box filter, aspect kept, centred) into its cell; black background.
Image montage(const std::vector<Image>& images, int cell);
// Reads `inputs`, writes their montage to `output` (any writable image format). Throws InputError.
void run_montage(const std::string& output, const std::vector<std::string>& inputs, int cell);

}  // namespace phos::app
