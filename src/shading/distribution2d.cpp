// Piecewise-constant 2D distribution: sample the row from the marginal, then the column from that
// row's conditional; the density is the product of the two continuous densities.
#include "shading/distribution2d.h"

#include <algorithm>

namespace phos::shading {

Distribution2D::Distribution2D(const std::vector<float>& f, int nu, int nv) : nu_(nu), nv_(nv) {
    rows_.reserve(size_t(nv));
    std::vector<float> row_sums(static_cast<size_t>(nv), 0.0f);
    for (int v = 0; v < nv; ++v) {
        std::vector<float> row(f.begin() + ptrdiff_t(v) * nu, f.begin() + ptrdiff_t(v + 1) * nu);
        rows_.emplace_back(row);
        row_sums[size_t(v)] = float(rows_.back().total());
    }
    marginal_ = Distribution1D(row_sums);
}

Vec2 Distribution2D::sample(Vec2 u, float* pdf) const {
    float pdf_v = 0, pdf_u = 0;
    size_t row = 0;
    const float v = marginal_.sample_continuous(u.y, &pdf_v, &row);
    const float x = rows_[row].sample_continuous(u.x, &pdf_u);
    if (pdf) *pdf = pdf_v * pdf_u;
    return {x, v};
}

float Distribution2D::pdf(Vec2 uv) const {
    if (nu_ == 0 || nv_ == 0 || !(uv.y >= 0) || !(uv.y < 1)) return 0;
    const size_t row = std::min(size_t(uv.y * float(nv_)), size_t(nv_ - 1));
    return marginal_.pdf_continuous(uv.y) * rows_[row].pdf_continuous(uv.x);
}

}  // namespace phos::shading
