// Texture evaluation for shading: scene/texture_eval.h (the scene layer holds it so that loaders
// can evaluate textures too, e.g. pbrt's mesh displacement) under the shading layer's names.
#pragma once

#include "scene/texture_eval.h"

namespace phos::shading {

using scene::eval_texture;
using scene::lookup_bilinear;
using scene::TextureContext;

}  // namespace phos::shading
