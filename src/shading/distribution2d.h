// Piecewise-constant 2D distribution on [0,1)^2 over an nu x nv grid (a marginal over rows v and
// one conditional per row over columns u), for importance-sampling environment maps.
#pragma once

#include <vector>

#include "core/vec.h"
#include "shading/distribution1d.h"

namespace phos::shading {

class Distribution2D {
public:
    Distribution2D() = default;
    // `f` holds nu * nv non-negative values, row-major: f[v * nu + u].
    Distribution2D(const std::vector<float>& f, int nu, int nv);

    int nu() const { return nu_; }
    int nv() const { return nv_; }
    // A point of [0,1)^2 distributed with density pdf(uv) = f(cell) / mean(f).
    Vec2 sample(Vec2 u, float* pdf = nullptr) const;
    float pdf(Vec2 uv) const;

private:
    int nu_ = 0, nv_ = 0;
    std::vector<Distribution1D> rows_;  // conditional p(u | v) per row
    Distribution1D marginal_;           // p(v)
};

}  // namespace phos::shading
