// The piecewise-bilinear warp of piecewise_linear_2d.h (Dupuy & Jakob 2018, sec. 5; pbrt-v4's
// PiecewiseLinear2D): CDFs built per slice, parameters interpolated through corner weights.
#include "scene/piecewise_linear_2d.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace phos::scene {

namespace {

// The largest i in [0, n - 2] with pred(i) true, for a pred that is true up to some index and false
// after it (0 when pred(0) is false): the interval of a sorted table that holds a value.
template <class Pred>
size_t find_interval(size_t n, Pred pred) {
    size_t first = 1, len = n >= 2 ? n - 2 : 0;
    while (len > 0) {
        const size_t half = len / 2, mid = first + half;
        if (pred(mid)) {
            first = mid + 1;
            len -= half + 1;
        } else {
            len = half;
        }
    }
    return std::min(first - 1, n >= 2 ? n - 2 : 0);
}

float clamp01(float x) { return std::fmin(std::fmax(x, 0.0f), 1.0f); }  // NaN -> 0

// t in [0, 1] with integral_0^t (a + (b - a) s) ds = v: the inverse of a linear density's CDF. The
// root (a - sqrt(a^2 - 2 v (a - b))) / (a - b) is taken in its rationalised form
// 2 v / (a + sqrt(...)), which does not cancel for small v and needs no case for a == b.
float solve_linear_cdf(float a, float b, float v) {
    const float den = a + std::sqrt(std::fmax(a * a - 2 * v * (a - b), 0.0f));
    return den > 0 ? clamp01(2 * v / den) : 0.0f;
}

}  // namespace

PiecewiseLinear2D::PiecewiseLinear2D(const float* values, int nx, int ny,
                                     std::vector<std::vector<float>> params, bool sampling)
    : nx_(nx), ny_(ny), sampling_(sampling), params_(std::move(params)) {
    size_t slices = 1;
    for (const auto& axis : params_) slices *= axis.size();
    const size_t n = size_t(nx) * size_t(ny);
    data_.assign(values, values + slices * n);
    if (!sampling) return;
    marginal_.assign(slices * size_t(ny), 0.0f);
    conditional_.assign(slices * n, 0.0f);
    for (size_t s = 0; s < slices; ++s) {
        float* data = data_.data() + s * n;
        float* cond = conditional_.data() + s * n;
        float* marg = marginal_.data() + s * size_t(ny);
        for (int y = 0; y < ny; ++y) {
            double sum = 0;
            const size_t row = size_t(y) * size_t(nx);
            for (int x = 0; x + 1 < nx; ++x) {
                sum += 0.5 * (double(data[row + size_t(x)]) + double(data[row + size_t(x) + 1]));
                cond[row + size_t(x) + 1] = float(sum);
            }
        }
        double sum = 0;
        for (int y = 0; y + 1 < ny; ++y) {
            sum += 0.5 * (double(cond[size_t(y + 1) * size_t(nx) - 1]) +
                          double(cond[size_t(y + 2) * size_t(nx) - 1]));
            marg[y + 1] = float(sum);
        }
        // Divided in double: 1 / sum overflows a float for a slice of tiny values (found by the
        // fuzzer). A slice without mass (which the readers refuse) is left at 0.
        const double total = sum > 0 && std::isfinite(sum) ? sum : 0.0;
        const auto scale = [total](float& v) { v = total > 0 ? float(double(v) / total) : 0.0f; };
        for (size_t i = 0; i < n; ++i) {
            scale(cond[i]);
            scale(data[i]);
        }
        for (int y = 0; y < ny; ++y) scale(marg[y]);
    }
}

double PiecewiseLinear2D::slice_integral(const float* v, int nx, int ny) {
    double sum = 0;
    for (int y = 0; y + 1 < ny; ++y)
        for (int x = 0; x + 1 < nx; ++x) {
            const size_t i = size_t(y) * size_t(nx) + size_t(x);
            sum += 0.25 * (double(v[i]) + double(v[i + 1]) + double(v[i + size_t(nx)]) +
                           double(v[i + size_t(nx) + 1]));
        }
    return sum / (double(nx - 1) * double(ny - 1));
}

PiecewiseLinear2D::Corners PiecewiseLinear2D::corners(const float* param) const {
    Corners c;
    c.n = 1;
    c.slice[0] = 0;
    c.weight[0] = 1;
    size_t stride = 1;
    for (const auto& axis : params_) stride *= axis.size();
    for (size_t d = 0; d < params_.size(); ++d) {
        const std::vector<float>& axis = params_[d];
        stride /= axis.size();
        if (axis.size() == 1) continue;
        const float p = param ? param[d] : 0.0f;
        const size_t i = find_interval(axis.size(), [&](size_t k) { return axis[k] <= p; });
        const float t = clamp01((p - axis[i]) / (axis[i + 1] - axis[i]));
        const int n = c.n;
        for (int k = 0; k < n; ++k) {
            const size_t base = c.slice[k];
            const float w = c.weight[k];
            c.slice[k] = base + i * stride;
            c.weight[k] = w * (1 - t);
            c.slice[n + k] = base + (i + 1) * stride;
            c.weight[n + k] = w * t;
        }
        c.n = 2 * n;
    }
    return c;
}

