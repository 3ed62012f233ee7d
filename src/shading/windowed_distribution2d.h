// Piecewise-constant 2D distribution on [0,1]^2 over an nu x nv grid that can be sampled restricted
// to any axis-aligned window (pbrt-v4's WindowedPiecewiseConstant2D; Bitterli et al. 2015): what
// the portal light samples, the window being the part of its image seen through the portal from the
// reference point. A summed-area table (Crow 1984) gives the integral over any window in O(1) (the
// integral of a piecewise-constant function from the origin is bilinear inside each cell), so the
// marginal in u over the window and the conditional in v inside the chosen column are inverted
// exactly: a binary search over cell edges, then the linear piece inside the cell.
#pragma once

#include <optional>
#include <vector>

#include "core/vec.h"

namespace phos::shading {

// The window [lo, hi] (lo <= hi componentwise, inside [0,1]^2).
struct UvWindow {
    Vec2 lo, hi;
    bool contains(Vec2 p) const { return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y; }
};

class WindowedDistribution2D {
public:
    WindowedDistribution2D() = default;
    // `f` holds nu * nv non-negative values, row-major: f[v * nu + u] (non-finite and negative: 0).
    WindowedDistribution2D(const std::vector<float>& f, int nu, int nv);

    int nu() const { return nu_; }
    int nv() const { return nv_; }
    // Integral of f (as a function on [0,1]^2) over the window.
    double integral(const UvWindow& w) const;
    // A point of the window with density f(cell) / integral(window) (nullopt when that is 0).
    std::optional<Vec2> sample(Vec2 u, const UvWindow& window, float* pdf) const;
    // The density sample() has at p (0 outside the window or when the window's integral is 0).
    float pdf(Vec2 p, const UvWindow& window) const;
    float value(Vec2 p) const;

private:
    // Integral of f over [0, x] x [0, y] (the summed-area table, bilinear within a cell).
    double cumulative(double x, double y) const;
    double table(int i, int j) const { return sat_[size_t(j) * size_t(nu_ + 1) + size_t(i)]; }

    int nu_ = 0, nv_ = 0;
    std::vector<float> f_;
    std::vector<double> sat_;  // (nu + 1) x (nv + 1): sum of cells below i, j, each of area 1/(nu nv)
};

}  // namespace phos::shading
