// Entry point of the `.scn` loader: runs the parser over the top-level file. (A scene without
// lights is reported once, for every format, by `phos render`.)
#include "io/scn/scn_loader.h"

#include "io/scn/scn_parser.h"

namespace phos::io {

scene::Scene load_scn(const std::string& path, const ScnOptions& options) {
    scene::Scene scene;
    scene.source = path;
    scn::Parser parser(scene, options);
    parser.parse_top(path);
    return scene;
}

}  // namespace phos::io
