// The dissertation's scene format: a `.scene` file listing objects, camera and lights, `.mesh`
// files naming a PLY mesh, a material and transforms, and `.mat` materials (docs/formats/scene.md).
#pragma once

#include <string>

#include "scene/scene.h"

namespace phos::io {

// Reads `path` and every file it names. Throws ParseError (file:line:col naming the `.scene`,
// `.mesh`, `.mat` or PLY file at fault) or InputError.
scene::Scene load_scene_format(const std::string& path);

}  // namespace phos::io
