// Wavelength sampling for spectral paths (see sampled_spectrum.h).
#include "spectrum/sampled_spectrum.h"

#include <algorithm>

#include "spectrum/cie_tables.h"

namespace phos::spectrum {

namespace {

// The visible density is a mixture: kSechShare of p1(λ) ∝ sech²(a (λ − c)) (Radziszewski, Boryczko &
// Alda 2009, as pbrt-v4 samples wavelengths; its CDF is (tanh(a (λ − c)) − t0) / (t1 − t0)) and the
// rest of p2(λ) ∝ x̄ + ȳ + z̄ (the colour-matching functions' sum, linear between the 1 nm samples).
// p1 alone follows ȳ and leaves the blue end, where z̄ and the sRGB blue lie, thin: white light's
// blue channel had a relative variance of 0.34 per path; the mixture has 0.06 / 0.01 / 0.01 (D65
// through linear sRGB, four stratified wavelengths), 4.5 times less in all.
constexpr double kA = 0.0072, kC = 538.0, kSechShare = 0.6;
// The sech² CDF's ends (functions, not globals: other files' static initialisers sample wavelengths).
double t0() { return std::tanh(kA * (double(kLambdaMin) - kC)); }
double t1() { return std::tanh(kA * (double(kLambdaMax) - kC)); }

// x̄ + ȳ + z̄ at 1 nm and its running integral (trapezoids), normalised to 1 over [360, 830].
struct CmfSum {
    std::array<double, kCieSamples> value{}, integral{};
    CmfSum() {
        for (int i = 0; i < kCieSamples; ++i) value[size_t(i)] = double(kCieX[i]) + kCieY[i] + kCieZ[i];
        for (int i = 1; i < kCieSamples; ++i)
            integral[size_t(i)] = integral[size_t(i) - 1] + 0.5 * (value[size_t(i) - 1] + value[size_t(i)]);
        const double total = integral[kCieSamples - 1];
        for (int i = 0; i < kCieSamples; ++i) value[size_t(i)] /= total, integral[size_t(i)] /= total;
    }
};
const CmfSum& cmf_sum() {
    static const CmfSum c;
    return c;
}

// The mixture's CDF at λ in [kLambdaMin, kLambdaMax].
double visible_cdf(double lambda) {
    const double sech = (std::tanh(kA * (lambda - kC)) - t0()) / (t1() - t0());
    const CmfSum& c = cmf_sum();
    const double x = lambda - kCieMin;
    const int i = std::clamp(int(x), 0, kCieSamples - 2);
    const double f = x - i, v0 = c.value[size_t(i)], v1 = c.value[size_t(i) + 1];
    const double cmf = c.integral[size_t(i)] + f * (v0 + 0.5 * f * (v1 - v0));
    return kSechShare * sech + (1 - kSechShare) * cmf;
}

float fraction(float u) { return u - std::floor(u); }

}  // namespace

float visible_pdf(float lambda) {
    if (!(lambda >= kLambdaMin && lambda <= kLambdaMax)) return 0;
    const double ch = std::cosh(kA * (double(lambda) - kC));
    const double sech = kA / ((t1() - t0()) * ch * ch);
    const CmfSum& c = cmf_sum();
    const double x = double(lambda) - kCieMin;
    const int i = std::clamp(int(x), 0, kCieSamples - 2);
    const double cmf = c.value[size_t(i)] + (x - i) * (c.value[size_t(i) + 1] - c.value[size_t(i)]);
    return float(kSechShare * sech + (1 - kSechShare) * cmf);
}

float sample_visible(float u) {
    // Bisection on the CDF (only the sampling table and tests call it).
    double lo = kLambdaMin, hi = kLambdaMax;
    for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        (visible_cdf(mid) < double(u) ? lo : hi) = mid;
    }
    return float(0.5 * (lo + hi));
}

SampledWavelengths SampledWavelengths::uniform(float u) {
    SampledWavelengths w;
    const float range = kLambdaMax - kLambdaMin;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        w.lambda_[size_t(i)] = kLambdaMin + range * fraction(u + float(i) / kSpectrumSamples);
        w.pdf_[size_t(i)] = 1 / range;
    }
    return w;
}

namespace {

// The inverse CDF at u = k / kVisibleSegments and the density of each segment between them.
struct VisibleTable {
    std::array<float, kVisibleSegments + 1> lambda;
    std::array<float, kVisibleSegments> pdf;
    VisibleTable() {
        for (int k = 0; k <= kVisibleSegments; ++k)
            lambda[size_t(k)] =
                k == kVisibleSegments ? kLambdaMax : sample_visible(float(k) / kVisibleSegments);
        lambda[0] = kLambdaMin;
        for (int k = 0; k < kVisibleSegments; ++k)
            pdf[size_t(k)] = 1.0f / (float(kVisibleSegments) * (lambda[size_t(k) + 1] - lambda[size_t(k)]));
    }
};
const VisibleTable& visible_table() {
    static const VisibleTable t;
    return t;
}

}  // namespace

SampledWavelengths SampledWavelengths::from_code(uint16_t code, bool secondary_terminated) {
    constexpr int kSteps = kWavelengthCodes / kVisibleSegments;
    const VisibleTable& t = visible_table();
    SampledWavelengths w;
    w.code_ = code;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        const int c = (int(code) + i * (kWavelengthCodes / kSpectrumSamples)) & (kWavelengthCodes - 1);
        const size_t k = size_t(c / kSteps);
        const float f = (float(c % kSteps) + 0.5f) * (1.0f / kSteps);  // the middle of the code's step
        w.lambda_[size_t(i)] = t.lambda[k] + f * (t.lambda[k + 1] - t.lambda[k]);
        w.pdf_[size_t(i)] = t.pdf[k];
    }
    if (secondary_terminated) w.terminate_secondary();
    return w;
}

float SampledWavelengths::visible_sampling_pdf(float lambda) {
    if (!(lambda >= kLambdaMin && lambda <= kLambdaMax)) return 0;
    const VisibleTable& t = visible_table();
    const auto it = std::upper_bound(t.lambda.begin(), t.lambda.end(), lambda);
    const size_t k = std::min(size_t(it - t.lambda.begin()), size_t(kVisibleSegments)) - 1;
    return t.pdf[k];
}

void SampledWavelengths::terminate_secondary() {
    if (secondary_terminated()) return;
    for (int i = 1; i < kSpectrumSamples; ++i) pdf_[size_t(i)] = 0;
    pdf_[0] /= kSpectrumSamples;
}

}  // namespace phos::spectrum
