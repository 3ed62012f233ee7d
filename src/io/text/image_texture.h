// An image file (PNG, JPEG, EXR, PFM, ...) read as an image texture for the text formats' materials.
#pragma once

#include <memory>
#include <string>

#include "core/image.h"
#include "scene/texture.h"

namespace phos::io::text {

// Reads `path` (8-bit formats decoded from sRGB to linear). Throws what the image readers throw
// (InputError, ParseError, a decoder's exception), and InputError for an empty image; callers add
// the location of the file name in their own file.
scene::Texture read_image_texture(const std::string& path);

// Decoded pixels as texels (row 0 at the top), for every reader that builds image textures.
std::shared_ptr<scene::TextureImage> to_texture_image(Image img);

}  // namespace phos::io::text
