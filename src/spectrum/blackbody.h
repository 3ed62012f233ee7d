// Blackbody emission (Planck's law) as pbrt-v4's "blackbody" spectrum defines it: the spectral
// radiance of a blackbody at temperature T divided by its value at the peak wavelength (Wien's
// displacement law, λmax = b / T), so that the spectrum's maximum is 1 whatever T; a light's
// `scale` or `power` then sets its brightness.
#pragma once

namespace phos::spectrum {

// Planck's spectral radiance B(λ, T) in W / (m² sr m), λ in nm, T in kelvin (0 for T <= 0).
double planck(double lambda_nm, double kelvin);

// Wien's displacement constant b (m K): the peak of B(·, T) lies at b / T.
inline constexpr double kWien = 2.897771955e-3;

class Blackbody {
public:
    explicit Blackbody(double kelvin);
    double kelvin() const { return kelvin_; }
    // B(λ, T) / B(λmax, T): 1 at the peak.
    float operator()(float lambda_nm) const;

private:
    double kelvin_;
    double normalisation_;  // 1 / B(λmax, T)
};

}  // namespace phos::spectrum
