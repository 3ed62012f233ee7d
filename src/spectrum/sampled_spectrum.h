// Spectra as a path carries them: the values at the path's kSpectrumSamples wavelengths (hero
// wavelength sampling, Wilkie, Hanika, Weidlich & Purgathofer 2014), and the wavelengths with
// their sampling densities. The hero wavelength is lambda[0]; the others are spaced evenly over
// [kLambdaMin, kLambdaMax) from it (rotated by (kLambdaMax - kLambdaMin) / n, wrapping around), so
// one uniform number stratifies all four, and each is distributed as the hero is.
#pragma once

#include <array>
#include <cmath>

namespace phos::spectrum {

inline constexpr int kSpectrumSamples = 4;
inline constexpr float kLambdaMin = 360.0f, kLambdaMax = 830.0f;  // nm

struct SampledSpectrum {
    std::array<float, kSpectrumSamples> v{};

    SampledSpectrum() = default;
    explicit SampledSpectrum(float c) { v.fill(c); }
    float& operator[](int i) { return v[size_t(i)]; }
    float operator[](int i) const { return v[size_t(i)]; }

#define PHOS_SPECTRUM_OP(op)                                                           \
    SampledSpectrum& operator op##=(const SampledSpectrum& o) {                        \
        for (int i = 0; i < kSpectrumSamples; ++i) v[size_t(i)] op## = o.v[size_t(i)]; \
        return *this;                                                                  \
    }                                                                                  \
    SampledSpectrum operator op(const SampledSpectrum& o) const { return SampledSpectrum(*this) op## = o; }
    PHOS_SPECTRUM_OP(+)
    PHOS_SPECTRUM_OP(-)
    PHOS_SPECTRUM_OP(*)
#undef PHOS_SPECTRUM_OP
    SampledSpectrum operator*(float s) const {
        SampledSpectrum r = *this;
        for (float& x : r.v) x *= s;
        return r;
    }
    // Division that leaves 0 where the divisor is 0 (a wavelength whose density is 0).
    SampledSpectrum safe_div(const SampledSpectrum& o) const {
        SampledSpectrum r;
        for (int i = 0; i < kSpectrumSamples; ++i) r[i] = o[i] != 0 ? v[size_t(i)] / o[i] : 0.0f;
        return r;
    }
    bool is_black() const {
        for (float x : v)
            if (x != 0) return false;
        return true;
    }
    float average() const {
        float s = 0;
        for (float x : v) s += x;
        return s / kSpectrumSamples;
    }
    float max() const {
        float m = v[0];
        for (float x : v) m = std::fmax(m, x);
        return m;
    }
};

// The density the visible-wavelength sampling uses, over [kLambdaMin, kLambdaMax] in 1/nm:
// p(λ) ∝ 1 / cosh²(0.0072 (λ − 538)), a smooth bump over the colour-matching functions' support
// (Radziszewski, Boryczko & Alda 2009, as pbrt-v4 samples wavelengths); normalised in
// visible_pdf over the interval, and sampled exactly by its inverse CDF.
float visible_pdf(float lambda);
float sample_visible(float u);  // u in [0, 1)

class SampledWavelengths {
public:
    // Uniform over [kLambdaMin, kLambdaMax]: the hero at u, the others stratified from it.
    static SampledWavelengths uniform(float u);
    // The visible density above for each of the four (the hero at u, the others at u + k / n mod 1
    // in the density's CDF: stratified in it).
    static SampledWavelengths visible(float u);

    float operator[](int i) const { return lambda_[size_t(i)]; }
    float pdf(int i) const { return pdf_[size_t(i)]; }
    SampledSpectrum pdf() const {
        SampledSpectrum p;
        p.v = pdf_;
        return p;
    }
    // A path that met a wavelength-dependent specular interface goes on with the hero alone
    // (the others' densities become 0, the hero's is divided by n: it now stands for the single
    // wavelength estimate n times over, keeping the estimator unbiased).
    void terminate_secondary();
    bool secondary_terminated() const { return pdf_[1] == 0; }

private:
    std::array<float, kSpectrumSamples> lambda_{}, pdf_{};
};

}  // namespace phos::spectrum
