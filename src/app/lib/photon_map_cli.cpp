// Command-line options of the photon-map integrator (registered on `phos render`).
#include "app/lib/photon_map_cli.h"

namespace phos::app {

void add_photon_map_options(CLI::App& /*render*/, integrators::PhotonMapOptions& /*options*/) {}

}  // namespace phos::app
