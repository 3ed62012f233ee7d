// The front door for scene files: picks the loader by extension (.scn, .pbrt, .scene).
#pragma once

#include <string>

#include "scene/scene.h"

namespace phos::io {

struct LoadOptions {
    bool raw_materials = false;       // .scn: keep kd + ks + kt > 1 as written (default: scaled to 1)
    bool legacy_attenuation = false;  // .scn: keep (ca, la, qa) attenuation without warning
    bool strict = false;              // pbrt: unused parameters are errors
    bool no_default_lights = false;   // .scn: no default lights for a scene without lights
    bool emission_lights = true;      // .scn: glowing surfaces are two-sided area lights
};

// Throws ParseError / InputError on malformed or missing files.
scene::Scene load_scene(const std::string& path, const LoadOptions& options = {});

}  // namespace phos::io
