// RGB to spectrum by sigmoid polynomials: the fit and its table (see rgb_sigmoid.h).
#include "spectrum/rgb_sigmoid.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "spectrum/cie_tables.h"
#include "spectrum/color.h"

namespace phos::spectrum {

namespace {

double sigmoid(double x) { return 0.5 + x / (2 * std::sqrt(1 + x * x)); }
double sigmoid_derivative(double x) { return 0.5 / std::pow(1 + x * x, 1.5); }
double to_t(double lambda) { return (lambda - kLambdaMin) / (double(kLambdaMax) - kLambdaMin); }

// Per 1 nm sample: t and the linear-sRGB weight of a unit reflectance there under D65, so that
// RGB(s) = sum_k s(t_k) w_k (and the w_k sum to white, (1, 1, 1)).
struct Weights {
    std::array<double, kCieSamples> t;
    std::array<std::array<double, 3>, kCieSamples> w;
};

const Weights& weights() {
    static const Weights W = [] {
        Weights w;
        double norm = 0;
        for (int k = 0; k < kCieSamples; ++k) norm += double(kCieD65[k]) * kCieY[k];
        const Mat3& m = xyz_to_srgb();
        for (int k = 0; k < kCieSamples; ++k) {
            w.t[size_t(k)] = to_t(kCieMin + k);
            const double e = double(kCieD65[k]) / norm;
            const double xyz[3] = {kCieX[k] * e, kCieY[k] * e, kCieZ[k] * e};
            for (int c = 0; c < 3; ++c)
                w.w[size_t(k)][size_t(c)] =
                    m[size_t(c)][0] * xyz[0] + m[size_t(c)][1] * xyz[1] + m[size_t(c)][2] * xyz[2];
        }
        return w;
    }();
    return W;
}

// RGB of coefficients c, and its Jacobian d RGB / d c.
void evaluate(const std::array<double, 3>& c, double rgb[3], double J[3][3]) {
    const Weights& W = weights();
    for (int i = 0; i < 3; ++i) {
        rgb[i] = 0;
        for (int j = 0; j < 3; ++j) J[i][j] = 0;
    }
    for (int k = 0; k < kCieSamples; ++k) {
        const double t = W.t[size_t(k)], x = (c[0] * t + c[1]) * t + c[2];
        const double s = sigmoid(x), ds = sigmoid_derivative(x);
        const double dx[3] = {t * t, t, 1};
        for (int i = 0; i < 3; ++i) {
            const double w = W.w[size_t(k)][size_t(i)];
            rgb[i] += s * w;
            for (int j = 0; j < 3; ++j) J[i][j] += ds * dx[j] * w;
        }
    }
}

// Solves the 3 x 3 system A d = b (Cramer's rule); false if singular.
bool solve3(const double A[3][3], const double b[3], double d[3]) {
    const double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                       A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                       A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    if (!(std::fabs(det) > 1e-300)) return false;
    for (int j = 0; j < 3; ++j) {
        double M[3][3];
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) M[r][c] = c == j ? b[r] : A[r][c];
        d[j] = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])) /
               det;
    }
    return true;
}

double max_abs(const double r[3]) { return std::max({std::fabs(r[0]), std::fabs(r[1]), std::fabs(r[2])}); }

// The z grid: dense near 0 and 1 (smoothstep applied twice).
float z_grid(int k, int res) {
    const auto smoothstep = [](double x) { return x * x * (3 - 2 * x); };
    return float(smoothstep(smoothstep(double(k) / double(res - 1))));
}

// The x and y grids: dense near 0 and 1, where the colour nears a face of the cube (saturated, or
// bright) and the coefficients change fastest: x = smoothstep(u), u = k / (res − 1); and its
// inverse, u = 1/2 − sin(asin(1 − 2x) / 3).
float xy_grid(int k, int res) {
    const double u = double(k) / double(res - 1);
    return float(u * u * (3 - 2 * u));
}
float xy_to_grid(float x, int res) {
    const double u = 0.5 - std::sin(std::asin(std::clamp(1 - 2 * double(x), -1.0, 1.0)) / 3);
    return float(std::clamp(u, 0.0, 1.0) * (res - 1));
}

}  // namespace

float SigmoidPolynomial::operator()(float lambda) const {
    const double t = to_t(lambda);
    const double x = (double(c[0]) * t + c[1]) * t + c[2];
    if (std::isinf(x)) return x > 0 ? 1.0f : 0.0f;
    return float(sigmoid(x));
}

