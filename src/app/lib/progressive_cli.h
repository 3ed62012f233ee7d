// Command-line options of the progressive (ppm / sppm) integrators.
#pragma once

#include <CLI/CLI.hpp>

#include "integrators/progressive_options.h"

namespace phos::app {

void add_progressive_options(CLI::App& render, integrators::ProgressiveOptions& options);

}  // namespace phos::app
