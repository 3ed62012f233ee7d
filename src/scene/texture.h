// Textures as plain data, referenced by index: pbrt-v4's constant, image map, scale, mix,
// directionmix, bilerp, checkerboard (2D and 3D), dots, fbm, wrinkled, windy and marble, with
// their 2D mappings (uv, spherical, cylindrical, planar) and the 3D point mapping.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/transform.h"
#include "core/vec.h"

namespace phos::scene {

class MipMap;  // scene/mip_map.h

// Decoded texels in linear RGB, row 0 at the top of the image.
struct TextureImage {
    int width = 0;
    int height = 0;
    std::vector<Rgb> texels;
    const Rgb& at(int x, int y) const { return texels[size_t(y) * size_t(width) + size_t(x)]; }
};

// A float texture is a grey Rgb; texture_eval.h defines each kind's value.
struct Texture {
    enum class Kind {
        Constant,
        Image,
        Checkerboard,
        Scale,
        Mix,           // (1 - amount) tex1 + amount tex2
        DirectionMix,  // |n . direction| tex1 + (1 - |n . direction|) tex2
        Bilerp,        // bilinear in (s, t) between the four corner values
        Dots,          // pbrt's polka dots: tex1 inside a dot, tex2 outside
        FBm,           // fractional Brownian motion of Perlin noise (3D)
        Wrinkled,      // turbulence of Perlin noise (3D)
        Windy,         // |fbm(p / 10, 1/2, 3)| * fbm(p, 1/2, 6) (3D)
        Marble,        // pbrt's marble colour spline over sin(y + variation fbm) (3D)
        UV,            // pbrt-v3's uv texture: (s - floor(s), t - floor(t), 0)
    };
    enum class Wrap { Repeat, Clamp, Black };
    // pbrt-v4's image texture filters ("string filter"). Bilinear looks the image itself up at the
    // point (no footprint); Point, Trilinear and Ewa filter the MIP map over the screen-space
    // footprint of the lookup (scene/mip_map.h, TextureContext's derivatives).
    enum class Filter { Point, Bilinear, Trilinear, Ewa };
    // How a 2D texture (Image, Checkerboard with dimension 2, Bilerp, Dots) finds (s, t): from the
    // surface uv, or from the point in texture space (see texture_from_world).
    enum class Mapping { UV, Spherical, Cylindrical, Planar };

    Kind kind = Kind::Constant;
    Rgb value{1.0f};                            // Constant; also the multiplier for Image
    std::shared_ptr<const TextureImage> image;  // Image
    std::string filename;                       // Image (for messages)
    Filter filter = Filter::Bilinear;           // Image
    float max_anisotropy = 8;                   // Image with Filter::Ewa: longest / shortest axis
    // Image with a filter other than Bilinear: the image's pyramid (with this texture's wrap),
    // shared by the textures that use the same image and wrap.
    std::shared_ptr<const MipMap> mip_map;
    Wrap wrap = Wrap::Repeat;
    Mapping mapping = Mapping::UV;
    // UV: (s, t) = (u * u_scale + u_offset, v * v_scale + v_offset). Planar: u_offset and v_offset
    // are pbrt's udelta and vdelta.
    float u_scale = 1, v_scale = 1, u_offset = 0, v_offset = 0;
    bool invert_v = false;
    // World to texture space: the inverse of pbrt's CTM at the Texture directive. Spherical,
    // cylindrical and planar mappings and the 3D textures evaluate the hit point in this space.
    Transform texture_from_world;
    Vec3 planar_s{1, 0, 0}, planar_t{0, 1, 0};  // Planar: s = u_offset + p.planar_s, t likewise
    // Checkerboard: tex1 on even cells (else value), tex2 on odd ones (else value2). Scale:
    // tex1 * (tex2 or value). Mix, DirectionMix: the two textures blended. Dots: tex1 inside a
    // dot, tex2 outside (indices of constants when pbrt's parameter was a value).
    int tex1 = -1, tex2 = -1;
    Rgb value2{0.0f};                          // Checkerboard second value when tex2 < 0
    int dimension = 2;                         // Checkerboard: 2 (s, t cells) or 3 (cells of texture space)
    int amount = -1;                           // Mix: the float texture of the amount, else:
    float amount_value = 0.5f;                 // Mix: the amount
    Vec3 direction{0, 1, 0};                   // DirectionMix: unit world-space direction
    std::array<Rgb, 4> corners{};              // Bilerp: the values at (s, t) = (0,0), (0,1), (1,0), (1,1)
    int octaves = 8;                           // FBm, Wrinkled, Marble
    float roughness = 0.5f;                    // FBm, Wrinkled, Marble: omega, each octave's weight ratio
    float marble_scale = 1, variation = 0.2f;  // Marble
};

}  // namespace phos::scene