SampledSpectrum SigmoidPolynomial::sample(const SampledWavelengths& w) const {
    SampledSpectrum s;
    for (int i = 0; i < kSpectrumSamples; ++i) s[i] = (*this)(w[i]);
    return s;
}

Vec3 reflectance_to_srgb(const SigmoidPolynomial& s) {
    const Weights& W = weights();
    double rgb[3] = {0, 0, 0};
    for (int k = 0; k < kCieSamples; ++k) {
        const double v = s(float(kCieMin + k));
        for (int c = 0; c < 3; ++c) rgb[c] += v * W.w[size_t(k)][size_t(c)];
    }
    return {float(rgb[0]), float(rgb[1]), float(rgb[2])};
}

float fit_sigmoid(Vec3 target, SigmoidPolynomial& fit, int max_iterations) {
    std::array<double, 3> c{fit.c[0], fit.c[1], fit.c[2]};
    double rgb[3], J[3][3];
    evaluate(c, rgb, J);
    double r[3] = {rgb[0] - target.x, rgb[1] - target.y, rgb[2] - target.z};
    double err = max_abs(r), mu = 1e-6;
    for (int it = 0; it < max_iterations && err > 1e-7; ++it) {
        // Levenberg-Marquardt: (JᵀJ + μ diag(JᵀJ)) d = −Jᵀ r.
        double A[3][3], b[3];
        for (int i = 0; i < 3; ++i) {
            b[i] = 0;
            for (int k = 0; k < 3; ++k) b[i] -= J[k][i] * r[k];
            for (int j = 0; j < 3; ++j) {
                A[i][j] = 0;
                for (int k = 0; k < 3; ++k) A[i][j] += J[k][i] * J[k][j];
            }
        }
        bool improved = false;
        for (int tries = 0; tries < 20 && !improved; ++tries) {
            double Ad[3][3], d[3];
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) Ad[i][j] = A[i][j] + (i == j ? mu * (A[i][i] + 1e-12) : 0);
            if (!solve3(Ad, b, d)) {
                mu *= 10;
                continue;
            }
            const std::array<double, 3> cn{c[0] + d[0], c[1] + d[1], c[2] + d[2]};
            double rgbn[3], Jn[3][3];
            evaluate(cn, rgbn, Jn);
            const double rn[3] = {rgbn[0] - target.x, rgbn[1] - target.y, rgbn[2] - target.z};
            const double errn = max_abs(rn);
            if (errn < err) {
                c = cn;
                std::memcpy(J, Jn, sizeof J);
                for (int i = 0; i < 3; ++i) r[i] = rn[i];
                err = errn;
                mu = std::max(mu * 0.1, 1e-12);
                improved = true;
            } else {
                mu *= 10;
            }
        }
        if (!improved) break;
    }
    fit.c = {float(c[0]), float(c[1]), float(c[2])};
    return float(err);
}

RgbSigmoidTable RgbSigmoidTable::fit(int res, float* worst) {
    if (res < 2) throw std::invalid_argument("RgbSigmoidTable: resolution below 2");
    RgbSigmoidTable t;
    t.res_ = res;
    t.z_.resize(size_t(res));
    for (int k = 0; k < res; ++k) t.z_[size_t(k)] = z_grid(k, res);
    t.coeffs_.resize(size_t(3) * size_t(res) * size_t(res) * size_t(res));
    std::vector<float> column_worst(size_t(3) * size_t(res) * size_t(res), 0.0f);
    const int start = res / 5;
    tbb::parallel_for(0, 3 * res * res, [&](int job) {
        const int m = job / (res * res), yi = (job / res) % res, xi = job % res;
        const float x = xy_grid(xi, res), y = xy_grid(yi, res);
        float column = 0;
        const auto solve_at = [&](int zi, SigmoidPolynomial& s) {
            const float z = t.z_[size_t(zi)];
            Vec3 rgb;
            rgb[m] = z;
            rgb[(m + 1) % 3] = x * z;
            rgb[(m + 2) % 3] = y * z;
            const float e = fit_sigmoid(rgb, s);
            if (z > 0 && z < 1) column = std::max(column, e);  // 0 and 1 are limits the sigmoid only nears
            t.coeffs_[t.index(m, zi, yi, xi)] = s;
        };
        SigmoidPolynomial mid;
        solve_at(start, mid);
        SigmoidPolynomial s = mid;
        for (int zi = start + 1; zi < res; ++zi) solve_at(zi, s);
        s = mid;
        for (int zi = start - 1; zi >= 0; --zi) solve_at(zi, s);
        column_worst[size_t(job)] = column;
    });
    if (worst) *worst = *std::max_element(column_worst.begin(), column_worst.end());
    return t;
}

