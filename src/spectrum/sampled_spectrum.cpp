// Wavelength sampling for spectral paths (see sampled_spectrum.h).
#include "spectrum/sampled_spectrum.h"

#include <algorithm>

namespace phos::spectrum {

namespace {

// p(λ) ∝ sech²(a (λ − c)) on [kLambdaMin, kLambdaMax]; its CDF is (tanh(a (λ − c)) − t0) / (t1 − t0).
constexpr double kA = 0.0072, kC = 538.0;
const double kT0 = std::tanh(kA * (double(kLambdaMin) - kC));
const double kT1 = std::tanh(kA * (double(kLambdaMax) - kC));

float fraction(float u) { return u - std::floor(u); }

}  // namespace

float visible_pdf(float lambda) {
    if (!(lambda >= kLambdaMin && lambda <= kLambdaMax)) return 0;
    const double ch = std::cosh(kA * (double(lambda) - kC));
    return float(kA / ((kT1 - kT0) * ch * ch));
}

float sample_visible(float u) {
    const double t = kT0 + double(u) * (kT1 - kT0);
    return std::clamp(float(kC + std::atanh(t) / kA), kLambdaMin, kLambdaMax);
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

SampledWavelengths SampledWavelengths::visible(float u) {
    SampledWavelengths w;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        w.lambda_[size_t(i)] = sample_visible(fraction(u + float(i) / kSpectrumSamples));
        w.pdf_[size_t(i)] = visible_pdf(w.lambda_[size_t(i)]);
    }
    return w;
}

void SampledWavelengths::terminate_secondary() {
    if (secondary_terminated()) return;
    for (int i = 1; i < kSpectrumSamples; ++i) pdf_[size_t(i)] = 0;
    pdf_[0] /= kSpectrumSamples;
}

}  // namespace phos::spectrum
