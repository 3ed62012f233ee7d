// An image texture's MIP map (Williams 1983) and its filtered lookups, as pbrt-v4's MIPMap defines
// them (PBR 4th ed., sec. 10.4.3): point, bilinear and trilinear lookups at the level the
// footprint selects, and elliptically weighted averaging (EWA, Heckbert 1989; Greene and Heckbert
// 1986) over the ellipse of the two screen-space derivatives of (s, t).
#pragma once

#include <vector>

#include "core/vec.h"
#include "scene/texture.h"

namespace phos::scene {

class MipMap {
public:
    // The pyramid of `image` with the texture's wrap mode (pbrt-v4's Image::GeneratePyramid):
    // an image whose sides are not both powers of two is first resampled up to the next powers of
    // two with pbrt-v4's separable windowed sinc (Lanczos, radius 2, tau 2: four taps per pixel,
    // texels outside the image per `wrap`, negative results clamped to 0); each further level is
    // the 2x2 box average of the one below (a side that is already 1 stays 1), down to 1 x 1.
    // Level 0 is the finest. An empty image gives an empty pyramid (levels() == 0).
    MipMap(const TextureImage& image, Texture::Wrap wrap);

    int levels() const { return int(levels_.size()); }
    const TextureImage& level(int i) const { return levels_[size_t(i)]; }
    Texture::Wrap wrap() const { return wrap_; }

    // The filtered value at (s, t) (image coordinates: (0, 0) the top-left corner of the image,
    // (1, 1) the bottom-right) for a footprint spanned by the derivatives dst0 and dst1 of (s, t)
    // along the image's x and y (pbrt-v4's MIPMap::Filter):
    //  - Point, Bilinear, Trilinear: width = 2 max(|dst0|, |dst1| componentwise) selects the
    //    continuous level l = levels - 1 + log2(width); at or beyond the top level the 1 x 1 texel;
    //    else, with i = max(0, floor(l)): Point the nearest texel of level i, Bilinear the bilinear
    //    lookup in level i, Trilinear the linear blend in l of levels i and i + 1 (level 0 alone
    //    when i = 0).
    //  - Ewa: the longer axis is clamped to max_anisotropy times the shorter one by lengthening the
    //    shorter; a zero shorter axis gives the bilinear lookup in level 0; else the level
    //    l = max(0, levels - 1 + log2(shorter)) and the linear blend in l of the EWA averages of
    //    levels floor(l) and floor(l) + 1 (ewa()).
    // Non-finite (s, t) give black; non-finite derivatives count as zero.
    Rgb filter(Texture::Filter f, Vec2 st, Vec2 dst0, Vec2 dst1, float max_anisotropy) const;

    // Lookups in one level: the texel (x, y) with the wrap mode; the bilinear lookup at (s, t);
    // the EWA average at (s, t) over the ellipse of dst0, dst1 (in level texels, each axis' length
    // grown by 1 so that it covers at least a texel): the texels whose squared radius r2 < 1
    // weighted by the Gaussian exp(-2 r2) - exp(-2), tabulated at 128 values of r2 as pbrt-v4
    // does. A level beyond the top gives the top's texel.
    Rgb texel(int level, int x, int y) const;
    Rgb bilerp(int level, Vec2 st) const;
    Rgb ewa(int level, Vec2 st, Vec2 dst0, Vec2 dst1) const;

private:
    std::vector<TextureImage> levels_;
    Texture::Wrap wrap_;
};

// pbrt-v4's resampling of an image up to a larger resolution (Image::FloatResizeUp), exposed for
// tests: new_width >= image.width and new_height >= image.height.
TextureImage resample_up(const TextureImage& image, int new_width, int new_height, Texture::Wrap wrap);

}  // namespace phos::scene
