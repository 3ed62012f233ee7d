// Loader for pbrt-v4 scene files (the subset research scenes use; see docs/formats/pbrt.md):
// reads a file and everything it includes into a scene::Scene.
#pragma once

#include <string>

#include "scene/scene.h"

namespace phos::io {

struct PbrtOptions {
    // A parameter that nothing reads is an error instead of a warning.
    bool strict = false;
};

// Throws ParseError (file:line:col of the offending token) on malformed input.
scene::Scene load_pbrt(const std::string& path, const PbrtOptions& options = {});

}  // namespace phos::io
