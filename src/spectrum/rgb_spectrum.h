// An RGB value (linear sRGB) as a smooth spectrum, in the three readings pbrt-v4 gives RGB values
// (Jakob & Hanika 2019 through RgbSigmoidTable):
//  - Albedo: a reflectance or transmittance, s(λ) = S(poly(λ)) within [0, 1] at every wavelength
//    for components in [0, 1] (a component above 1 is read as Unbounded, so no energy is lost);
//  - Unbounded: m S(poly(λ)) with the polynomial fitted to rgb / (2m), m the largest component
//    (indices, coefficients of media);
//  - Illuminant: the Unbounded spectrum times the colour space's illuminant (D65, scaled to
//    luminance 1), so that an emitter's RGB comes back as that RGB through the film.
// A grey value v is the flat spectrum v exactly (polynomial 0, scale 2v). Its RGB through the film
// equals the input within the table's accuracy (rgb_sigmoid.h).
#pragma once

#include <immintrin.h>

#include "core/vec.h"
#include "spectrum/color.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::spectrum {

class RgbSpectrum {
public:
    enum class Use { Albedo, Unbounded, Illuminant };
    // Exact: the fit refined per value (scene constants); Table: the table's interpolation (per
    // texel or per hit, 3e-3 from the RGB).
    enum class Fit { Exact, Table };

    RgbSpectrum() = default;  // 0 at every wavelength
    RgbSpectrum(Rgb rgb, Use use, Fit fit = Fit::Exact);

    float operator()(float lambda) const;
    // operator() at the four wavelengths (inline below: every BSDF runs it).
    SampledSpectrum sample(const std::array<float, kSpectrumSamples>& lambda) const;
    SampledSpectrum sample(const SampledWavelengths& w) const { return sample(w.lambdas()); }
    bool is_black() const { return scale_ == 0; }

private:
    float c0_ = 0, c1_ = 0, c2_ = 0;  // the sigmoid's polynomial in t = (λ − 360) / 470
    float scale_ = 0;                 // multiplies S(poly): 1 (albedo), 2m (unbounded, illuminant)
    bool illuminant_ = false;
};

inline SampledSpectrum RgbSpectrum::sample(const std::array<float, kSpectrumSamples>& w) const {
    // operator() at the four wavelengths in the lanes of one SSE register; x is clamped where x²
    // would overflow (S is then 0 or 1 to float precision anyway).
    static_assert(kSpectrumSamples == 4);
    SampledSpectrum s;
    if (scale_ == 0) return s;
    if (c0_ == 0 && c1_ == 0 && c2_ == 0 && !illuminant_)
        return SampledSpectrum(scale_ * 0.5f);  // grey: flat
    const __m128 lambda = _mm_loadu_ps(w.data());
    const __m128 t = _mm_mul_ps(_mm_sub_ps(lambda, _mm_set1_ps(kLambdaMin)),
                                _mm_set1_ps(1.0f / (kLambdaMax - kLambdaMin)));
    __m128 x = _mm_add_ps(_mm_mul_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(c0_), t), _mm_set1_ps(c1_)), t),
                          _mm_set1_ps(c2_));
    x = _mm_max_ps(_mm_min_ps(x, _mm_set1_ps(1e15f)), _mm_set1_ps(-1e15f));
    const __m128 root = _mm_sqrt_ps(_mm_add_ps(_mm_set1_ps(1.0f), _mm_mul_ps(x, x)));
    const __m128 sig = _mm_add_ps(_mm_set1_ps(0.5f), _mm_div_ps(x, _mm_add_ps(root, root)));
    _mm_storeu_ps(s.v.data(), _mm_mul_ps(sig, _mm_set1_ps(scale_)));
    if (illuminant_) s *= d65_luminance_1(w);
    return s;
}

}  // namespace phos::spectrum
