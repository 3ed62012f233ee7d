// What vcm's merging needs before its first iteration: the light subpaths per pixel and each
// pixel's first merging radius, from a pilot light pass and a pilot camera ray per pixel (their own
// random numbers, the same on every rank, not part of the image). docs/bidirectional.md.
#pragma once

#include <vector>

#include "integrators/camera_subpath.h"
#include "integrators/progressive_options.h"

namespace phos::integrators::vcm {

struct MergingPlan {
    int merge_from = 0;  // light subpath vertices this many segments from the light on merge (0: none)
    int light_paths_per_pixel = 1;  // light subpaths per pixel and iteration
    double mergeable_per_path = 0;  // the pilot's mergeable vertices per light subpath (0: no pilot)
    float base_radius = 0;          // the first iteration's largest merging radius
    // Merging at the first non-delta camera vertex: each pixel's first radius (pixel_radii);
    // empty: `base_radius` for every pixel.
    std::vector<float> pixel_radius;
};

// The plan for `strategies` (nothing without merging): with --vcm-light-paths 0 (automatic) the
// pilot's light subpaths count the mergeable vertices per subpath (light_paths_per_pixel); with
// merging at the first non-delta vertex, the pilot grows to an iteration's light subpaths, whose
// density the pixels' radii are set for (pixel_radii).
MergingPlan plan_merging(const Prepared& P, const ProgressiveOptions& o, const Strategies& strategies);

}  // namespace phos::integrators::vcm
