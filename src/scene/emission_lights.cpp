// Conversion of glowing shapes into area lights (see emission_lights.h).
#include "scene/emission_lights.h"

#include <map>

namespace phos::scene {

int emissive_shapes_to_lights(Scene& scene, bool two_sided) {
    std::map<int, int> without_glow;  // material -> its copy with emission removed
    int added = 0;
    const size_t n = scene.shapes.size();
    for (size_t i = 0; i < n; ++i) {
        Shape& shape = scene.shapes[i];
        if (shape.area_light >= 0 || shape.material < 0 || size_t(shape.material) >= scene.materials.size())
            continue;
        const Rgb e = scene.materials[size_t(shape.material)].emission;
        if (e.is_black()) continue;
        auto it = without_glow.find(shape.material);
        if (it == without_glow.end()) {
            Material m = scene.materials[size_t(shape.material)];
            m.emission = Rgb(0.0f);
            m.name += " (emission as light)";
            scene.materials.push_back(m);
            it = without_glow.emplace(shape.material, int(scene.materials.size()) - 1).first;
        }
        shape.material = it->second;
        Light light;
        light.kind = Light::Kind::Area;
        light.color = e;
        light.two_sided = two_sided;
        light.shape = int(i);
        shape.area_light = int(scene.lights.size());
        scene.lights.push_back(light);
        ++added;
    }
    return added;
}

}  // namespace phos::scene
