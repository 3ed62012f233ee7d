// pbrt-v4's mix material resolved at a point (see material_mix.h).
#include "scene/material_mix.h"

#include <algorithm>
#include <bit>
#include <cstdint>

#include "core/rng.h"
#include "scene/texture_eval.h"

namespace phos::scene {

int resolve_material(const Scene& scene, int material, Vec3 p, Vec2 uv) {
    // The loader only mixes materials defined before the mix, so the chain ends; the bound keeps a
    // hand-built cycle from looping.
    for (size_t depth = 0; depth <= scene.materials.size(); ++depth) {
        if (material < 0 || size_t(material) >= scene.materials.size()) return material;
        const Material& m = scene.materials[size_t(material)];
        if (!m.is_mix()) return material;
        float amount = m.mix_amount;
        if (m.mix_amount_texture >= 0)
            amount *=
                eval_texture(scene, m.mix_amount_texture, TextureContext{uv, p, {0, 0, 1}, {}}).average();
        if (!(amount > 0)) {
            material = m.mix_a;
            continue;
        }
        if (amount >= 1) {
            material = m.mix_b;
            continue;
        }
        uint64_t h = hash_combine(std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y));
        h = hash_combine(h, std::bit_cast<uint32_t>(p.z));
        h = hash_combine(h, (uint64_t(uint32_t(m.mix_a)) << 32) | uint32_t(m.mix_b));
        material = amount < bits_to_unit_float(uint32_t(h >> 32)) ? m.mix_a : m.mix_b;
    }
    return material;
}

bool has_mix_materials(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [](const Material& m) { return m.is_mix(); });
}

}  // namespace phos::scene
