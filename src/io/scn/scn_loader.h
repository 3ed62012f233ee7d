// Loader for Princeton's `.scn` scene format (see docs/formats/scn.md): reads a file and the files it
// includes into a scene::Scene, with phos's physically based reading of every number.
#pragma once

#include <string>

#include "scene/scene.h"

namespace phos::io {

struct ScnOptions {
    // Keep materials whose lobes sum to more than 1 in a channel (kd + ks + kt > 1) as written,
    // creating energy; by default each such channel is scaled down to sum to 1 (what the seed's
    // `-real` flag did), with one warning per material naming its factors.
    bool raw_materials = false;
    // A scene without any light command gets the seed's two default directional lights (white,
    // travelling along (-3,-4,-5), and half as bright along (3,2,3)) with one warning; this refuses
    // them (the scene then renders black except for emission).
    bool no_default_lights = false;
    // Keep non-physical light attenuation constants silently (they are stored in Light::attenuation
    // either way; without this flag each light with constants other than 0 0 1 gets a warning).
    bool legacy_attenuation = false;
    // Glowing surfaces (material emission `e`) are two-sided area lights: they light the scene and
    // emit photons from both sides, as their glow is seen from both sides. False: the glow is only
    // seen (by camera rays and through mirrors and glass), as in the seed renderer.
    bool emission_lights = true;
};

// Reads `path` (and its includes, meshes and textures). Throws ParseError (file:line:col of the
// offending token, in the file that contains it) on any malformed input.
scene::Scene load_scn(const std::string& path, const ScnOptions& options = {});

}  // namespace phos::io
