// Spectral values of pbrt scenes: blackbody temperatures, pbrt-v4's named spectra (metals, glasses,
// standard illuminants) and sampled wavelength-value spectra, as phos's linear sRGB and, where the
// scene keeps a spectrum (light emission, conductors' η and k, dispersive indices), as a
// spectrum::Distribution whose sRGB is that colour.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/vec.h"
#include "spectrum/distribution.h"

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

// `d` scaled to luminance Y = 1, as pbrt-v4 scales every emission spectrum other than RGB (so its
// sRGB is the Illuminant colour above); the constant 0 when its luminance is not positive.
spectrum::Distribution luminance_1(const spectrum::Distribution& d);
// pbrt-v4's named illuminants as the spectra whose colours named_spectrum_rgb gives (not yet
// normalised): "stdillum-D65" the CIE D65 table; "stdillum-A", "stdillum-D50", the fluorescent
// "stdillum-F1" to "stdillum-F12" and "illum-acesD60" their tables (spectrum/
// standard_illuminants.h). nullopt for other names.
std::optional<spectrum::Distribution> named_illuminant(const std::string& name);
// The measured spectra of pbrt-v4's named metals ("metal-Au-eta", "metal-Au-k": spectrum/
// named_metals.h's tables) and glasses ("glass-BK7": the Sellmeier index); nullopt for other
// names.
std::optional<spectrum::Distribution> named_material_spectrum(const std::string& name);

}  // namespace phos::io::pbrt
