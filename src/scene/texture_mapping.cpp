// pbrt-v4's 2D texture mappings (see texture_mapping.h).
#include "scene/texture_mapping.h"

#include <algorithm>
#include <cmath>

namespace phos::scene {

Vec2 map_2d(const Texture& t, const TextureContext& ctx) {
    switch (t.mapping) {
        case Texture::Mapping::UV:
            return {ctx.uv.x * t.u_scale + t.u_offset, ctx.uv.y * t.v_scale + t.v_offset};
        case Texture::Mapping::Spherical: {
            const Vec3 p = t.texture_from_world.point(ctx.p);
            const float len = length(p);
            if (!(len > 0)) return {0, 0};
            const Vec3 d = p / len;
            const float theta = std::acos(std::clamp(d.z, -1.0f, 1.0f));
            float phi = std::atan2(d.y, d.x);
            if (phi < 0) phi += 2 * kPi;
            return {theta * kInvPi, phi * (0.5f * kInvPi)};
        }
        case Texture::Mapping::Cylindrical: {
            const Vec3 p = t.texture_from_world.point(ctx.p);
            return {(kPi + std::atan2(p.y, p.x)) * (0.5f * kInvPi), p.z};
        }
        case Texture::Mapping::Planar: {
            const Vec3 p = t.texture_from_world.point(ctx.p);
            return {t.u_offset + dot(p, t.planar_s), t.v_offset + dot(p, t.planar_t)};
        }
    }
    return ctx.uv;
}

}  // namespace phos::scene
