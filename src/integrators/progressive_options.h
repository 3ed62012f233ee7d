// Options of the progressive photon-mapping integrators (--integrator ppm | sppm). Filled by the
// CLI (app/lib/progressive_cli.cpp); documented in docs/progressive.md.
#pragma once

#include <cstdint>

namespace phos::integrators {

struct ProgressiveOptions {};

}  // namespace phos::integrators
