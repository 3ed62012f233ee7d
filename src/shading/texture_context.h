// The texture context of a surface hit (scene::TextureContext): the point, its uv and geometric
// normal, and, for scenes with filtered image textures, the screen-space derivatives of p and
// (u, v) from pbrt-v4's camera footprint approximation (scene/camera_footprint.h).
#pragma once

#include "accel/ray.h"
#include "scene/camera_footprint.h"
#include "scene/scene.h"
#include "scene/texture_mapping.h"

namespace phos::shading {

// Without a footprint: {hit.uv, hit.p, hit.ng} and zero derivatives (point lookups). With one:
// dpdx and dpdy from approximate_dp_dxy at (hit.p, hit.ng) and the (u, v) derivatives from the
// surface's dpdu and dpdv (accel::surface_derivatives), as pbrt-v4 computes them for every hit
// that is not a camera ray's (SurfaceInteraction::ComputeDifferentials); phos uses the
// approximation for camera rays too, and for photon paths.
scene::TextureContext texture_context(const scene::Scene& scene, const accel::SurfaceHit& hit,
                                      const scene::CameraFootprint* footprint);

}  // namespace phos::shading
