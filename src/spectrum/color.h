// From spectra to the output colour space: CIE 1931 XYZ by the colour-matching functions (a
// sampled spectrum's Monte Carlo estimate, or a tabulated spectrum's integral), and XYZ <-> linear
// sRGB (Rec. 709 primaries, D65 white: the D65 table's own chromaticity), the matrices derived
// from the primaries' and white's chromaticities (IEC 61966-2-1).
#pragma once

#include <array>
#include <functional>

#include "core/vec.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::spectrum {

using Mat3 = std::array<std::array<double, 3>, 3>;

// x̄, ȳ, z̄ at `lambda` (nm; linear between the 1 nm samples, 0 outside [360, 830]).
Vec3 cie_xyz(float lambda);
// D65's relative power at `lambda` (100 at 560 nm; linear between samples, 0 outside).
float d65(float lambda);

// The XYZ the film adds for one path: (1/n) sum_i L(λi) (x̄, ȳ, z̄)(λi) / p(λi), over ∫ȳ (so that
// a constant spectrum 1 has Y = 1). Wavelengths with p = 0 (terminated) add nothing.
Vec3 to_xyz(const SampledSpectrum& L, const SampledWavelengths& w);
// ∫ S (x̄, ȳ, z̄) dλ / ∫ȳ over [360, 830] by the 1 nm sum.
Vec3 integrate_xyz(const std::function<double(double lambda)>& S);

// The matrices between XYZ and linear sRGB.
const Mat3& xyz_to_srgb();
const Mat3& srgb_to_xyz();
Vec3 apply(const Mat3& m, Vec3 v);

}  // namespace phos::spectrum
