// Image textures for the text formats: decode, check, wrap as scene::Texture.
#include "io/text/image_texture.h"

#include <memory>

#include "core/error.h"
#include "io/image/image_io.h"

namespace phos::io::text {

scene::Texture read_image_texture(const std::string& path) {
    Image img = read_image(path, /*srgb=*/true);
    if (img.width <= 0 || img.height <= 0) throw InputError("the image is empty");
    scene::Texture tex;
    tex.kind = scene::Texture::Kind::Image;
    tex.image = to_texture_image(std::move(img));
    tex.filename = path;
    return tex;
}

std::shared_ptr<scene::TextureImage> to_texture_image(Image img) {
    auto image = std::make_shared<scene::TextureImage>();
    image->width = img.width;
    image->height = img.height;
    image->texels = std::move(img.pixels);
    return image;
}

}  // namespace phos::io::text
