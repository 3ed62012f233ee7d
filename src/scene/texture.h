// Textures as plain data: constant, image map, checkerboard and scale, referenced by index.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/vec.h"

namespace phos::scene {

// Decoded texels in linear RGB, row 0 at the top of the image.
struct TextureImage {
    int width = 0;
    int height = 0;
    std::vector<Rgb> texels;
    const Rgb& at(int x, int y) const { return texels[size_t(y) * size_t(width) + size_t(x)]; }
};

struct Texture {
    enum class Kind { Constant, Image, Checkerboard, Scale };
    enum class Wrap { Repeat, Clamp, Black };
    Kind kind = Kind::Constant;
    Rgb value{1.0f};                            // Constant; also the multiplier for Image
    std::shared_ptr<const TextureImage> image;  // Image
    std::string filename;                       // Image (for messages)
    Wrap wrap = Wrap::Repeat;
    float u_scale = 1, v_scale = 1, u_offset = 0, v_offset = 0;  // uv mapping
    bool invert_v = false;
    int tex1 = -1, tex2 = -1;  // Checkerboard: the two textures; Scale: tex1 * (tex2 or value)
    Rgb value2{0.0f};          // Checkerboard second value when tex2 < 0
};

}  // namespace phos::scene
