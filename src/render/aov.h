// Auxiliary images for denoisers (--aov albedo,normal,depth): a separate deterministic pass over
// the same camera samples as the render, stored as film layers named after the AOV.
#pragma once

#include "film/film.h"
#include "render/prepared.h"

namespace phos::render {

// For each name in P.options.aovs (see aov_names()), fills the film layer of that name with the
// mean over each pixel's camera samples (the pixel loop's tiles, samples and random numbers, so
// any thread count gives the same bytes) of:
// - "albedo": what the pixel's colour is made of, the way denoisers such as OIDN expect it. At the
//   first surface seen, the directional albedo (LobeAlbedos at wo) of its non-delta lobes (kd for a
//   Lambertian surface, texture applied); delta lobes (mirrors, smooth glass) are followed like
//   the integrators follow them (one sampled branch, up to max_depth bounces) and add the albedo
//   of what they show times their throughput. A ray that leaves the scene adds its throughput
//   times the radiance seen there (background plus infinite lights) clamped to [0, 1] per
//   channel: a flat feature of the sky's colour rather than a black hole. A light source adds
//   its own material's albedo (black for .scn lights).
// - "normal": the world-space shading normal of the first surface hit, turned towards the camera
//   (the side the ray arrives from); (0, 0, 0) for a sample that hits nothing, so a pixel on a
//   silhouette gets a shorter mean normal and the sky a zero one, as OIDN expects.
// - "depth": the distance in scene units from the lens point along the camera ray to the first
//   surface (medium interfaces pass through), in all three channels. The mean is over the
//   samples that hit something; 0 means no sample hit anything (there is no infinity: image files
//   and the film keep finite values only).
// Throws InputError for a name that is not an AOV, naming the valid ones. Does nothing without
// AOVs. Ray counts are not added to the render's statistics.
void render_aovs(const Prepared& P, film::Film& film);

}  // namespace phos::render
