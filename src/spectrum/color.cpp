// Colour-matching, and the sRGB matrices from the primaries (see color.h).
#include "spectrum/color.h"

#include <cmath>

#include "spectrum/blackbody.h"
#include "spectrum/cie_tables.h"
#include "spectrum/rgb_spectrum.h"

namespace phos::spectrum {

namespace {

// Linear interpolation in a table sampled at every nanometre from kCieMin.
float lookup(const float* table, float lambda) {
    const float x = lambda - float(kCieMin);
    if (!(x >= 0 && x <= float(kCieSamples - 1))) return 0;
    const int i = std::min(int(x), kCieSamples - 2);
    const float t = x - float(i);
    return table[i] * (1 - t) + table[i + 1] * t;
}

Mat3 inverse(const Mat3& m) {
    const double a = m[0][0], b = m[0][1], c = m[0][2], d = m[1][0], e = m[1][1], f = m[1][2], g = m[2][0],
                 h = m[2][1], k = m[2][2];
    const double A = e * k - f * h, B = -(d * k - f * g), C = d * h - e * g;
    const double det = a * A + b * B + c * C;
    Mat3 r;
    r[0] = {A / det, -(b * k - c * h) / det, (b * f - c * e) / det};
    r[1] = {B / det, (a * k - c * g) / det, -(a * f - c * d) / det};
    r[2] = {C / det, -(a * h - b * g) / det, (a * e - b * d) / det};
    return r;
}

// The RGB -> XYZ matrix of primaries (x, y) whose white (x, y) has Y = 1: each primary's XYZ
// column scaled so that the three sum to the white.
Mat3 rgb_to_xyz_from(const double prim[3][2], const double white[2]) {
    Mat3 p;
    for (int j = 0; j < 3; ++j) {
        const double x = prim[j][0], y = prim[j][1];
        p[0][size_t(j)] = x / y;
        p[1][size_t(j)] = 1;
        p[2][size_t(j)] = (1 - x - y) / y;
    }
    const double W[3] = {white[0] / white[1], 1, (1 - white[0] - white[1]) / white[1]};
    const Mat3 pi = inverse(p);
    double s[3];
    for (int j = 0; j < 3; ++j)
        s[j] = pi[size_t(j)][0] * W[0] + pi[size_t(j)][1] * W[1] + pi[size_t(j)][2] * W[2];
    Mat3 m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[size_t(i)][size_t(j)] = p[size_t(i)][size_t(j)] * s[j];
    return m;
}

}  // namespace

Vec3 cie_xyz(float lambda) { return {lookup(kCieX, lambda), lookup(kCieY, lambda), lookup(kCieZ, lambda)}; }

float d65(float lambda) { return lookup(kCieD65, lambda); }

Vec3 to_xyz(const SampledSpectrum& L, const SampledWavelengths& w) {
    double X = 0, Y = 0, Z = 0;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        if (!(w.pdf(i) > 0)) continue;
        const Vec3 c = cie_xyz(w[i]);
        const double v = double(L[i]) / double(w.pdf(i));
        X += c.x * v, Y += c.y * v, Z += c.z * v;
    }
    const double s = 1.0 / (kSpectrumSamples * kCieYIntegral);
    return {float(X * s), float(Y * s), float(Z * s)};
}

Rgb to_srgb(const SampledSpectrum& L, const SampledWavelengths& w) {
    static const std::array<float, 9> m = [] {
        std::array<float, 9> f;
        for (size_t i = 0; i < 9; ++i)
            f[i] = float(xyz_to_srgb()[i / 3][i % 3] / (kSpectrumSamples * kCieYIntegral));
        return f;
    }();
    float X = 0, Y = 0, Z = 0;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        if (!(w.pdf(i) > 0) || L[i] == 0) continue;
        const Vec3 c = cie_xyz(w[i]);
        const float v = L[i] / w.pdf(i);
        X += c.x * v, Y += c.y * v, Z += c.z * v;
    }
    return {m[0] * X + m[1] * Y + m[2] * Z, m[3] * X + m[4] * Y + m[5] * Z, m[6] * X + m[7] * Y + m[8] * Z};
}

ColourWeights colour_weights(const SampledSpectrum& L, const SampledWavelengths& w) {
    static_assert(kSpectrumSamples == 4);
    const Mat3& m = xyz_to_srgb();
    ColourWeights cw;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        if (!(w.pdf(i) > 0) || L[i] == 0) {
            cw.w[size_t(i)] = Rgb(0.0f);
            continue;
        }
        const Vec3 c =
            cie_xyz(w[i]) * float(double(L[i]) / (double(w.pdf(i)) * kSpectrumSamples * kCieYIntegral));
        const Vec3 rgb = apply(m, c);
        cw.w[size_t(i)] = Rgb(rgb.x, rgb.y, rgb.z);
    }
    return cw;
}

