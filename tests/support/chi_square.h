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

    // Expected counts for `total` attempts of a sampler with solid-angle density `pdf`, integrated
    // over each bin by adaptive 6-point Gauss-Legendre quadrature in theta and phi: a cell is split
    // in four while the split changes its integral by more than a small fraction of a count (pdfs
    // may jump inside a bin, e.g. the frosted dielectric's at wi where the half vector turns
    // horizontal). Residual = total - the rest.
    std::vector<double> expected(const std::function<double(Vec3)>& pdf) const {
        std::vector<double> e(counts.size(), 0.0);
        const double dt = theta_max / n_theta, dp = 2 * M_PI / n_phi;
        double sum = 0;
        for (int it = 0; it < n_theta; ++it)
            for (int ip = 0; ip < n_phi; ++ip) {
                const double v =
                    total * adaptive(pdf, it * dt, (it + 1) * dt, ip * dp, (ip + 1) * dp,
                                     gauss(pdf, it * dt, (it + 1) * dt, ip * dp, (ip + 1) * dp), 0);
                e[size_t(it) * size_t(n_phi) + size_t(ip)] = v;
                sum += v;
            }
        e.back() = std::max(0.0, total - sum);
        return e;
    }

private:
    static double gauss(const std::function<double(Vec3)>& pdf, double t0, double t1, double p0, double p1) {
        static constexpr double x[6] = {-0.9324695142031521, -0.6612093864662645, -0.2386191860831969,
                                        0.2386191860831969,  0.6612093864662645,  0.9324695142031521};
        static constexpr double wgt[6] = {0.1713244923791704, 0.3607615730481386, 0.4679139345726910,
                                          0.4679139345726910, 0.3607615730481386, 0.1713244923791704};
        double acc = 0;
        for (int a = 0; a < 6; ++a) {
            const double theta = 0.5 * (t0 + t1) + 0.5 * (t1 - t0) * x[a];
            const double st = std::sin(theta), ct = std::cos(theta);
            for (int b = 0; b < 6; ++b) {
                const double phi = 0.5 * (p0 + p1) + 0.5 * (p1 - p0) * x[b];
                const Vec3 w(float(st * std::cos(phi)), float(st * std::sin(phi)), float(ct));
                acc += wgt[a] * wgt[b] * pdf(w) * st;
            }
        }
        return acc * 0.25 * (t1 - t0) * (p1 - p0);
    }
    double adaptive(const std::function<double(Vec3)>& pdf, double t0, double t1, double p0, double p1,
                    double coarse, int depth) const {
        const double tm = 0.5 * (t0 + t1), pm = 0.5 * (p0 + p1);
        const double q[4] = {gauss(pdf, t0, tm, p0, pm), gauss(pdf, tm, t1, p0, pm),
                             gauss(pdf, t0, tm, pm, p1), gauss(pdf, tm, t1, pm, p1)};
        const double fine = q[0] + q[1] + q[2] + q[3];
        // Tolerance in counts: far below the Poisson noise sqrt(expected) of any bin.
        if (depth >= 6 || std::fabs(fine - coarse) * total <= 0.01 + 1e-4 * fine * total) return fine;
        return adaptive(pdf, t0, tm, p0, pm, q[0], depth + 1) +
               adaptive(pdf, tm, t1, p0, pm, q[1], depth + 1) +
               adaptive(pdf, t0, tm, pm, p1, q[2], depth + 1) +
               adaptive(pdf, tm, t1, pm, p1, q[3], depth + 1);
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
