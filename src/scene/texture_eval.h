// Evaluation of scene::Texture at a surface point (shading at hits, the pbrt loader at mesh
// vertices for displacement), as pbrt-v4 evaluates each kind at a point; image textures with a
// Point, Trilinear or Ewa filter are filtered over the context's screen-space footprint.
#pragma once

#include "core/vec.h"
#include "scene/scene.h"
#include "scene/texture_mapping.h"

namespace phos::scene {

// Value of texture `texture` (an index into scene.textures) at the surface point `ctx`. An index
// of -1 means "no texture" and gives white, so callers can multiply unconditionally; an index
// out of range also gives white (loaders validate indices, this only keeps a bad scene from
// crashing). A float texture's value is grey. With (s, t) from the texture's 2D mapping
// (texture_mapping.h) and p its texture-space point:
//   Constant: value. Image: value x the bilinear lookup below at (s, t) (Filter::Bilinear, the
//   default), or with another filter value x MipMap::filter at (s, t) in image coordinates over
//   the derivatives of (s, t) (map_2d_derivatives). Scale: tex1 x (tex2 or
//   value). Mix: (1 - a) tex1 + a tex2, a the mean of the amount texture (or amount_value).
//   DirectionMix: c tex1 + (1 - c) tex2 with c = |n . direction|. Bilerp: the bilinear blend of
//   the corners at (s, t) (extrapolating outside the unit square, as pbrt does). Checkerboard:
//   tex1 where checker_odd is false, tex2 where true, of (s, t) or of p by dimension. Dots: tex1
//   inside a polka dot of (s, t), tex2 outside. FBm: fbm(p, roughness, octaves). Wrinkled:
//   turbulence(p, roughness, octaves). Windy: windy(p). Marble: marble(p, marble_scale,
//   variation, roughness, octaves) (procedural_textures.h, perlin_noise.h).
// A texture that refers to itself (a malformed cycle) gives white beyond 32 levels.
Rgb eval_texture(const Scene& scene, int texture, const TextureContext& ctx);

// The same at a uv alone (p = 0, n = +z, no footprint): for loaders at mesh vertices, alpha masks
// and area lights (pbrt-v4 evaluates alpha without differentials too). A 3D or spherical,
// cylindrical or planar texture sees the texture-space image of the origin.
Rgb eval_texture(const Scene& scene, int texture, Vec2 uv);

// True when a texture of `scene` reads the screen-space footprint (an image texture with a Point,
// Trilinear or Ewa filter): renderers compute TextureContext's derivatives only then.
bool reads_footprint(const Scene& scene);

// Image convention: (s, t) = (0, 0) is the bottom-left corner of an image and (1, 1) its
// top-right (t grows upwards, as in OBJ and pbrt); `invert_v` puts t = 0 at the top row instead.
// Texel centres sit at half-integer positions and lookups interpolate bilinearly between the four
// nearest texels, wrapping per Texture::wrap (Repeat tiles, Clamp extends the edge texels, Black
// treats texels outside the image as black).

// An integer texel index mapped inside [0, n) per wrap mode; -1 for a texel that Black makes black.
int wrap_index(int i, int n, Texture::Wrap wrap);
// Bilinear lookup of an image at continuous texel coordinates (x, y) in [0, width] x [0, height]
// (row 0 at the top), with the given wrap mode. Exposed for tests.
Rgb lookup_bilinear(const TextureImage& image, float x, float y, Texture::Wrap wrap);

}  // namespace phos::scene