SigmoidPolynomial RgbSigmoidTable::lookup(Vec3 rgb) const {
    for (int c = 0; c < 3; ++c) rgb[c] = std::clamp(rgb[c], 0.0f, 1.0f);
    const int m = rgb.x >= rgb.y && rgb.x >= rgb.z ? 0 : (rgb.y >= rgb.z ? 1 : 2);
    const float z = rgb[m];
    SigmoidPolynomial out;
    if (z <= 0) {
        out.c = {0, 0, -std::numeric_limits<float>::infinity()};
        return out;
    }
    const float xf = xy_to_grid(rgb[(m + 1) % 3] / z, res_), yf = xy_to_grid(rgb[(m + 2) % 3] / z, res_);
    const int xi = std::min(int(xf), res_ - 2), yi = std::min(int(yf), res_ - 2);
    const int zi = std::clamp(int(std::upper_bound(z_.begin(), z_.end(), z) - z_.begin()) - 1, 0, res_ - 2);
    const float dx = xf - float(xi), dy = yf - float(yi);
    const float dz = (z - z_[size_t(zi)]) / (z_[size_t(zi) + 1] - z_[size_t(zi)]);
    for (int i = 0; i < 3; ++i) {
        const auto co = [&](int a, int b, int d) {
            return coeffs_[index(m, zi + a, yi + b, xi + d)].c[size_t(i)];
        };
        const float c00 = co(0, 0, 0) * (1 - dx) + co(0, 0, 1) * dx,
                    c01 = co(0, 1, 0) * (1 - dx) + co(0, 1, 1) * dx;
        const float c10 = co(1, 0, 0) * (1 - dx) + co(1, 0, 1) * dx,
                    c11 = co(1, 1, 0) * (1 - dx) + co(1, 1, 1) * dx;
        out.c[size_t(i)] = (c00 * (1 - dy) + c01 * dy) * (1 - dz) + (c10 * (1 - dy) + c11 * dy) * dz;
    }
    return out;
}

SigmoidPolynomial RgbSigmoidTable::exact(Vec3 rgb) const {
    for (int c = 0; c < 3; ++c) rgb[c] = std::clamp(rgb[c], 0.0f, 1.0f);
    SigmoidPolynomial s;
    if (std::min({rgb.x, rgb.y, rgb.z}) >= 1) {  // white: the sigmoid's limit at +infinity
        s.c = {0, 0, std::numeric_limits<float>::infinity()};
        return s;
    }
    s = lookup(rgb);
    if (std::isinf(s.c[2])) return s;  // black
    fit_sigmoid(rgb, s, 16);
    return s;
}

std::vector<uint8_t> RgbSigmoidTable::bytes() const {
    std::vector<uint8_t> out(8 + 8 + coeffs_.size() * 3 * sizeof(float));
    std::memcpy(out.data(), "PHOSRGBS", 8);
    const uint32_t header[2] = {1, uint32_t(res_)};
    std::memcpy(out.data() + 8, header, 8);
    uint8_t* p = out.data() + 16;
    for (const SigmoidPolynomial& s : coeffs_) {
        std::memcpy(p, s.c.data(), 3 * sizeof(float));
        p += 3 * sizeof(float);
    }
    return out;
}

RgbSigmoidTable RgbSigmoidTable::from_bytes(const uint8_t* data, size_t size) {
    uint32_t header[2];
    if (size < 16 || std::memcmp(data, "PHOSRGBS", 8) != 0)
        throw std::runtime_error("RGB sigmoid table: bad header");
    std::memcpy(header, data + 8, 8);
    const int res = int(header[1]);
    const size_t n = size_t(3) * size_t(res) * size_t(res) * size_t(res);
    if (header[0] != 1 || res < 2 || size != 16 + n * 3 * sizeof(float))
        throw std::runtime_error("RGB sigmoid table: bad version or size");
    RgbSigmoidTable t;
    t.res_ = res;
    t.z_.resize(size_t(res));
    for (int k = 0; k < res; ++k) t.z_[size_t(k)] = z_grid(k, res);
    t.coeffs_.resize(n);
    const uint8_t* p = data + 16;
    for (SigmoidPolynomial& s : t.coeffs_) {
        std::memcpy(s.c.data(), p, 3 * sizeof(float));
        p += 3 * sizeof(float);
    }
    return t;
}

}  // namespace phos::spectrum
