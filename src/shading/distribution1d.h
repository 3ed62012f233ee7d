// Piecewise-constant 1D distribution over n bins: discrete sampling (pick bin i with probability
// w_i / sum) and continuous sampling on [0,1). Used to pick lights by power, mesh triangles by
// area and environment-map rows and columns. All-zero weights fall back to uniform.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace phos::shading {

class Distribution1D {
public:
    Distribution1D() = default;
    // Negative or non-finite weights count as 0.
    explicit Distribution1D(const std::vector<float>& weights);

    size_t size() const { return weights_.size(); }
    bool empty() const { return weights_.empty(); }
    // Sum of the (sanitised) weights; 0 when all are zero (sampling is then uniform).
    double total() const { return total_; }
    float weight(size_t i) const { return weights_[i]; }

    // Picks bin i with probability pmf(i). `remapped` (optional) receives u rescaled to [0,1)
    // within the chosen bin, so the same number can be reused for a further choice.
    size_t sample_discrete(float u, float* pmf = nullptr, float* remapped = nullptr) const {
        if (weights_.size() != 1) return search(u, pmf, remapped);
        // One bin (a scene's only light, as every emitted photon draws): search()'s result without
        // the call, bit for bit. Its width cdf_[1] - cdf_[0] is exactly 1, so pmf is 1 and u is
        // remapped to itself (x - 0 divided by 1), within search()'s clamps.
        const double x = std::clamp(double(u), 0.0, std::nextafter(1.0, 0.0));
        if (pmf) *pmf = 1.0f;
        if (remapped) *remapped = std::min(float(x), std::nextafter(1.0f, 0.0f));
        return 0;
    }
    float pmf(size_t i) const;
    // Cumulative probability before bin i (cdf(size()) == 1).
    double cdf(size_t i) const { return cdf_[i]; }

    // Continuous x in [0,1) with the piecewise-constant density pdf = w_i / (total / n).
    float sample_continuous(float u, float* pdf = nullptr, size_t* bin = nullptr) const;
    float pdf_continuous(float x) const;

private:
    size_t search(float u, float* pmf, float* remapped) const;  // sample_discrete over any bins

    std::vector<float> weights_;
    std::vector<double> cdf_;  // size n + 1, cdf_[0] = 0, cdf_[n] = 1
    double total_ = 0;
};

}  // namespace phos::shading
