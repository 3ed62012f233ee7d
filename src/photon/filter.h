// Kernel filters for photon density estimation (Jensen, "Realistic Image Synthesis Using Photon
// Mapping", 2001, sec. 7.2): box, cone and Gaussian weights of a photon at distance d from the
// query point inside the estimate's radius r, each with the normalisation that makes the
// estimate of a uniform photon density unbiased.
#pragma once

#include <cmath>
#include <string>

namespace phos::photon {

enum class FilterKind { Box, Cone, Gauss };

// Parses "none" / "box" / "cone" / "gauss" (or "gaussian"); returns false for anything else.
bool parse_filter_kind(const std::string& name, FilterKind& kind);
const char* filter_name(FilterKind kind);

struct KernelFilter {
    FilterKind kind = FilterKind::Box;
    float cone_k = 1.1f;  // cone slope: weight 1 - d / (k r), k >= 1

    // Jensen's Gaussian (after Pavicic): w = alpha [1 - (1 - e^(-beta d^2 / (2 r^2))) / (1 - e^-beta)].
    static constexpr float kGaussBeta = 1.953f;

    // Unnormalised weight of a photon at squared distance d2 inside radius^2 r2 (> 0).
    float weight(float d2, float r2) const {
        switch (kind) {
            case FilterKind::Box:
                return 1.0f;
            case FilterKind::Cone:
                return 1.0f - std::sqrt(d2 / r2) / cone_k;
            case FilterKind::Gauss:
                return 1.0f -
                       (1.0f - std::exp(-kGaussBeta * d2 / (2.0f * r2))) / (1.0f - std::exp(-kGaussBeta));
        }
        return 1.0f;
    }
    // The mean of weight() over the disk of radius r (uniform density): dividing the weighted sum
    // by mean * pi r^2 makes the estimate of a uniform density exact.
    //  - box: 1.
    //  - cone: with t = d / r, 2 * integral_0^1 (1 - t/k) t dt = 1 - 2 / (3k) (Jensen's factor).
    //  - Gauss: with s = d^2 / r^2 uniform on [0, 1], the mean of w is
    //    1 - (1 - (2 / beta)(1 - e^(-beta/2))) / (1 - e^-beta) = 0.5785 for beta = 1.953; Jensen
    //    folds this into his alpha constant. Computed here rather than quoted so that it stays
    //    right if beta changes; checked numerically by tests/photon/estimate_test.cpp.
    float mean_weight() const {
        switch (kind) {
            case FilterKind::Box:
                return 1.0f;
            case FilterKind::Cone:
                return 1.0f - 2.0f / (3.0f * cone_k);
            case FilterKind::Gauss: {
                const double b = kGaussBeta;
                return float(1.0 - (1.0 - (2.0 / b) * (1.0 - std::exp(-b / 2.0))) / (1.0 - std::exp(-b)));
            }
        }
        return 1.0f;
    }
};

}  // namespace phos::photon
