// `phos diff IMAGE REFERENCE`: the error metrics of ../shared/bench/README.md between two images.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace phos::app {

struct DiffCommand {
    std::string image, reference;
    // Optional pixel window x0 x1 y0 y1 (half-open, y from the top) whose means are compared.
    std::vector<int> window;
    // With a block size: also the 16x16 (or this size) block correlation of the two images, which
    // may then differ in size by an integer factor (relMSE and mean ratio need equal sizes).
    int block_correlation = 0;
};

// Prints relMSE, mean ratio (equal sizes), with a window both window means and with a block size
// the block correlation; throws InputError.
void run_diff(const DiffCommand& cmd);

}  // namespace phos::app
