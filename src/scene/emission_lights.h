// Turns emissive surfaces (.scn materials with a glow `e`) into real area lights, for
// `--emission-lights`: they then light the scene, emit photons and are sampled for direct light.
#pragma once

#include "scene/scene.h"

namespace phos::scene {

// Every top-level shape whose material has non-black emission becomes an area light of radiance
// `emission` (one-sided, on its outward side); its material is replaced by a copy without the glow
// so the emission is not counted twice. Returns the number of lights added.
int emissive_shapes_to_lights(Scene& scene);

}  // namespace phos::scene
