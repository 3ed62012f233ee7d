// The CIE tables spectral rendering converts through: the CIE 1931 2-degree colour-matching
// functions x̄, ȳ, z̄ and the relative spectral power of standard illuminant D65 (100 at 560 nm),
// tabulated at every nanometre from kCieMin to kCieMax (cie_tables.cpp has their source).
#pragma once

namespace phos::spectrum {

inline constexpr int kCieMin = 360;  // nm
inline constexpr int kCieMax = 830;  // nm
inline constexpr int kCieSamples = kCieMax - kCieMin + 1;

extern const float kCieX[kCieSamples];
extern const float kCieY[kCieSamples];
extern const float kCieZ[kCieSamples];
extern const float kCieD65[kCieSamples];

// The integral of ȳ over [kCieMin, kCieMax] (the 1 nm sum): XYZ = ∫ S x̄ / kCieYIntegral makes a
// spectrum of constant 1 have Y = 1.
inline constexpr double kCieYIntegral = 106.856917105;

}  // namespace phos::spectrum
