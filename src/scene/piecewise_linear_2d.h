// A bilinear function over the unit square tabulated on a regular nx x ny grid, optionally a family
// of them conditioned on up to three parameters (each a sorted axis of values; between two values
// the tables are interpolated linearly), as Dupuy & Jakob 2018 ("An Adaptive Parameterization for
// Efficient Material Acquisition and Rendering", ACM TOG 37(6), sec. 5 and its supplemental
// "piecewise-linear warp") and pbrt-v4's PiecewiseLinear2D (util/sampling.h, used by
// MeasuredBxDF, PBR 4th ed. sec. 9.8) define it. Used by the measured BSDF tables
// (scene/measured_bsdf.h) both as an interpolant (eval) and, when built for sampling, as a warp of
// the unit square: sample() draws a point with density proportional to the bilinear function
// (marginal over rows, then the conditional within the row, each by inverting a piecewise-quadratic
// CDF), invert() is its exact inverse, and both return that density.
//
// Layout: values[slice][y][x], slices in row-major order of the parameters (the first parameter
// outermost). Between parameter values the marginal and conditional CDFs are interpolated with the
// same weights as the values, which samples exactly the interpolated density.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace phos::scene {

class PiecewiseLinear2D {
public:
    static constexpr int kMaxParams = 3;

    struct Result {
        Vec2 p;     // in [0, 1]^2
        float pdf;  // density over the unit square (for eval-only tables: the value)
    };

    PiecewiseLinear2D() = default;
    // `values` holds slices x ny x nx floats, slices the product of the parameter axes' sizes; each
    // axis is strictly increasing (the caller checks: nx, ny >= 2, finite values; for sampling,
    // values >= 0 and every slice with a positive integral). With `sampling`, each slice is scaled
    // to integrate to 1 over the unit square and its CDFs are built (sample, invert, eval give
    // densities); without it eval() gives the bilinear interpolation of the values themselves.
    PiecewiseLinear2D(const float* values, int nx, int ny, std::vector<std::vector<float>> params,
                      bool sampling);

    // `param` holds one value per parameter axis (clamped to each axis's range).
    float eval(Vec2 p, const float* param = nullptr) const;
    Result sample(Vec2 u, const float* param = nullptr) const;
    Result invert(Vec2 p, const float* param = nullptr) const;

    int nx() const { return nx_; }
    int ny() const { return ny_; }
    bool sampling() const { return sampling_; }
    // The integral over the unit square of a slice's bilinear function (raw values): trapezoidal sums.
    static double slice_integral(const float* slice, int nx, int ny);

private:
    // The slices that a parameter point interpolates (up to 2^kMaxParams) and their weights.
    struct Corners {
        int n = 0;
        size_t slice[1 << kMaxParams];
        float weight[1 << kMaxParams];
    };
    Corners corners(const float* param) const;
    // sum over corners of weight x table[slice * stride + i]
    static float lookup(const std::vector<float>& table, size_t stride, size_t i, const Corners& c);

    int nx_ = 0, ny_ = 0;
    bool sampling_ = false;
    std::vector<std::vector<float>> params_;
    std::vector<float> data_;         // values (scaled per slice when sampling)
    std::vector<float> marginal_;     // [slice][ny]: integral of rows 0..y (trapezoids of row integrals)
    std::vector<float> conditional_;  // [slice][ny][nx]: integral of a row's values 0..x
};

}  // namespace phos::scene
