// Options of the two-pass photon-map integrator (--integrator photonmap). Filled by the CLI
// (app/lib/photon_map_cli.cpp); documented in docs/photon-mapping.md.
#pragma once

#include <cstdint>

namespace phos::integrators {

struct PhotonMapOptions {};

}  // namespace phos::integrators
