// Entry point of the `.scn` loader: runs the parser over the top-level file, then checks the scene
// as a whole (a scene without lights renders black, which deserves a warning).
#include "io/scn/scn_loader.h"

#include "core/log.h"
#include "io/scn/scn_parser.h"

namespace phos::io {

scene::Scene load_scn(const std::string& path, const ScnOptions& options) {
    scene::Scene scene;
    scene.source = path;
    scn::Parser parser(scene, options);
    parser.parse_top(path);
    if (scene.lights.empty())
        log::warn(path +
                  ": the scene has no lights; the image will be black except for emission (e) "
                  "and the background");
    return scene;
}

}  // namespace phos::io
