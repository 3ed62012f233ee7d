// Entry point of the `.scn` loader: runs the parser over the top-level file, adds the seed's default
// lights to a scene without light commands, and makes glowing surfaces area lights. (A scene without
// lights is reported once, for every format, by `phos render`.)
#include "io/scn/scn_loader.h"

#include "core/log.h"
#include "io/scn/scn_parser.h"
#include "scene/emission_lights.h"

namespace phos::io {

scene::Scene load_scn(const std::string& path, const ScnOptions& options) {
    scene::Scene scene;
    scene.source = path;
    scn::Parser parser(scene, options);
    parser.parse_top(path);
    if (scene.lights.empty() && !options.no_default_lights) {
        // The seed's scene reader lights a scene that has no light with these two.
        const struct {
            Vec3 direction;
            float e;
        } defaults[2] = {{Vec3(-3, -4, -5), 1.0f}, {Vec3(3, 2, 3), 0.5f}};
        for (const auto& d : defaults) {
            scene::Light l;
            l.kind = scene::Light::Kind::Directional;
            l.color = Rgb(d.e);
            l.direction = normalize(d.direction);
            scene.lights.push_back(l);
        }
        log::warn(
            path +
            ": the scene has no light commands; added the seed renderer's two default directional lights "
            "(irradiance 1 along (-3,-4,-5), 0.5 along (3,2,3)); --no-default-lights refuses them");
    }
    // After the default lights: as in the seed, only light commands keep those away.
    if (options.emission_lights) scene::emissive_shapes_to_lights(scene, /*two_sided=*/true);
    return scene;
}

}  // namespace phos::io
