// Colour-matching, and the sRGB matrices from the primaries (see color.h).
#include "spectrum/color.h"

#include <immintrin.h>

#include <algorithm>
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

namespace {

// Per nanometre: the linear sRGB matching functions xyz_to_srgb() (x̄, ȳ, z̄) / (n ∫ȳ) and D65 at
// luminance 1, a row of four floats, so that one SSE interpolation gives what the film adds per
// unit of L / p at a wavelength and the colour space's illuminant there. (The matrix is linear,
// so interpolating its products is interpolating x̄, ȳ, z̄ and applying it.)
struct MatchingTable {
    alignas(16) float row[kCieSamples][4];
    MatchingTable() {
        const Mat3& m = xyz_to_srgb();
        const double s = 1.0 / (kSpectrumSamples * kCieYIntegral);
        double y = 0;
        for (int i = 0; i < kCieSamples; ++i) y += double(kCieD65[i]) * kCieY[i];
        const double d65_scale = kCieYIntegral / y;
        for (int i = 0; i < kCieSamples; ++i) {
            const double xyz[3] = {kCieX[i], kCieY[i], kCieZ[i]};
            for (size_t c = 0; c < 3; ++c)
                row[i][c] = float((m[c][0] * xyz[0] + m[c][1] * xyz[1] + m[c][2] * xyz[2]) * s);
            row[i][3] = float(kCieD65[i] * d65_scale);
        }
    }
};
const MatchingTable& matching_table() {
    static const MatchingTable t;
    return t;
}

// The table's row at `lambda`, linear between nanometres; 0 outside [kCieMin, kCieMax].
inline __m128 matching_at(const MatchingTable& t, float lambda) {
    const float x = lambda - float(kCieMin);
    if (!(x >= 0 && x <= float(kCieSamples - 1))) return _mm_setzero_ps();
    const int i = std::min(int(x), kCieSamples - 2);
    const __m128 f = _mm_set1_ps(x - float(i));
    const __m128 a = _mm_load_ps(t.row[i]), b = _mm_load_ps(t.row[i + 1]);
    return _mm_add_ps(a, _mm_mul_ps(f, _mm_sub_ps(b, a)));
}

// The table's D65 (luminance 1) at `lambda`: its row's last lane.
inline float d65_at(const MatchingTable& t, float lambda) {
    const __m128 r = matching_at(t, lambda);
    return _mm_cvtss_f32(_mm_shuffle_ps(r, r, _MM_SHUFFLE(3, 3, 3, 3)));
}

}  // namespace

float d65_luminance_1(float lambda) { return d65_at(matching_table(), lambda); }

SampledSpectrum d65_luminance_1(const std::array<float, kSpectrumSamples>& w) {
    const MatchingTable& t = matching_table();
    SampledSpectrum s;
    for (int i = 0; i < kSpectrumSamples; ++i) s[i] = d65_at(t, w[size_t(i)]);
    return s;
}

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
    const MatchingTable& t = matching_table();
    __m128 sum = _mm_setzero_ps();
    for (int i = 0; i < kSpectrumSamples; ++i) {
        if (!(w.pdf(i) > 0) || L[i] == 0) continue;
        sum = _mm_add_ps(sum, _mm_mul_ps(matching_at(t, w[i]), _mm_set1_ps(L[i] / w.pdf(i))));
    }
    alignas(16) float c[4];
    _mm_store_ps(c, sum);
    return {c[0], c[1], c[2]};
}

ColourWeights colour_weights(const SampledSpectrum& L, const SampledWavelengths& w) {
    static_assert(kSpectrumSamples == 4);
    const MatchingTable& t = matching_table();
    alignas(16) float c[kSpectrumSamples][4];  // wavelength i's (r, g, b, D65) weighed by L / p
    for (int i = 0; i < kSpectrumSamples; ++i) {
        const bool adds = w.pdf(i) > 0 && L[i] != 0;
        _mm_store_ps(
            c[i], adds ? _mm_mul_ps(matching_at(t, w[i]), _mm_set1_ps(L[i] / w.pdf(i))) : _mm_setzero_ps());
    }
    __m128 r0 = _mm_load_ps(c[0]), r1 = _mm_load_ps(c[1]), r2 = _mm_load_ps(c[2]), r3 = _mm_load_ps(c[3]);
    _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
    ColourWeights cw;
    _mm_store_ps(cw.rows[0].data(), r0);
    _mm_store_ps(cw.rows[1].data(), r1);
    _mm_store_ps(cw.rows[2].data(), r2);
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

std::optional<Mat3> rgb_space_to_srgb(const std::string& name, bool adapt_white) {
    static const double kD65[2] = {0.3127, 0.3290};
    static const double kAcesWhite[2] = {0.32168, 0.33767};
    static const double kRec2020[3][2] = {{0.708, 0.292}, {0.170, 0.797}, {0.131, 0.046}};
    static const double kDciP3[3][2] = {{0.680, 0.320}, {0.265, 0.690}, {0.150, 0.060}};
    static const double kAp0[3][2] = {{0.7347, 0.2653}, {0.0, 1.0}, {0.0001, -0.0770}};
    if (name == "srgb") return Mat3{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    const double(*prim)[2] = name == "rec2020"      ? kRec2020
                             : name == "dci-p3"     ? kDciP3
                             : name == "aces2065-1" ? kAp0
                                                    : nullptr;
    if (!prim) return std::nullopt;
    const double* white = prim == kAp0 ? kAcesWhite : kD65;
    Mat3 to_xyz = rgb_to_xyz_from(prim, white);
    if (adapt_white) {  // to sRGB's own white exactly (phos's D65 is the CIE table's)
        const std::array<double, 3> src = times(kBradford, times(to_xyz, {1.0, 1.0, 1.0}));
        const std::array<double, 3> dst = times(kBradford, times(srgb_to_xyz(), {1.0, 1.0, 1.0}));
        Mat3 scale{};
        for (size_t i = 0; i < 3; ++i) scale[i][i] = dst[i] / src[i];
        to_xyz = multiply(multiply(inverse(kBradford), multiply(scale, kBradford)), to_xyz);
    }
    return multiply(xyz_to_srgb(), to_xyz);
}

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
