// Test support: Pearson chi-square goodness-of-fit of sample histograms against integrated pdfs
// (for the warps and the BSDFs), and direction histograms on a (theta, phi) grid. Header-only, so
// tests of any layer can include it.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "core/vec.h"

namespace phos::test {

struct ChiSquareResult {
    double statistic = 0;
    int dof = 0;
    double threshold = 0;
    bool passed = false;
    std::string detail;
};

// Upper quantile of the standard normal: z with P(Z > z) = p (bisection on erfc).
inline double normal_upper_quantile(double p) {
    double lo = 0, hi = 40;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// Chi-square quantile with k degrees of freedom at upper-tail probability p (Wilson-Hilferty
// cube-root normal approximation; relative error well under 1% for k >= 10, which is our regime).
inline double chi_square_quantile(int k, double p) {
    const double z = normal_upper_quantile(p), a = 2.0 / (9.0 * k);
    const double c = 1 - a + z * std::sqrt(a);
    return k * c * c * c;
}

// Compares observed with expected counts (same total is not required: callers add a residual bin
// for mass that falls outside the histogram). Bins with small expectation are pooled, smallest
// first, until every pooled bin expects >= min_expected (the classic validity condition). Passes
// when the statistic is below the chi-square quantile at `significance`.
inline ChiSquareResult chi_square(const std::vector<double>& observed, const std::vector<double>& expected,
                                  double significance = 1e-4, double min_expected = 5) {
    std::vector<size_t> order(expected.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });
    ChiSquareResult r;
    const auto term = [](double o, double e) { return (o - e) * (o - e) / e; };
    double pool_obs = 0, pool_exp = 0;  // the pool being filled
    double last_obs = 0, last_exp = 0;  // the last pool flushed (to absorb a small rest)
    int bins = 0;
    double impossible = 0;  // samples in bins whose expectation is zero
    for (size_t i : order) {
        if (expected[i] <= 0 && observed[i] > 0) impossible += observed[i];
        if (expected[i] >= min_expected) {
            r.statistic += term(observed[i], expected[i]);
            ++bins;
            continue;
        }
        pool_obs += observed[i];
        pool_exp += expected[i];
        if (pool_exp >= min_expected) {
            r.statistic += term(pool_obs, pool_exp);
            ++bins;
            last_obs = pool_obs;
            last_exp = pool_exp;
            pool_obs = pool_exp = 0;
        }
    }
    if (pool_exp > 0 || pool_obs > 0) {
        if (last_exp > 0) {  // merge the small rest into the last pool
            r.statistic += term(last_obs + pool_obs, last_exp + pool_exp) - term(last_obs, last_exp);
        } else if (pool_exp > 0) {
            r.statistic += term(pool_obs, pool_exp);
            ++bins;
        } else {
            impossible += pool_obs;
        }
    }
    r.dof = std::max(1, bins - 1);
    r.threshold = chi_square_quantile(r.dof, significance);
    r.passed = r.statistic <= r.threshold && impossible == 0;
    std::ostringstream os;
    os << "chi2 = " << r.statistic << " (dof " << r.dof << ", threshold " << r.threshold
       << "), samples where pdf = 0: " << impossible;
    r.detail = os.str();
    return r;
}

// A (theta, phi) grid over the directions with theta in [0, theta_max] (theta measured from +z);
// everything else (theta > theta_max, rejected and delta samples) goes to one residual bin.
struct DirectionHistogram {
    int n_theta, n_phi;
    double theta_max;
    std::vector<double> counts;
    double total = 0;  // number of attempts, including those that produced nothing

    DirectionHistogram(int nt, int np, double tmax)
        : n_theta(nt), n_phi(np), theta_max(tmax), counts(size_t(nt) * size_t(np) + 1, 0.0) {}

    void add(Vec3 w) {
        const double theta = std::acos(std::clamp(double(w.z), -1.0, 1.0));
        double phi = std::atan2(double(w.y), double(w.x));
        if (phi < 0) phi += 2 * M_PI;
        if (theta > theta_max) {
            counts.back() += 1;
            return;
        }
        const int it = std::min(n_theta - 1, int(theta / theta_max * n_theta));
        const int ip = std::min(n_phi - 1, int(phi / (2 * M_PI) * n_phi));
        counts[size_t(it) * size_t(n_phi) + size_t(ip)] += 1;
    }
    // An attempt that produced no direction in the grid's measure (rejected or delta sample).
    void add_residual() { counts.back() += 1; }

    // Expected counts for `total` attempts of a sampler with solid-angle density `pdf`: composite
    // Simpson over each bin (sub x sub intervals, sub even), residual = total - the rest.
    std::vector<double> expected(const std::function<double(Vec3)>& pdf, int sub = 8) const {
        std::vector<double> e(counts.size(), 0.0);
        const double dt = theta_max / n_theta, dp = 2 * M_PI / n_phi;
        const auto simpson_w = [sub](int k) { return (k == 0 || k == sub) ? 1.0 : (k % 2 ? 4.0 : 2.0); };
        double sum = 0;
        for (int it = 0; it < n_theta; ++it)
            for (int ip = 0; ip < n_phi; ++ip) {
                double acc = 0;
                for (int a = 0; a <= sub; ++a) {
                    const double theta = (it + double(a) / sub) * dt;
                    const double st = std::sin(theta), ct = std::cos(theta);
                    for (int b = 0; b <= sub; ++b) {
                        const double phi = (ip + double(b) / sub) * dp;
                        const Vec3 w(float(st * std::cos(phi)), float(st * std::sin(phi)), float(ct));
                        acc += simpson_w(a) * simpson_w(b) * pdf(w) * st;
                    }
                }
                const double v = acc * (dt / (3 * sub)) * (dp / (3 * sub)) * total;
                e[size_t(it) * size_t(n_phi) + size_t(ip)] = v;
                sum += v;
            }
        e.back() = std::max(0.0, total - sum);
        return e;
    }
};

// Integral of a solid-angle density over directions with theta in [0, theta_max] (2D Simpson).
inline double integrate_sphere(const std::function<double(Vec3)>& pdf, double theta_max, int nt = 512,
                               int np = 64) {
    const double dt = theta_max / nt, dp = 2 * M_PI / np;
    double acc = 0;
    for (int a = 0; a <= nt; ++a) {
        const double wa = (a == 0 || a == nt) ? 1 : (a % 2 ? 4 : 2);
        const double theta = a * dt, st = std::sin(theta), ct = std::cos(theta);
        for (int b = 0; b <= np; ++b) {
            const double wb = (b == 0 || b == np) ? 1 : (b % 2 ? 4 : 2);
            const double phi = b * dp;
            acc += wa * wb * st * pdf(Vec3(float(st * std::cos(phi)), float(st * std::sin(phi)), float(ct)));
        }
    }
    return acc * dt / 3 * dp / 3;
}

}  // namespace phos::test
