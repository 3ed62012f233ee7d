// Light-transport options over render::RenderOptions that only some integrators read: which
// glossy lobes camera paths follow (--sharp-glossy: photonmap, ppm, sppm) and path tracing's
// regularisation of sharp lobes after a rough bounce (--regularize: path). Their fields live in
// RenderOptions so that every integrator sees them through Prepared; this table (in the
// integrators layer, which knows the integrators) says which ones they apply to.
#pragma once

#include "core/option_table.h"

namespace phos::integrators {

const options::Table& transport_options();

}  // namespace phos::integrators
