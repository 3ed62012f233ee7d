// A spectrum tabulated at every nanometre of [kLambdaMin, kLambdaMax] and interpolated linearly
// between (pbrt-v4's lights hold their emission so, as DenselySampledSpectrum): what a light's
// emission is evaluated through, four table reads per path instead of the source's own formula
// (a sigmoid times D65, a blackbody, a search in a measured table). A constant stays exactly
// constant; anything else differs from its source by the interpolation between nanometres only.
#pragma once

#include <array>

#include "spectrum/distribution.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::spectrum {

class DenseSpectrum {
public:
    static constexpr int kSamples = int(kLambdaMax - kLambdaMin) + 1;

    DenseSpectrum() = default;  // 0 everywhere
    explicit DenseSpectrum(const Distribution& d) {
        for (int i = 0; i < kSamples; ++i) value_[size_t(i)] = d(kLambdaMin + float(i));
        value_[kSamples] = value_[kSamples - 1];  // read (times 0) at kLambdaMax itself
    }

    float operator()(float lambda) const {
        const float x = lambda - kLambdaMin;
        if (!(x >= 0 && x <= float(kSamples - 1))) return 0;
        const int i = int(x);
        const float f = x - float(i);
        return value_[size_t(i)] + f * (value_[size_t(i) + 1] - value_[size_t(i)]);
    }
    SampledSpectrum sample(const SampledWavelengths& w) const {
        SampledSpectrum s;
        for (int k = 0; k < kSpectrumSamples; ++k) s[k] = (*this)(w[k]);
        return s;
    }

private:
    std::array<float, kSamples + 1> value_{};
};

}  // namespace phos::spectrum
