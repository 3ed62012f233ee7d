// Helpers for the shading tests' spectral checks: fixed and stratified path wavelengths, what an
// RGB input reads as at them (spectrum/rgb_spectrum.h: a grey value is flat, a colour the smooth
// sigmoid spectrum), per-wavelength comparisons, and colours through the film (spectrum::to_srgb).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "core/vec.h"
#include "spectrum/color.h"
#include "spectrum/dense_spectrum.h"
#include "spectrum/rgb_spectrum.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::shading::spectral {

using spectrum::kSpectrumSamples;
using spectrum::RgbSpectrum;

// One fixed set of path wavelengths spread over the visible range (the hero at 0.37 of the sampling
// density's CDF, the others stratified from it: about 420, 505, 545 and 600 nm), for checks made at
// fixed wavelengths.
inline const Wavelengths& fixed_lambda() {
    static const Wavelengths w = Wavelengths::visible(0.37f);
    return w;
}

// The k-th of n stratified wavelength sets (hero u in the middle of the k-th of n intervals).
inline Wavelengths stratified_lambda(int k, int n) {
    return Wavelengths::visible((float(k) + 0.5f) / float(n));
}

// An RGB read as a reflectance / transmittance, as a coefficient and as an emitter's colour, at `w`.
inline Spectrum albedo(Rgb c, const Wavelengths& w) {
    return RgbSpectrum(c, RgbSpectrum::Use::Albedo).sample(w);
}
inline Spectrum unbounded(Rgb c, const Wavelengths& w) {
    return RgbSpectrum(c, RgbSpectrum::Use::Unbounded).sample(w);
}
inline Spectrum illuminant(Rgb c, const Wavelengths& w) {
    return RgbSpectrum(c, RgbSpectrum::Use::Illuminant).sample(w);
}
// What a light of colour c emits at w: the illuminant spectrum as lights hold it, tabulated at
// every nanometre (spectrum::DenseSpectrum).
inline Spectrum emitted(Rgb c, const Wavelengths& w) {
    return spectrum::DenseSpectrum(spectrum::Distribution::rgb(c, RgbSpectrum::Use::Illuminant)).sample(w);
}

inline std::string describe(const Spectrum& s) {
    std::ostringstream o;
    o << "(" << s[0];
    for (int i = 1; i < kSpectrumSamples; ++i) o << ", " << s[i];
    o << ")";
    return o.str();
}

// Every wavelength sample of `s` within `tol` of `v` (what an old per-channel check of a grey value
// becomes: a grey input is the same at every wavelength).
inline ::testing::AssertionResult flat_near(const Spectrum& s, double v, double tol) {
    for (int i = 0; i < kSpectrumSamples; ++i)
        if (!(std::fabs(double(s[i]) - v) <= tol))
            return ::testing::AssertionFailure()
                   << describe(s) << " is not " << v << " +- " << tol << " at sample " << i;
    return ::testing::AssertionSuccess();
}

// Every wavelength sample of `a` within `rel` x |b| + `abs` of that of `b`.
inline ::testing::AssertionResult spectra_near(const Spectrum& a, const Spectrum& b, double rel,
                                               double abs = 0) {
    for (int i = 0; i < kSpectrumSamples; ++i)
        if (!(std::fabs(double(a[i]) - double(b[i])) <= rel * std::fabs(double(b[i])) + abs))
            return ::testing::AssertionFailure()
                   << describe(a) << " differs from " << describe(b) << " at sample " << i << " (tolerance "
                   << rel << " relative + " << abs << ")";
    return ::testing::AssertionSuccess();
}

// The colour the film gives a spectral value on average: the mean of to_srgb(f(lambda), lambda)
// over n stratified wavelength sets.
template <class F>
Rgb film_colour(F&& f, int n = 4096) {
    double sum[3] = {0, 0, 0};
    for (int k = 0; k < n; ++k) {
        const Wavelengths w = stratified_lambda(k, n);
        const Rgb c = spectrum::to_srgb(f(w), w);
        for (int ch = 0; ch < 3; ++ch) sum[ch] += c[ch];
    }
    return Rgb(float(sum[0] / n), float(sum[1] / n), float(sum[2] / n));
}

// Every channel of `a` within `rel` x |b| + `abs` of that of `b`.
inline ::testing::AssertionResult rgb_near(Rgb a, Rgb b, double rel, double abs = 0) {
    for (int c = 0; c < 3; ++c)
        if (!(std::fabs(double(a[c]) - double(b[c])) <= rel * std::fabs(double(b[c])) + abs))
            return ::testing::AssertionFailure()
                   << "(" << a.r << ", " << a.g << ", " << a.b << ") differs from (" << b.r << ", " << b.g
                   << ", " << b.b << ") in channel " << c << " (tolerance " << rel << " relative + " << abs
                   << ")";
    return ::testing::AssertionSuccess();
}

}  // namespace phos::shading::spectral
