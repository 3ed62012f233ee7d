// Where each light sits among the participating media: the medium its photons and light subpaths
// start in. A light the file places (scene::Light::medium_declared) keeps its declaration; any
// other sits in the medium that medium tracking from the camera reaches at its emitting points, the
// same tracking camera and shadow rays do, so every integrator sees one scene.
#pragma once

#include <optional>
#include <vector>

#include "accel/embree_scene.h"
#include "core/vec.h"
#include "shading/lights.h"

namespace phos::shading {

// The medium a ray from `from`, travelling in `medium` (-1 = vacuum), is in when it reaches `to`:
// each medium transition it crosses on the way changes it (SurfaceWalk::medium_after); other
// surfaces do not. nullopt when the segment crosses more surfaces than a walk may.
std::optional<int> medium_reached(const accel::EmbreeScene& accel, Vec3 from, int medium, Vec3 to);

// Each light's media (LightSet::set_media), seen from a camera at `eye` in `camera_medium`. An area
// light whose shape is a medium transition emits into the medium on each side of it (outside
// along its normal). Every other light's emitting points (up to 16, from sample_Le) are tracked
// from the camera; a declared light keeps its declaration. Warns once per light, naming its
// origin, when its points lie in different media (the most common one is chosen) or when a
// declaration differs from what tracking finds.
std::vector<LightMedia> place_lights_in_media(const accel::EmbreeScene& accel, const LightSet& lights,
                                              Vec3 eye, int camera_medium);

}  // namespace phos::shading
