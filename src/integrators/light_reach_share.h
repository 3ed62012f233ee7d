// How a prepared scene is lit, for choosing its defaults (app/lib/scene_defaults.h): the share of
// the lights' power that first reaches the surfaces through mirrors, glass or sharp glossy lobes.
#pragma once

#include "render/prepared.h"

namespace phos::integrators {

// photon::survey_light_reach's followed share on P (its --sharp-glossy split and seed); 0 without
// lights or without any material that can carry light that way.
double share_lit_through_interfaces(const render::Prepared& P);

}  // namespace phos::integrators
