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

St2Derivatives map_2d_derivatives(const Texture& t, const TextureContext& ctx) {
    St2Derivatives d;
    if (t.mapping == Texture::Mapping::UV) {
        d.dsdx = t.u_scale * ctx.dudx;
        d.dsdy = t.u_scale * ctx.dudy;
        d.dtdx = t.v_scale * ctx.dvdx;
        d.dtdy = t.v_scale * ctx.dvdy;
        return d;
    }
    const Vec3 p = t.texture_from_world.point(ctx.p);
    const Vec3 dpdx = t.texture_from_world.vector(ctx.dpdx), dpdy = t.texture_from_world.vector(ctx.dpdy);
    Vec3 dsdp, dtdp;
    switch (t.mapping) {
        case Texture::Mapping::Spherical: {
            // s = theta / pi, t = phi / 2pi (map_2d), differentiated (PBR 4th ed., sec. 10.2.2).
            const float x2y2 = p.x * p.x + p.y * p.y, r_xy = std::sqrt(x2y2);
            dsdp = Vec3(p.x * p.z / r_xy, p.y * p.z / r_xy, -r_xy) / (kPi * (x2y2 + p.z * p.z));
            dtdp = Vec3(-p.y, p.x, 0) / (2 * kPi * x2y2);
            break;
        }
        case Texture::Mapping::Cylindrical:
            dsdp = Vec3(-p.y, p.x, 0) / (2 * kPi * (p.x * p.x + p.y * p.y));
            dtdp = Vec3(0, 0, 1);
            break;
        default:  // Planar
            dsdp = t.planar_s;
            dtdp = t.planar_t;
            break;
    }
    d.dsdx = dot(dsdp, dpdx);
    d.dsdy = dot(dsdp, dpdy);
    d.dtdx = dot(dtdp, dpdx);
    d.dtdy = dot(dtdp, dpdy);
    // On the axis (spherical, cylindrical) the gradients are infinite: a point lookup there.
    if (!std::isfinite(d.dsdx) || !std::isfinite(d.dsdy) || !std::isfinite(d.dtdx) || !std::isfinite(d.dtdy))
        d = St2Derivatives{};
    return d;
}

}  // namespace phos::scene
