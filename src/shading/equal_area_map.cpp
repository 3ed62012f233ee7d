// Equal-area map: nearest-pixel lookups and the pixel distribution. Equal area means the Jacobian
// from the unit square to the sphere is the constant 4 pi, so a density pdf_uv over the square is
// pdf_uv / (4 pi) per steradian (pbrt-v4, ImageInfiniteLight::PDF_Li).
#include "shading/equal_area_map.h"

#include <algorithm>
#include <cmath>

#include "core/equal_area.h"

namespace phos::shading {

EqualAreaMap::EqualAreaMap(std::vector<Rgb> texels, int n) : n_(n), texels_(std::move(texels)) {
    std::vector<float> weights(texels_.size());
    double sum[3] = {0, 0, 0};
    for (size_t k = 0; k < texels_.size(); ++k) {
        Rgb& c = texels_[k];
        for (int ch = 0; ch < 3; ++ch) c[ch] = std::isfinite(c[ch]) ? std::max(c[ch], 0.0f) : 0.0f;
        weights[k] = c.average();
        for (int ch = 0; ch < 3; ++ch) sum[ch] += c[ch];
    }
    const double count = double(std::max<size_t>(texels_.size(), 1));
    mean_ = Rgb(float(sum[0] / count), float(sum[1] / count), float(sum[2] / count));
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