float PiecewiseLinear2D::lookup(const std::vector<float>& table, size_t stride, size_t i, const Corners& c) {
    float v = 0;
    for (int k = 0; k < c.n; ++k)
        if (c.weight[k] != 0) v += c.weight[k] * table[c.slice[k] * stride + i];
    return v;
}

float PiecewiseLinear2D::eval(Vec2 p, const float* param) const {
    if (data_.empty()) return 0;
    const Corners c = corners(param);
    const float px = clamp01(p.x) * float(nx_ - 1), py = clamp01(p.y) * float(ny_ - 1);
    const size_t col = std::min(size_t(px), size_t(nx_ - 2)), row = std::min(size_t(py), size_t(ny_ - 2));
    const float fx = px - float(col), fy = py - float(row);
    const size_t n = size_t(nx_) * size_t(ny_), i = row * size_t(nx_) + col;
    const float v00 = lookup(data_, n, i, c), v10 = lookup(data_, n, i + 1, c),
                v01 = lookup(data_, n, i + size_t(nx_), c), v11 = lookup(data_, n, i + size_t(nx_) + 1, c);
    const float v = (1 - fy) * ((1 - fx) * v00 + fx * v10) + fy * ((1 - fx) * v01 + fx * v11);
    return sampling_ ? v * float(nx_ - 1) * float(ny_ - 1) : v;
}

PiecewiseLinear2D::Result PiecewiseLinear2D::sample(Vec2 u, const float* param) const {
    if (!sampling_ || data_.empty()) return {Vec2(0, 0), 0};
    constexpr float kEps = 5.9604645e-8f;  // 2^-24: keeps u off the ends, where the search degenerates
    u.x = std::fmin(std::fmax(u.x, kEps), 1 - kEps);
    u.y = std::fmin(std::fmax(u.y, kEps), 1 - kEps);
    const Corners c = corners(param);
    const size_t nx = size_t(nx_), ny = size_t(ny_), n = nx * ny;

    // The row: invert the marginal CDF, then the linear density between the two rows' integrals.
    const size_t row = find_interval(ny, [&](size_t y) { return lookup(marginal_, ny, y, c) < u.y; });
    u.y -= lookup(marginal_, ny, row, c);
    const size_t off = row * nx;
    const float r0 = lookup(conditional_, n, off + nx - 1, c),
                r1 = lookup(conditional_, n, off + 2 * nx - 1, c);
    const float t = solve_linear_cdf(r0, r1, u.y);

    // The column within the row at height t.
    u.x *= (1 - t) * r0 + t * r1;
    const auto cdf = [&](size_t x) {
        return (1 - t) * lookup(conditional_, n, off + x, c) + t * lookup(conditional_, n, off + nx + x, c);
    };
    const size_t col = find_interval(nx, [&](size_t x) { return cdf(x) < u.x; });
    u.x -= cdf(col);
    const size_t i = off + col;
    const float v00 = lookup(data_, n, i, c), v10 = lookup(data_, n, i + 1, c),
                v01 = lookup(data_, n, i + nx, c), v11 = lookup(data_, n, i + nx + 1, c);
    const float c0 = (1 - t) * v00 + t * v01, c1 = (1 - t) * v10 + t * v11;
    const float s = solve_linear_cdf(c0, c1, u.x);
    return {Vec2((float(col) + s) / float(nx - 1), (float(row) + t) / float(ny - 1)),
            ((1 - s) * c0 + s * c1) * float(nx - 1) * float(ny - 1)};
}

PiecewiseLinear2D::Result PiecewiseLinear2D::invert(Vec2 p, const float* param) const {
    if (!sampling_ || data_.empty()) return {Vec2(0, 0), 0};
    const Corners c = corners(param);
    const size_t nx = size_t(nx_), ny = size_t(ny_), n = nx * ny;
    const float px = clamp01(p.x) * float(nx - 1), py = clamp01(p.y) * float(ny - 1);
    const size_t col = std::min(size_t(px), nx - 2), row = std::min(size_t(py), ny - 2);
    const float fx = px - float(col), fy = py - float(row);
    const size_t i = row * nx + col;
    const float v00 = lookup(data_, n, i, c), v10 = lookup(data_, n, i + 1, c),
                v01 = lookup(data_, n, i + nx, c), v11 = lookup(data_, n, i + nx + 1, c);
    const float c0 = (1 - fy) * v00 + fy * v01, c1 = (1 - fy) * v10 + fy * v11;
    const float pdf = (1 - fx) * c0 + fx * c1;
    // The conditional CDF at (col + fx) within the row at height fy, over the row's integral.
    float x = fx * (c0 + 0.5f * fx * (c1 - c0)) + (1 - fy) * lookup(conditional_, n, i, c) +
              fy * lookup(conditional_, n, i + nx, c);
    const float r0 = lookup(conditional_, n, row * nx + nx - 1, c),
                r1 = lookup(conditional_, n, row * nx + 2 * nx - 1, c);
    const float row_mass = (1 - fy) * r0 + fy * r1;
    x = row_mass > 0 ? x / row_mass : 0.0f;
    const float y = fy * (r0 + 0.5f * fy * (r1 - r0)) + lookup(marginal_, ny, row, c);
    return {Vec2(x, y), pdf * float(nx - 1) * float(ny - 1)};
}

}  // namespace phos::scene
