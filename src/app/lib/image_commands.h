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
};
ImageInfo image_info(const Image& image);

// Prints one line per image: "path WxH mean M black B nonfinite N". Throws InputError.
void run_info(const std::vector<std::string>& paths);

// The contact sheet: ceil(sqrt(n)) columns of `cell` x `cell` pixel cells, each image scaled
// (box filter, aspect kept, centred) into its cell; black background.
Image montage(const std::vector<Image>& images, int cell);
// Reads `inputs`, writes their montage to `output` (any writable image format). Throws InputError.
void run_montage(const std::string& output, const std::vector<std::string>& inputs, int cell);

}  // namespace phos::app
