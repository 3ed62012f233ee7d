// Spectral values of pbrt scenes turned into phos's linear sRGB: blackbody temperatures, pbrt-v4's
// named spectra (metals, glasses, standard illuminants) and sampled wavelength-value spectra.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/vec.h"

namespace phos::io::pbrt {

// How a spectrum is used decides its normalisation:
//  - Albedo / Unbounded: a flat spectrum of value v gives RGB (v, v, v);
//  - Illuminant: pbrt-v4 scales every emission spectrum (other than RGB) to luminance 1 nit, so the
//    result has luminance Y = 1 and only its colour comes from the spectrum.
enum class SpectrumUse { Albedo, Unbounded, Illuminant };

// Normalised blackbody emitter colour: linear sRGB with luminance 1.
Rgb blackbody_rgb(float kelvin);

// Piecewise-linear spectrum through (lambda[i], value[i]) (nm, sorted) as RGB.
Rgb sampled_spectrum_rgb(const std::vector<float>& lambda, const std::vector<float>& value, SpectrumUse use);
// Value of the piecewise-linear spectrum at `nm` (clamped at the ends).
float sampled_spectrum_at(const std::vector<float>& lambda, const std::vector<float>& value, float nm);

// pbrt-v4's named spectra ("metal-Cu-eta", "glass-BK7", "stdillum-D65", ...) as RGB;
// nullopt for names phos does not know.
std::optional<Rgb> named_spectrum_rgb(const std::string& name, SpectrumUse use);
// A named spectrum's single value: a named glass's index at the d line (587.6 nm), else the green
// of its RGB.
std::optional<float> named_spectrum_value(const std::string& name);

}  // namespace phos::io::pbrt
