// A spectrum as a scene gives it, evaluated at any wavelength: a constant, an RGB value (read as
// rgb_spectrum.h says), a blackbody (peak 1, blackbody.h), a table of wavelength-value points (a
// named metal's η or k, an inline "spectrum" list, an .spd file), or a dispersive index of
// refraction (Sellmeier, or Cauchy n(λ) = A + B / λ²); each times a scale. Scene data holds these
// where a value's spectrum matters beyond its RGB (light emission, conductors, dispersion);
// everything else stays RGB and is upsampled where it is used.
#pragma once

#include <memory>
#include <vector>

#include "core/vec.h"
#include "spectrum/blackbody.h"
#include "spectrum/dispersion.h"
#include "spectrum/rgb_spectrum.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::spectrum {

class Distribution {
public:
    Distribution() = default;  // the constant 0
    static Distribution constant(float c);
    static Distribution rgb(Rgb rgb, RgbSpectrum::Use use);
    static Distribution blackbody(float kelvin);
    // Points (lambda[i], value[i]), lambda non-decreasing (nm); linear between them, held beyond.
    static Distribution tabulated(std::vector<float> lambda, std::vector<float> value);
    static Distribution sellmeier(const Sellmeier& s);
    // n(λ) = a + b / λ², λ in µm (b in µm²).
    static Distribution cauchy(float a, float b);
    // The Cauchy index with refractive index n_d at the d line and Abbe number V_d:
    // b = (n_d − 1) / (V_d (1/λF² − 1/λC²)), a = n_d − b / λd².
    static Distribution abbe(float n_d, float v_d);

    Distribution scaled(float s) const;
    float operator()(float lambda) const;
    SampledSpectrum sample(const SampledWavelengths& w) const;
    // True when the value is the same at every wavelength (a constant, a grey RGB).
    bool is_constant() const { return kind_ == Kind::Constant; }
    // ∫ S (x̄, ȳ, z̄) / ∫ȳ (1 nm sums), and its linear sRGB.
    Vec3 xyz() const;
    Rgb srgb() const;

private:
    enum class Kind { Constant, Rgb, Blackbody, Tabulated, Sellmeier, Cauchy };
    Kind kind_ = Kind::Constant;
    float scale_ = 0;  // Constant: the value
    RgbSpectrum rgb_;
    float kelvin_ = 0;
    std::shared_ptr<const Blackbody> blackbody_;
    std::shared_ptr<const std::vector<float>> lambda_, value_;
    Sellmeier sellmeier_;
    float a_ = 0, b_ = 0;
};

}  // namespace phos::spectrum
