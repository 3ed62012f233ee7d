// Pixel filters as pbrt-v4 defines them, and their importance sampling per axis (see
// pixel_filter.h).
#include "render/pixel_filter.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace phos::render {

namespace {

using Kind = scene::PixelFilter::Kind;

constexpr int kCells = 512;  // per axis; the weight of a positive filter stays within ~0.3 % of 1

double gaussian(double x, double sigma) {
    return std::exp(-x * x / (2 * sigma * sigma)) / std::sqrt(2 * double(kPi) * sigma * sigma);
}

// Mitchell & Netravali 1988, eq. 8, on [-2, 2].
double mitchell(double x, double B, double C) {
    x = std::fabs(x);
    if (x <= 1) return ((12 - 9 * B - 6 * C) * x * x * x + (-18 + 12 * B + 6 * C) * x * x + (6 - 2 * B)) / 6;
    if (x <= 2)
        return ((-B - 6 * C) * x * x * x + (6 * B + 30 * C) * x * x + (-12 * B - 48 * C) * x +
                (8 * B + 24 * C)) /
               6;
    return 0;
}

double sinc(double x) {
    if (std::fabs(x) < 1e-5) return 1 - double(kPi) * double(kPi) * x * x / 6;
    return std::sin(double(kPi) * x) / (double(kPi) * x);
}

}  // namespace

float PixelFilterSampler::Axis::f(float xf) const {
    const double x = xf;
    if (!(std::fabs(x) <= r)) return 0;
    switch (shape.kind) {
        case Kind::Box:
            return 1;
        case Kind::Gaussian:
            return float(std::max(0.0, gaussian(x, shape.sigma) - gaussian(r, shape.sigma)));
        case Kind::Mitchell:
            return float(mitchell(2 * x / r, shape.b, shape.c));
        case Kind::Lanczos:
            return float(sinc(x) * sinc(x / shape.tau));
        case Kind::Triangle:
            return float(std::max(0.0, double(r) - std::fabs(x)));
    }
    return 0;
}

void PixelFilterSampler::Axis::sample(float u, float& x, float& ratio) const {
    const auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    const int i = std::clamp(int(it - cdf.begin()) - 1, 0, kCells - 1);
    const float span = cdf[size_t(i) + 1] - cdf[size_t(i)];
    const float t = span > 0 ? std::clamp((u - cdf[size_t(i)]) / span, 0.0f, 1.0f) : 0.5f;
    const float dx = 2 * r / float(kCells);
    x = std::clamp(-r + (float(i) + t) * dx, -r, r);
    ratio = pdf[size_t(i)] > 0 ? f(x) / pdf[size_t(i)] : 0.0f;
}

PixelFilterSampler::PixelFilterSampler(const scene::PixelFilter& filter) : filter_(filter) {
    if (!(filter.radius.x > 0 && filter.radius.y > 0 && std::isfinite(filter.radius.x) &&
          std::isfinite(filter.radius.y)))
        throw InputError("pixel filter: the radius must be positive");
    if (filter.kind == Kind::Gaussian && !(filter.sigma > 0))
        throw InputError("pixel filter: the Gaussian's sigma must be positive");
    if (filter.kind == Kind::Lanczos && !(filter.tau > 0))
        throw InputError("pixel filter: the Lanczos filter's tau must be positive");
    for (int a = 0; a < 2; ++a) {
        Axis& ax = axis_[a];
        ax.shape = filter;
        ax.r = a == 0 ? filter.radius.x : filter.radius.y;
        // ∫ f1 by Simpson's rule on 2^13 intervals (exact for the box, triangle and the Mitchell
        // cubic, whose knots fall on interval ends; the Gaussian and sinc are smooth).
        constexpr int kSimpson = 8192;
        const double h = 2.0 * ax.r / kSimpson;
        double sum = 0;
        for (int k = 0; k <= kSimpson; ++k) {
            const double w = (k == 0 || k == kSimpson) ? 1 : (k % 2 ? 4 : 2);
            sum += w * double(ax.f(float(-double(ax.r) + k * h)));
        }
        ax.integral = sum * h / 3;
        if (!(ax.integral > 0)) throw InputError("pixel filter: its integral is not positive");
        // |f1| bounded per cell by its largest value at the ends and the middle.
        const double dx = 2.0 * ax.r / kCells;
        std::vector<double> bound(kCells);
        double total = 0;
        for (int i = 0; i < kCells; ++i) {
            const double x0 = -double(ax.r) + i * dx;
            bound[size_t(i)] =
                std::max({std::fabs(double(ax.f(float(x0)))), std::fabs(double(ax.f(float(x0 + dx / 2)))),
                          std::fabs(double(ax.f(float(x0 + dx))))});
            total += bound[size_t(i)];
        }
        ax.cdf.assign(kCells + 1, 0.0f);
        ax.pdf.assign(kCells, 0.0f);
        double run = 0;
        for (int i = 0; i < kCells; ++i) {
            ax.pdf[size_t(i)] = float(bound[size_t(i)] / (total * dx));
            run += bound[size_t(i)];
            ax.cdf[size_t(i) + 1] = float(run / total);
        }
        ax.cdf.back() = 1;
    }
}

PixelFilterSampler::FilmSample PixelFilterSampler::sample(Vec2 u) const {
    if (filter_.is_pixel_box()) return {u, 1.0f};
    if (filter_.kind == Kind::Box)
        return {Vec2(0.5f + (2 * u.x - 1) * filter_.radius.x, 0.5f + (2 * u.y - 1) * filter_.radius.y), 1.0f};
    if (filter_.kind == Kind::Triangle) {
        // The tent's inverse CDF, exact: the weight is 1.
        const auto tent = [](float v, float r) {
            return v < 0.5f ? r * (std::sqrt(2 * v) - 1) : r * (1 - std::sqrt(2 - 2 * v));
        };
        return {Vec2(0.5f + tent(u.x, filter_.radius.x), 0.5f + tent(u.y, filter_.radius.y)), 1.0f};
    }
    float x, y, rx, ry;
    axis_[0].sample(u.x, x, rx);
    axis_[1].sample(u.y, y, ry);
    return {Vec2(0.5f + x, 0.5f + y),
            float(double(rx) * double(ry) / (axis_[0].integral * axis_[1].integral))};
}

float PixelFilterSampler::splat_weight(Vec2 d) const {
    if (filter_.is_pixel_box()) return std::fabs(d.x) <= 0.5f && std::fabs(d.y) <= 0.5f ? 1.0f : 0.0f;
    return float(double(evaluate(d)) / (axis_[0].integral * axis_[1].integral));
}

}  // namespace phos::render
