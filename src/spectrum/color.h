// From spectra to the output colour space: CIE 1931 XYZ by the colour-matching functions (a
// sampled spectrum's Monte Carlo estimate, or a tabulated spectrum's integral), and XYZ <-> linear
// sRGB (Rec. 709 primaries, D65 white: the D65 table's own chromaticity), the matrices derived
// from the primaries' and white's chromaticities (IEC 61966-2-1).
#pragma once

#include <immintrin.h>

#include <array>
#include <functional>
#include <optional>
#include <string>

#include "core/vec.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::spectrum {

using Mat3 = std::array<std::array<double, 3>, 3>;

// x̄, ȳ, z̄ at `lambda` (nm; linear between the 1 nm samples, 0 outside [360, 830]).
Vec3 cie_xyz(float lambda);
// D65's relative power at `lambda` (100 at 560 nm; linear between samples, 0 outside).
float d65(float lambda);
// D65 scaled to luminance 1 (Y = 1 through to_xyz): the illuminant RgbSpectrum multiplies by.
float d65_luminance_1(float lambda);
SampledSpectrum d65_luminance_1(const std::array<float, kSpectrumSamples>& lambda);

// The XYZ the film adds for one path: (1/n) sum_i L(λi) (x̄, ȳ, z̄)(λi) / p(λi), over ∫ȳ (so that
// a constant spectrum 1 has Y = 1). Wavelengths with p = 0 (terminated) add nothing.
Vec3 to_xyz(const SampledSpectrum& L, const SampledWavelengths& w);
// The linear sRGB the film adds for one path: xyz_to_srgb() applied to to_xyz(L, w).
Rgb to_srgb(const SampledSpectrum& L, const SampledWavelengths& w);
// The colour each of L's wavelengths adds through the film: to_srgb(f * L, w) = sum_i f[i] * w[i]
// for any f (a BSDF's value at those wavelengths), computed once for many f (SPPM's photons meet
// many visible points).
struct ColourWeights {
    // Row c holds channel c of the four wavelengths' colours (lanes = wavelengths), so that of()
    // is three products and a horizontal sum in SSE registers (SPPM and VCM run it per photon and
    // point met).
    alignas(16) std::array<std::array<float, kSpectrumSamples>, 3> rows{};
    Rgb of(const SampledSpectrum& f) const {
        static_assert(kSpectrumSamples == 4);
        const __m128 v = _mm_loadu_ps(f.v.data());
        const __m128 r = _mm_mul_ps(_mm_load_ps(rows[0].data()), v);
        const __m128 g = _mm_mul_ps(_mm_load_ps(rows[1].data()), v);
        const __m128 b = _mm_mul_ps(_mm_load_ps(rows[2].data()), v);
        return horizontal_sums(r, g, b);
    }
    Rgb total() const {
        return horizontal_sums(_mm_load_ps(rows[0].data()), _mm_load_ps(rows[1].data()),
                               _mm_load_ps(rows[2].data()));
    }

private:
    // (Σ r, Σ g, Σ b) over the lanes, each summed as (l0 + l2) + (l1 + l3).
    static Rgb horizontal_sums(__m128 r, __m128 g, __m128 b) {
        const __m128 rg = _mm_add_ps(_mm_unpacklo_ps(r, g), _mm_unpackhi_ps(r, g));  // r01 g01 r23 g23
        const __m128 bb = _mm_add_ps(_mm_unpacklo_ps(b, b), _mm_unpackhi_ps(b, b));  // b02 b02 b13 b13
        alignas(16) float x[4], y[4];
        _mm_store_ps(x, rg);
        _mm_store_ps(y, bb);
        return {x[0] + x[2], x[1] + x[3], y[0] + y[2]};
    }
};
ColourWeights colour_weights(const SampledSpectrum& L, const SampledWavelengths& w);

// An estimate that is already a colour (a photon estimate, each photon taken to colour at its own
// wavelengths) seen through a path's throughput `beta` at `lambda`: beta's common value times the
// colour while beta is the same at every wavelength and none was terminated (exact: most camera
// paths reach their photon estimate so), else the colour read as a spectrum at `lambda`
// (rgb_spectrum.h, as an illuminant), times beta, back to colour (the colour's spectrum is the
// smooth one its RGB gives).
Rgb colour_through(const SampledSpectrum& beta, const SampledWavelengths& lambda, Rgb colour);
// ∫ S (x̄, ȳ, z̄) dλ / ∫ȳ over [360, 830] by the 1 nm sum.
Vec3 integrate_xyz(const std::function<double(double lambda)>& S);

// The matrices between XYZ and linear sRGB.
const Mat3& xyz_to_srgb();
const Mat3& srgb_to_xyz();
Vec3 apply(const Mat3& m, Vec3 v);

// White balance as pbrt-v4's film does it ("whitebalance" T): the white of an illuminant of
// temperature T is the CIE daylight chromaticity at T × 1.4388 / 1.4380 (the daylight formula's
// temperatures are on the scale of the old second radiation constant, 1.4380 cm K), or, below
// 4000 K where the daylight locus is undefined, that Planckian's. white_balance_source gives its
// XYZ (Y = 1).
Vec3 white_balance_source(float kelvin);
// The linear sRGB -> linear sRGB matrix that adapts that white to the sRGB white by von Kries
// scaling in the Bradford cone space: the source white becomes (1, 1, 1). Identity for T <= 0;
// finite from about 300 K up (the pbrt loader accepts 1000 K to 40000 K).
Mat3 white_balance(float source_kelvin);

// pbrt-v4's named RGB colour spaces (its ColorSpace directive): "srgb", "rec2020" and "dci-p3" (D65
// white) and "aces2065-1" (the ACES AP0 primaries, white x = 0.32168, y = 0.33767). The matrix
// taking an RGB of that space to the linear sRGB of the same XYZ (an emitted colour), or, with
// `adapt_white`, to the linear sRGB after Bradford adaptation of the space's white to sRGB's (a
// reflectance: the space's white stays white); nullopt for another name.
std::optional<Mat3> rgb_space_to_srgb(const std::string& name, bool adapt_white);

}  // namespace phos::spectrum
