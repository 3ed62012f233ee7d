// Where a texture is evaluated (TextureContext) and pbrt-v4's texture mappings: the (s, t) of a
// 2D texture from the surface uv or from the point in texture space (spherical, cylindrical,
// planar), and the texture-space point of a 3D texture.
#pragma once

#include "core/vec.h"
#include "scene/texture.h"

namespace phos::scene {

// A texture lookup's surface point, as pbrt-v4's TextureEvalContext carries it. The screen-space
// derivatives (how p and uv change from one pixel to the next along the image's x and y) are what
// filtered image textures (Texture::Filter other than Bilinear) read; zero means a point lookup
// (the finest MIP level). shading/texture_context.h fills them from the camera footprint.
struct TextureContext {
    Vec2 uv;  // the surface parameterisation
    Vec3 p;   // world-space point
    // The surface normal directionmix compares with its direction (pbrt-v4 passes the
    // interaction's geometric normal, oriented like the shading normal; only |n . dir| is used).
    Vec3 n{0, 0, 1};
    Vec3 wo;                            // outgoing direction (world space); no pbrt texture reads it
    Vec3 dpdx{0, 0, 0}, dpdy{0, 0, 0};  // world space
    float dudx = 0, dudy = 0, dvdx = 0, dvdy = 0;
};

// A 2D texture's screen-space derivatives of (s, t) (pbrt-v4's TexCoord2D differentials): uv:
// (su dudx, sv dvdx) and likewise in y; spherical, cylindrical and planar: the gradients of s and
// t with respect to the texture-space point applied to dpdx and dpdy taken to texture space.
struct St2Derivatives {
    float dsdx = 0, dsdy = 0, dtdx = 0, dtdy = 0;
};
St2Derivatives map_2d_derivatives(const Texture& texture, const TextureContext& ctx);

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
