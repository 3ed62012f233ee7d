// Turns emissive surfaces (.scn materials with a glow `e`) into real area lights: they then light the
// scene, emit photons and are sampled for direct light. The .scn loader does this unless told not to
// (`--no-emission-lights`).
#pragma once

#include "scene/scene.h"

namespace phos::scene {

// Every top-level shape whose material has non-black emission becomes an area light of radiance
// `emission`, on both sides when `two_sided` (as a .scn glow is seen from both sides), else on its
// outward side; its material is replaced by a copy without the glow so the emission is not counted
// twice. Returns the number of lights added.
int emissive_shapes_to_lights(Scene& scene, bool two_sided);

}  // namespace phos::scene
