// Piecewise-constant 1D distribution: the CDF is kept in double so that meshes with millions of
// triangles keep every triangle's share resolvable.
#include "shading/distribution1d.h"

#include <algorithm>
#include <cmath>

namespace phos::shading {

Distribution1D::Distribution1D(const std::vector<float>& weights) : weights_(weights) {
    for (float& w : weights_)
        if (!(w > 0) || !std::isfinite(w)) w = 0;
    const size_t n = weights_.size();
    cdf_.assign(n + 1, 0.0);
    total_ = 0;
    for (size_t i = 0; i < n; ++i) total_ += weights_[i];
    for (size_t i = 0; i < n; ++i)
        cdf_[i + 1] = cdf_[i] + (total_ > 0 ? weights_[i] / total_ : 1.0 / double(n));
    if (n > 0) cdf_[n] = 1.0;
}

float Distribution1D::pmf(size_t i) const {
    if (i >= weights_.size()) return 0;
    return float(cdf_[i + 1] - cdf_[i]);
}

size_t Distribution1D::search(float u, float* pmf, float* remapped) const {
    const size_t n = weights_.size();
    const double x = std::clamp(double(u), 0.0, std::nextafter(1.0, 0.0));
    // First bin whose upper edge exceeds x; empty bins (zero width) can never satisfy this.
    size_t i;
    if (n <= 16) {
        // Few bins (the triangles of a quad light): the edges at or below x counted without
        // branches. They are a prefix (the sums never fall, and an edge that rounding put above the
        // last one, 1, is above x < 1 too), so the count is the binary search's index; the binary
        // search's random turns would be mispredicted at half of all photon emissions.
        i = 0;
        for (size_t k = 1; k < n; ++k) i += cdf_[k] <= x;
    } else {
        i = size_t(std::upper_bound(cdf_.begin() + 1, cdf_.end(), x) - (cdf_.begin() + 1));
    }
    if (i >= n) i = n - 1;
    // Guard against rounding at the top end. (The width first: i > 0 is a coin toss between
    // the two triangles of a quad light, the empty bin almost never happens.)
    while (cdf_[i + 1] - cdf_[i] <= 0 && i > 0) --i;
    const double width = cdf_[i + 1] - cdf_[i];
    if (pmf) *pmf = float(width);
    if (remapped) {
        const double r = width > 0 ? (x - cdf_[i]) / width : 0.0;
        *remapped = std::min(float(std::clamp(r, 0.0, 1.0)), std::nextafter(1.0f, 0.0f));
    }
    return i;
}

float Distribution1D::sample_continuous(float u, float* pdf, size_t* bin) const {
    float p = 0, r = 0;
    const size_t i = sample_discrete(u, &p, &r);
    const size_t n = weights_.size();
    if (pdf) *pdf = p * float(n);
    if (bin) *bin = i;
    return std::min((float(i) + r) / float(n), std::nextafter(1.0f, 0.0f));
}

float Distribution1D::pdf_continuous(float x) const {
    const size_t n = weights_.size();
    if (n == 0 || !(x >= 0) || !(x < 1)) return 0;
    const size_t i = std::min(size_t(x * float(n)), n - 1);
    return pmf(i) * float(n);
}

}  // namespace phos::shading
