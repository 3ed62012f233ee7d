// RGB values as spectra (see rgb_spectrum.h).
#include "spectrum/rgb_spectrum.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>

#include "spectrum/cie_tables.h"
#include "spectrum/color.h"
#include "spectrum/rgb_sigmoid.h"

namespace phos::spectrum {

namespace {

float sigmoid_of(float c0, float c1, float c2, float lambda) {
    const float t = (lambda - kLambdaMin) * (1.0f / (kLambdaMax - kLambdaMin));
    const float x = (c0 * t + c1) * t + c2;
    if (!std::isfinite(x)) return x > 0 ? 1.0f : 0.0f;
    return 0.5f + x / (2 * std::sqrt(1 + x * x));
}

}  // namespace

RgbSpectrum::RgbSpectrum(Rgb rgb, Use use, Fit fit) {
    rgb = Rgb(std::max(rgb.r, 0.0f), std::max(rgb.g, 0.0f), std::max(rgb.b, 0.0f));
    const float m = rgb.max();
    illuminant_ = use == Use::Illuminant;
    if (m == 0) return;                      // black
    if (rgb.r == rgb.g && rgb.g == rgb.b) {  // flat: S(0) = 1/2
        scale_ = 2 * m;
        return;
    }
    Vec3 target(rgb.r, rgb.g, rgb.b);
    if (use == Use::Albedo && m <= 1) {
        scale_ = 1;
    } else {
        scale_ = 2 * m;
        target = target / scale_;
    }
    const RgbSigmoidTable& table = RgbSigmoidTable::srgb();
    const SigmoidPolynomial p = fit == Fit::Exact ? table.exact(target) : table.lookup(target);
    c0_ = p.c[0], c1_ = p.c[1], c2_ = p.c[2];
}

float RgbSpectrum::operator()(float lambda) const {
    if (scale_ == 0) return 0;
    const float v = scale_ * sigmoid_of(c0_, c1_, c2_, lambda);
    return illuminant_ ? v * d65_luminance_1(lambda) : v;
}

SampledSpectrum RgbSpectrum::sample(const SampledWavelengths& w) const {
    // operator() at the four wavelengths in the lanes of one SSE register (every BSDF evaluation
    // and emission runs this); x is clamped where x² would overflow (S is then 0 or 1 to float
    // precision anyway).
    static_assert(kSpectrumSamples == 4);
    SampledSpectrum s;
    if (scale_ == 0) return s;
    if (c0_ == 0 && c1_ == 0 && c2_ == 0 && !illuminant_)
        return SampledSpectrum(scale_ * 0.5f);  // grey: flat
    const __m128 lambda = _mm_setr_ps(w[0], w[1], w[2], w[3]);
    const __m128 t = _mm_mul_ps(_mm_sub_ps(lambda, _mm_set1_ps(kLambdaMin)),
                                _mm_set1_ps(1.0f / (kLambdaMax - kLambdaMin)));
    __m128 x = _mm_add_ps(_mm_mul_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(c0_), t), _mm_set1_ps(c1_)), t),
                          _mm_set1_ps(c2_));
    x = _mm_max_ps(_mm_min_ps(x, _mm_set1_ps(1e15f)), _mm_set1_ps(-1e15f));
    const __m128 root = _mm_sqrt_ps(_mm_add_ps(_mm_set1_ps(1.0f), _mm_mul_ps(x, x)));
    const __m128 sig = _mm_add_ps(_mm_set1_ps(0.5f), _mm_div_ps(x, _mm_add_ps(root, root)));
    _mm_storeu_ps(s.v.data(), _mm_mul_ps(sig, _mm_set1_ps(scale_)));
    if (illuminant_)
        for (int i = 0; i < kSpectrumSamples; ++i) s[i] *= d65_luminance_1(w[i]);
    return s;
}

float d65_luminance_1(float lambda) {
    static const float k = [] {
        double y = 0;
        for (int i = 0; i < kCieSamples; ++i) y += double(kCieD65[i]) * kCieY[i];
        return float(kCieYIntegral / y);
    }();
    return d65(lambda) * k;
}

}  // namespace phos::spectrum
