// Evaluation of scene::Texture at a surface point's uv (shading at hits, the pbrt loader at mesh
// vertices for displacement): constant, image (bilinear, wrap modes),
// checkerboard and scale textures, with each texture's uv scale/offset mapping.
#pragma once

#include "core/vec.h"
#include "scene/scene.h"

namespace phos::scene {

// Value of texture `texture` (an index into scene.textures) at `uv`. An index of -1 means "no
// texture" and gives white, so callers can multiply unconditionally; an index out of range also
// gives white (loaders validate indices, this only keeps a bad scene from crashing).
//
// uv convention: (u, v) = (0, 0) is the bottom-left corner of an image and (1, 1) its top-right
// (v grows upwards, as in OBJ and pbrt); `invert_v` puts v = 0 at the top row instead. Texel
// centres sit at half-integer positions and lookups interpolate bilinearly between the four
// nearest texels, wrapping per Texture::wrap (Repeat tiles, Clamp extends the edge texels, Black
// treats texels outside the image as black). The mapping applied first is
// (u, v) -> (u * u_scale + u_offset, v * v_scale + v_offset).
Rgb eval_texture(const Scene& scene, int texture, Vec2 uv);

// Bilinear lookup of an image at continuous texel coordinates (x, y) in [0, width] x [0, height]
// (row 0 at the top), with the given wrap mode. Exposed for tests.
Rgb lookup_bilinear(const TextureImage& image, float x, float y, Texture::Wrap wrap);

}  // namespace phos::scene
