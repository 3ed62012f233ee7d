// Command-line options of the photon-map integrator.
#pragma once

#include <CLI/CLI.hpp>

#include "integrators/photon_map_options.h"

namespace phos::app {

void add_photon_map_options(CLI::App& render, integrators::PhotonMapOptions& options);

}  // namespace phos::app
