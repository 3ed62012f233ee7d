// Alpha cut-outs: a shape's alpha at a uv and the per-ray decision (see alpha_mask.h).
#include "accel/alpha_mask.h"

#include <algorithm>
#include <bit>

#include "core/rng.h"
#include "scene/texture_eval.h"

namespace phos::accel {

float alpha_at(const scene::Scene& scene, const scene::Shape& shape, Vec2 uv) {
    const float a = shape.alpha_texture >= 0 ? scene::eval_texture(scene, shape.alpha_texture, uv).average()
                                             : shape.alpha;
    return a >= 0 ? std::min(a, 1.0f) : 0.0f;  // (NaN counts as 0)
}

float alpha_hash(Vec3 origin, Vec3 dir, uint64_t salt) {
    const auto pair = [](float a, float b) {
        return (uint64_t(std::bit_cast<uint32_t>(a)) << 32) | std::bit_cast<uint32_t>(b);
    };
    uint64_t h = mix64(salt + 0x51ed270b27cd3a5bULL);
    h = hash_combine(h, pair(origin.x, origin.y));
    h = hash_combine(h, pair(origin.z, dir.x));
    h = hash_combine(h, pair(dir.y, dir.z));
    return bits_to_unit_float(uint32_t(h >> 32));
}

bool alpha_keeps(const scene::Scene& scene, const scene::Shape& shape, Vec2 uv, Vec3 origin, Vec3 dir,
                 uint64_t salt) {
    const float a = alpha_at(scene, shape, uv);
    if (a >= 1) return true;
    if (a <= 0) return false;
    return alpha_hash(origin, dir, salt) < a;
}

}  // namespace phos::accel
