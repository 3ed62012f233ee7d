// A tabulated spectrum's value: linear between its points, held at the first and last point's
// value outside them. The points are read through accessors, so a table of wavelength-value pairs
// and a table of records (a metal's λ, η, k) use the same interpolation.
#pragma once

#include <cstddef>

namespace phos::spectrum {

// The value at `at` of the n points (x(i), y(i)), x non-decreasing; 0 when n is 0. Where points
// share a wavelength (a step), the value at that wavelength is the first one's.
template <class X, class Y>
float piecewise_linear(size_t n, X&& x, Y&& y, float at) {
    if (n == 0) return 0.0f;
    if (!(at > x(0))) return y(0);
    if (!(at < x(n - 1))) return y(n - 1);
    size_t lo = 0, hi = n - 1;  // x(lo) < at <= x(hi)
    while (hi - lo > 1) {
        const size_t mid = (lo + hi) / 2;
        (x(mid) < at ? lo : hi) = mid;
    }
    const float t = (at - x(lo)) / (x(hi) - x(lo));
    return y(lo) + t * (y(hi) - y(lo));
}

}  // namespace phos::spectrum
