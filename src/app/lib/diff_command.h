// `phos diff IMAGE REFERENCE`: the error metrics of ../shared/bench/README.md between two images.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/image.h"

namespace phos::app {

struct DiffCommand {
    std::string image, reference;
    // Optional pixel window x0 x1 y0 y1 (half-open, y from the top) whose means are compared.
    std::vector<int> window;
    // With a block size: also the block correlation of the two images as displayed (sRGB, clamped:
    // their look), which may then differ in size by an integer factor (relMSE and mean ratio need
    // equal sizes).
    int block_correlation = 0;
};

// The image as a display shows it: sRGB-encoded, clamped to [0, 1] (what the look comparisons and
// the speckle fraction read).
Image displayed(const Image& image);

// Prints relMSE, mean ratio (equal sizes), with a window both window means and with a block size
// the block correlation; throws InputError.
void run_diff(const DiffCommand& cmd);

}  // namespace phos::app
