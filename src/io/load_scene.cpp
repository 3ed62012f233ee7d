// Scene loading by file extension.
#include "io/load_scene.h"

#include <algorithm>
#include <filesystem>

#include "core/error.h"
#include "io/pbrt/pbrt_loader.h"
#include "io/scene_format/scene_format_loader.h"
#include "io/scn/scn_loader.h"

namespace phos::io {

scene::Scene load_scene(const std::string& path, const LoadOptions& options) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    std::error_code ec;  // the non-throwing overloads: an unusable name (too long, say) is not found
    if (!std::filesystem::exists(path, ec))
        throw ParseError(path, 0, 0, "cannot open scene file: no such file");
    if (std::filesystem::is_directory(path, ec))
        throw ParseError(path, 0, 0, "is a directory, not a scene file");
    if (ext == ".scn")
        return load_scn(path, ScnOptions{.raw_materials = options.raw_materials,
                                         .no_default_lights = options.no_default_lights,
                                         .legacy_attenuation = options.legacy_attenuation,
                                         .emission_lights = options.emission_lights});
    if (ext == ".pbrt") return load_pbrt(path, PbrtOptions{options.strict});
    if (ext == ".scene") return load_scene_format(path);
    throw ParseError(path, 0, 0, "unknown scene format '" + ext + "' (phos reads .scn, .pbrt and .scene)");
}

}  // namespace phos::io
