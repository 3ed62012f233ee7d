// Spectra as a path carries them: the values at the path's kSpectrumSamples wavelengths (hero
// wavelength sampling, Wilkie, Hanika, Weidlich & Purgathofer 2014), and the wavelengths with
// their sampling densities. The hero wavelength is lambda[0]; the others are spaced evenly from it
// in the sampling density's CDF (u + k / n, wrapping around), so one uniform number stratifies all
// four, and each is distributed as the hero is.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "core/low_discrepancy.h"

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
    PHOS_SPECTRUM_OP(/)
#undef PHOS_SPECTRUM_OP
    SampledSpectrum& operator*=(float s) {
        for (float& x : v) x *= s;
        return *this;
    }
    SampledSpectrum operator*(float s) const { return SampledSpectrum(*this) *= s; }
    SampledSpectrum operator/(float s) const { return SampledSpectrum(*this) *= 1 / s; }
    friend SampledSpectrum operator*(float s, const SampledSpectrum& c) { return c * s; }
    bool operator==(const SampledSpectrum&) const = default;
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
    // The same value at every wavelength (what a throughput is until something coloured scales it).
    bool is_flat() const {
        for (float x : v)
            if (x != v[0]) return false;
        return true;
    }
    bool is_finite() const {
        for (float x : v)
            if (!std::isfinite(x)) return false;
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

inline SampledSpectrum exp(const SampledSpectrum& s) {
    SampledSpectrum r;
    for (int i = 0; i < kSpectrumSamples; ++i) r[i] = std::exp(s[i]);
    return r;
}

// The density the visible-wavelength sampling follows, over [kLambdaMin, kLambdaMax] in 1/nm: 0.6
// of 1 / cosh²(0.0072 (λ − 538)), a smooth bump over the colour-matching functions' support
// (Radziszewski, Boryczko & Alda 2009, as pbrt-v4 samples wavelengths), and 0.4 of x̄ + ȳ + z̄,
// which reaches the blue end the first leaves thin; each normalised over the interval.
// sample_visible is its inverse CDF.
float visible_pdf(float lambda);
float sample_visible(float u);  // u in [0, 1)

// Paths sample that density through a table: its inverse CDF at kVisibleSegments + 1 evenly spaced
// u, linear in between, so the density sampled is piecewise constant (within 3 % of
// visible_pdf) and both the wavelength and its density cost a table lookup. A path's u is a
// 16-bit code (kVisibleSegments segments of 64 steps), which is all a photon stores of its
// wavelengths.
inline constexpr int kVisibleSegments = 1024;
inline constexpr int kWavelengthCodes = 1 << 16;

class SampledWavelengths {
public:
    // Uniform over [kLambdaMin, kLambdaMax]: the hero at u, the others stratified from it.
    static SampledWavelengths uniform(float u);
    // The tabulated visible density above for each of the four: the hero at the code of u, the
    // others at code + k * 2^16 / n (mod 2^16), stratified in its CDF.
    static SampledWavelengths visible(float u) { return from_code(code_of(u)); }
    static SampledWavelengths from_code(uint16_t code, bool secondary_terminated = false);
    static uint16_t code_of(float u) { return uint16_t(std::fmin(u, 0.99999994f) * float(kWavelengthCodes)); }
    // The tabulated density at `lambda` (what visible() samples with).
    static float visible_sampling_pdf(float lambda);
    // Wavelengths with these values and density 1 each: where spectra are only evaluated (a BSDF
    // at a photon's wavelengths), never for an estimate's division by the densities.
    static SampledWavelengths at_values(const std::array<float, kSpectrumSamples>& lambda) {
        SampledWavelengths w;
        w.lambda_ = lambda;
        w.pdf_.fill(1.0f);
        return w;
    }

    float operator[](int i) const { return lambda_[size_t(i)]; }
    const std::array<float, kSpectrumSamples>& lambdas() const { return lambda_; }
    float pdf(int i) const { return pdf_[size_t(i)]; }
    SampledSpectrum pdf() const {
        SampledSpectrum p;
        p.v = pdf_;
        return p;
    }
    // The hero's code (visible(): the 16-bit u it was made from; uniform(): 0).
    uint16_t code() const { return code_; }
    // A path that met a wavelength-dependent specular interface goes on with the hero alone
    // (the others' densities become 0, the hero's is divided by n: it now stands for the single
    // wavelength estimate n times over, keeping the estimator unbiased).
    void terminate_secondary();
    bool secondary_terminated() const { return pdf_[1] == 0; }

private:
    std::array<float, kSpectrumSamples> lambda_{}, pdf_{};
    uint16_t code_ = 0;
};

// Point s of a stratified sequence of wavelength samples keyed by `key` (one per pixel), as the u of
// SampledWavelengths::visible(u). The four wavelengths of visible(u) repeat with period 1/4 in u
// (u and u + 1/4 give the same four, only the hero differs), so the sequence stratifies u within a
// quarter (a padded 1D dimension: core/low_discrepancy.h) and picks the quarter, which wavelength
// is the hero, at random: over a pixel's samples the wavelengths then cover the spectrum evenly,
// while each sample's u stays uniform on [0, 1).
inline float wavelength_sequence_point(uint32_t s, uint64_t key) {
    const float v = padded_point1(s, key);
    const uint32_t hero = uint32_t(mix64(hash_combine(key, s)) >> 62);
    return (float(hero) + v) * 0.25f;
}

// Terminates `lambda`'s secondary wavelengths and zeroes `s` at them (a photon's power, a path's
// throughput: what is carried on with the hero alone).
inline void terminate_secondary(SampledWavelengths& lambda, SampledSpectrum& s) {
    lambda.terminate_secondary();
    for (int i = 1; i < kSpectrumSamples; ++i) s[i] = 0;
}

}  // namespace phos::spectrum

namespace phos {
// The names light transport uses: a path's values at its wavelengths, and the wavelengths.
using Spectrum = spectrum::SampledSpectrum;
using Wavelengths = spectrum::SampledWavelengths;
}  // namespace phos
