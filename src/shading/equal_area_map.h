// A square RGB image over the sphere of directions in pbrt-v4's equal-area octahedral layout
// (core/equal_area.h): what pbrt-v4's image infinite light and goniometric light hold. Lookups
// take the nearest pixel (pbrt-v4's LookupNearest with the octahedral-sphere wrap), so the radiance
// is piecewise constant over pixels of equal solid angle 4 pi / N^2; directions are sampled from a
// piecewise-constant 2D distribution over the pixels by their channel average (pbrt-v4's
// Image::GetSamplingDistribution), which makes the solid-angle pdf pdf_uv / (4 pi).
#pragma once

#include <vector>

#include "core/vec.h"
#include "shading/distribution2d.h"

namespace phos::shading {

class EqualAreaMap {
public:
    EqualAreaMap() = default;
    // `texels`: n x n values, row-major, row 0 at the top (v = 0). Negative and non-finite values
    // count as 0. A non-zero `hemisphere` (unit, light space) keeps sampling to the pixels that
    // reach into the hemisphere w . hemisphere > 0 (a pixel is kept when one of 3 x 3 points on it
    // lies within its own angular size of that hemisphere, which keeps every pixel the boundary
    // crosses); mean() and the density are then those of the kept pixels.
    EqualAreaMap(std::vector<Rgb> texels, int n, Vec3 hemisphere = Vec3(0.0f));

    int resolution() const { return n_; }
    bool empty() const { return n_ == 0; }
    // The pixel a light-space unit direction falls in, and its value.
    Rgb lookup(Vec3 w) const;
    const Rgb& texel(int x, int y) const { return texels_[size_t(y) * size_t(n_) + size_t(x)]; }
    // A texel fetched with the octahedral-sphere wrap (x, y may lie outside the image).
    Rgb texel_wrapped(int x, int y) const;
    // A light-space unit direction with solid-angle density pdf(w) (0 when the map is all zero).
    Vec3 sample(Vec2 u, float* pdf) const;
    float pdf(Vec3 w) const;
    // The mean of the texels: the integral over the sphere is 4 pi times this.
    Rgb mean() const { return mean_; }
    // The integral over the sphere of the texels restricted to the hemisphere (4 pi mean() without
    // one), each pixel counted by the share of 3 x 3 points on it that lie in the hemisphere.
    Rgb hemisphere_integral() const { return hemisphere_integral_; }

private:
    int n_ = 0;
    std::vector<Rgb> texels_;
    Distribution2D distribution_;
    Rgb mean_{0.0f};
    Rgb hemisphere_integral_{0.0f};
};

}  // namespace phos::shading
