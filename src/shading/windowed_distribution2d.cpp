// Windowed piecewise-constant 2D distribution (see the header). Sampling inverts the window's
// marginal cumulative in u, P(x) = I([lo.x, x] x [lo.y, hi.y]) / I(window), which is linear inside
// each column; then the conditional in v of the chosen column over [lo.y, hi.y], linear inside each
// row. The density of the point is f(cell) / I(window) (pbrt-v4's windowed PDF).
#include "shading/windowed_distribution2d.h"

#include <algorithm>
#include <cmath>

namespace phos::shading {

WindowedDistribution2D::WindowedDistribution2D(const std::vector<float>& f, int nu, int nv)
    : nu_(nu), nv_(nv), f_(f), sat_(size_t(nu + 1) * size_t(nv + 1), 0.0) {
    for (float& x : f_) x = std::isfinite(x) ? std::max(x, 0.0f) : 0.0f;
    const double cell = 1.0 / (double(nu) * double(nv));
    for (int j = 0; j < nv; ++j) {
        double row = 0;
        for (int i = 0; i < nu; ++i) {
            row += double(f_[size_t(j) * size_t(nu) + size_t(i)]) * cell;
            sat_[size_t(j + 1) * size_t(nu + 1) + size_t(i + 1)] = table(i + 1, j) + row;
        }
    }
}

double WindowedDistribution2D::cumulative(double x, double y) const {
    x = std::clamp(x, 0.0, 1.0) * nu_;
    y = std::clamp(y, 0.0, 1.0) * nv_;
    const int i = std::min(int(x), nu_ - 1), j = std::min(int(y), nv_ - 1);
    const double dx = x - i, dy = y - j;
    return (1 - dx) * (1 - dy) * table(i, j) + dx * (1 - dy) * table(i + 1, j) +
           (1 - dx) * dy * table(i, j + 1) + dx * dy * table(i + 1, j + 1);
}

double WindowedDistribution2D::integral(const UvWindow& w) const {
    if (nu_ == 0) return 0;
    return std::max(0.0, cumulative(w.hi.x, w.hi.y) - cumulative(w.lo.x, w.hi.y) -
                             cumulative(w.hi.x, w.lo.y) + cumulative(w.lo.x, w.lo.y));
}

float WindowedDistribution2D::value(Vec2 p) const {
    const int i = std::clamp(int(p.x * float(nu_)), 0, nu_ - 1),
              j = std::clamp(int(p.y * float(nv_)), 0, nv_ - 1);
    return f_[size_t(j) * size_t(nu_) + size_t(i)];
}

float WindowedDistribution2D::pdf(Vec2 p, const UvWindow& window) const {
    if (nu_ == 0 || !window.contains(p)) return 0;
    const double total = integral(window);
    return total > 0 ? float(double(value(p)) / total) : 0.0f;
}

namespace {

// Inverts a cumulative function P, non-decreasing on [a, b] and linear between the edges k / n, at
// target t in [P(a), P(b)]: a binary search over the edges inside (a, b), then linear interpolation.
template <typename P>
double invert(const P& cdf, double t, double a, double b, int n) {
    double lo = a, hi = b;
    int k_lo = int(std::floor(a * n)) + 1, k_hi = int(std::ceil(b * n)) - 1;  // the edges strictly inside
    while (k_lo <= k_hi) {
        const int mid = (k_lo + k_hi) / 2;
        const double x = double(mid) / n;
        if (cdf(x) > t) {
            hi = x;
            k_hi = mid - 1;
        } else {
            lo = x;
            k_lo = mid + 1;
        }
    }
    const double p_lo = cdf(lo), p_hi = cdf(hi);
    const double s = p_hi > p_lo ? (t - p_lo) / (p_hi - p_lo) : 0.5;
    return std::clamp(lo + std::clamp(s, 0.0, 1.0) * (hi - lo), a, b);
}

}  // namespace

std::optional<Vec2> WindowedDistribution2D::sample(Vec2 u, const UvWindow& w, float* pdf) const {
    const double total = integral(w);
    if (!(total > 0)) return std::nullopt;
    // Marginal in u: the integral over [lo.x, x] x [lo.y, hi.y].
    const auto px = [&](double x) { return integral({w.lo, {float(x), w.hi.y}}); };
    const double x = invert(px, double(u.x) * total, w.lo.x, w.hi.x, nu_);
    // Conditional in v inside the column holding x (clipped to the window's rows).
    const int col = std::clamp(int(x * nu_), 0, nu_ - 1);
    const float c0 = float(col) / float(nu_), c1 = float(col + 1) / float(nu_);
    const double column = integral({{c0, w.lo.y}, {c1, w.hi.y}});
    if (!(column > 0)) return std::nullopt;
    const auto py = [&](double y) { return integral({{c0, w.lo.y}, {c1, float(y)}}); };
    const double y = invert(py, double(u.y) * column, w.lo.y, w.hi.y, nv_);
    const Vec2 p(std::clamp(float(x), w.lo.x, w.hi.x), std::clamp(float(y), w.lo.y, w.hi.y));
    const float density = float(double(value(p)) / total);
    if (!(density > 0)) return std::nullopt;
    if (pdf) *pdf = density;
    return p;
}

}  // namespace phos::shading
