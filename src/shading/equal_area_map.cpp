// Equal-area map: nearest-pixel lookups and the pixel distribution. Equal area means the Jacobian
// from the unit square to the sphere is the constant 4 pi, so a density pdf_uv over the square is
// pdf_uv / (4 pi) per steradian (pbrt-v4, ImageInfiniteLight::PDF_Li).
#include "shading/equal_area_map.h"

#include <algorithm>
#include <cmath>

#include "core/equal_area.h"

namespace phos::shading {

EqualAreaMap::EqualAreaMap(std::vector<Rgb> texels, int n, Vec3 hemisphere)
    : n_(n), texels_(std::move(texels)) {
    std::vector<float> weights(texels_.size());
    double sum[3] = {0, 0, 0}, half[3] = {0, 0, 0};
    const bool restricted = length_squared(hemisphere) > 0;
    // The sine of a pixel's angular size, generously: a great circle that crosses a pixel passes
    // within this of one of the 3 x 3 points.
    const float margin = std::min(1.0f, 2 * std::sqrt(4 * kPi / float(n_ * n_)));
    for (int y = 0; y < n_; ++y)
        for (int x = 0; x < n_; ++x) {
            const size_t k = size_t(y) * size_t(n_) + size_t(x);
            Rgb& c = texels_[k];
            for (int ch = 0; ch < 3; ++ch) c[ch] = std::isfinite(c[ch]) ? std::max(c[ch], 0.0f) : 0.0f;
            for (int ch = 0; ch < 3; ++ch) sum[ch] += c[ch];
            weights[k] = c.average();
            if (!restricted) continue;
            float nearest = -1;
            int inside = 0;
            for (int j = 0; j < 3; ++j)
                for (int i = 0; i < 3; ++i) {
                    const Vec3 w = equal_area_square_to_sphere(
                        {(float(x) + 0.5f * float(i)) / float(n_), (float(y) + 0.5f * float(j)) / float(n_)});
                    const float d = dot(normalize(w), hemisphere);
                    nearest = std::max(nearest, d);
                    inside += d > 0;
                }
            if (nearest <= -margin) weights[k] = 0;
            for (int ch = 0; ch < 3; ++ch) half[ch] += c[ch] * double(inside) / 9;
        }
    const double count = double(std::max<size_t>(texels_.size(), 1));
    mean_ = Rgb(float(sum[0] / count), float(sum[1] / count), float(sum[2] / count));
    if (!restricted)
        hemisphere_integral_ = mean_ * (4 * kPi);
    else
        hemisphere_integral_ =
            Rgb(float(half[0] / count), float(half[1] / count), float(half[2] / count)) * (4 * kPi);
    distribution_ = Distribution2D(weights, n_, n_);
}

Rgb EqualAreaMap::texel_wrapped(int x, int y) const {
    wrap_octahedral(x, y, n_);
    return texel(x, y);
}

Rgb EqualAreaMap::lookup(Vec3 w) const {
    // A direction on the square's outer edge (u or v = 1) takes the last pixel, as pdf() does: the
    // wrap would give the folded pixel, whose texel is the same direction's other image.
    const Vec2 uv = equal_area_sphere_to_square(w);
    return texel(std::min(int(uv.x * float(n_)), n_ - 1), std::min(int(uv.y * float(n_)), n_ - 1));
}

Vec3 EqualAreaMap::sample(Vec2 u, float* pdf) const {
    float pdf_uv = 0;
    const Vec2 uv = distribution_.sample(u, &pdf_uv);
    *pdf = pdf_uv / (4 * kPi);
    return normalize(equal_area_square_to_sphere(uv));
}

float EqualAreaMap::pdf(Vec3 w) const {
    const Vec2 uv = equal_area_sphere_to_square(w);
    // u or v = 1 exactly lies on the map's last pixel (the distribution's cells are half-open).
    const float below_one = std::nextafter(1.0f, 0.0f);
    return distribution_.pdf({std::min(uv.x, below_one), std::min(uv.y, below_one)}) / (4 * kPi);
}

}  // namespace phos::shading
