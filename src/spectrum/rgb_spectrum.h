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

#include "core/vec.h"
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
    SampledSpectrum sample(const SampledWavelengths& w) const;
    bool is_black() const { return scale_ == 0; }

private:
    float c0_ = 0, c1_ = 0, c2_ = 0;  // the sigmoid's polynomial in t = (λ − 360) / 470
    float scale_ = 0;                 // multiplies S(poly): 1 (albedo), 2m (unbounded, illuminant)
    bool illuminant_ = false;
};

// D65 scaled to luminance 1 (Y = 1 through to_xyz): the illuminant RgbSpectrum multiplies by.
float d65_luminance_1(float lambda);

}  // namespace phos::spectrum