Rgb colour_through(const SampledSpectrum& beta, const SampledWavelengths& lambda, Rgb colour) {
    if (beta.is_flat() && !lambda.secondary_terminated()) return colour * beta[0];
    if (beta.is_black()) return Rgb(0.0f);
    const RgbSpectrum s(colour, RgbSpectrum::Use::Illuminant, RgbSpectrum::Fit::Table);
    return to_srgb(beta * s.sample(lambda), lambda);
}

Vec3 integrate_xyz(const std::function<double(double lambda)>& S) {
    double X = 0, Y = 0, Z = 0;
    for (int i = 0; i < kCieSamples; ++i) {
        const double v = S(double(kCieMin + i));
        X += kCieX[i] * v, Y += kCieY[i] * v, Z += kCieZ[i] * v;
    }
    return {float(X / kCieYIntegral), float(Y / kCieYIntegral), float(Z / kCieYIntegral)};
}

const Mat3& srgb_to_xyz() {
    static const Mat3 m = [] {
        // The white is the chromaticity of the D65 table itself (the standard's (0.3127, 0.3290) to
        // within 3e-5), as pbrt-v4 derives it, so that D65 light maps to RGB (1, 1, 1) exactly.
        const double prim[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
        const Vec3 w = integrate_xyz([](double l) { return double(d65(float(l))); });
        const double sum = double(w.x) + double(w.y) + double(w.z);
        const double white[2] = {w.x / sum, w.y / sum};
        return rgb_to_xyz_from(prim, white);
    }();
    return m;
}

const Mat3& xyz_to_srgb() {
    static const Mat3 m = inverse(srgb_to_xyz());
    return m;
}

Vec3 apply(const Mat3& m, Vec3 v) {
    double r[3];
    for (int i = 0; i < 3; ++i) r[i] = m[size_t(i)][0] * v.x + m[size_t(i)][1] * v.y + m[size_t(i)][2] * v.z;
    return {float(r[0]), float(r[1]), float(r[2])};
}

namespace {

Mat3 multiply(const Mat3& a, const Mat3& b) {
    Mat3 m{};
    for (size_t i = 0; i < 3; ++i)
        for (size_t j = 0; j < 3; ++j)
            for (size_t k = 0; k < 3; ++k) m[i][j] += a[i][k] * b[k][j];
    return m;
}

std::array<double, 3> times(const Mat3& m, const std::array<double, 3>& v) {
    std::array<double, 3> r{};
    for (size_t i = 0; i < 3; ++i) r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
    return r;
}

// XYZ -> the Bradford transform's cone-like responses (Lam 1985, as CIECAM97s uses it).
const Mat3 kBradford = {{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};

}  // namespace

Vec3 white_balance_source(float kelvin) {
    const double cct = double(kelvin) * 1.4388 / 1.4380;
    if (cct < 4000) {
        const Blackbody b(cct);
        const Vec3 c = integrate_xyz([&](double l) { return double(b(float(l))); });
        return c / c.y;
    }
    // The CIE daylight locus (CIE 15): x from the temperature, y from x.
    const double t = cct, t2 = t * t, t3 = t2 * t;
    const double x = cct <= 7000 ? -4.6070e9 / t3 + 2.9678e6 / t2 + 0.09911e3 / t + 0.244063
                                 : -2.0064e9 / t3 + 1.9018e6 / t2 + 0.24748e3 / t + 0.237040;
    const double y = -3.0 * x * x + 2.870 * x - 0.275;
    return {float(x / y), 1.0f, float((1 - x - y) / y)};
}

Mat3 white_balance(float source_kelvin) {
    if (!(source_kelvin > 0)) return {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    const Vec3 s = white_balance_source(source_kelvin);
    const std::array<double, 3> src = times(kBradford, {double(s.x), double(s.y), double(s.z)});
    const std::array<double, 3> dst = times(kBradford, times(srgb_to_xyz(), {1.0, 1.0, 1.0}));
    Mat3 scale{};
    for (size_t i = 0; i < 3; ++i) scale[i][i] = dst[i] / src[i];
    const Mat3 xyz = multiply(inverse(kBradford), multiply(scale, kBradford));
    return multiply(xyz_to_srgb(), multiply(xyz, srgb_to_xyz()));
}

}  // namespace phos::spectrum
