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
};

// Prints relMSE, mean ratio and (with a window) both window means; throws InputError.
void run_diff(const DiffCommand& cmd);

}  // namespace phos::app
