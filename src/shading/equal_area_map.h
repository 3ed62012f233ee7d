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
    // count as 0.
    EqualAreaMap(std::vector<Rgb> texels, int n);

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

private:
    int n_ = 0;
    std::vector<Rgb> texels_;
    Distribution2D distribution_;
    Rgb mean_{0.0f};
};

}  // namespace phos::shading
