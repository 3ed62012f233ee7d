// Where a texture is evaluated (TextureContext) and pbrt-v4's texture mappings: the (s, t) of a
// 2D texture from the surface uv or from the point in texture space (spherical, cylindrical,
// planar), and the texture-space point of a 3D texture.
#pragma once

#include "core/vec.h"
#include "scene/texture.h"

namespace phos::scene {

// A texture lookup's surface point, as pbrt-v4's TextureEvalContext carries it (without the
// screen-space differentials: phos evaluates textures at a point, unfiltered).
struct TextureContext {
    Vec2 uv;  // the surface parameterisation
    Vec3 p;   // world-space point
    // The surface normal directionmix compares with its direction (pbrt-v4 passes the
    // interaction's geometric normal, oriented like the shading normal; only |n . dir| is used).
    Vec3 n{0, 0, 1};
    Vec3 wo;  // outgoing direction (world space); no pbrt texture reads it
};

// A 2D texture's (s, t) (PBRT 4th ed., section 10.2): uv: (u su + du, v sv + dv); in texture
// space p' = texture_from_world(p), spherical: (theta / pi, phi / 2pi) of the direction of p'
// (theta from +z, phi from +x towards +y in [0, 2pi)); cylindrical: ((pi + atan2(y', x')) / 2pi,
// z'); planar: (du + p'.v1, dv + p'.v2). A point at the texture-space origin maps to (0, 0)
// spherically.
Vec2 map_2d(const Texture& texture, const TextureContext& ctx);

// A 3D texture's point: the hit point in texture space.
inline Vec3 map_3d(const Texture& texture, const TextureContext& ctx) {
    return texture.texture_from_world.point(ctx.p);
}

}  // namespace phos::scene
