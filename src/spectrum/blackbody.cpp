// Planck's law (see blackbody.h). Constants: CODATA 2018 (exact SI values of c, h, k_B).
#include "spectrum/blackbody.h"

#include <cmath>

namespace phos::spectrum {

double planck(double lambda_nm, double kelvin) {
    if (!(kelvin > 0) || !(lambda_nm > 0)) return 0;
    constexpr double c = 299792458.0, h = 6.62607015e-34, kb = 1.380649e-23;
    const double l = lambda_nm * 1e-9;
    return 2 * h * c * c / (l * l * l * l * l * std::expm1(h * c / (l * kb * kelvin)));
}

Blackbody::Blackbody(double kelvin) : kelvin_(kelvin) {
    const double peak = kelvin > 0 ? planck(kWien / kelvin * 1e9, kelvin) : 0;
    normalisation_ = peak > 0 ? 1 / peak : 0;
}

float Blackbody::operator()(float lambda_nm) const {
    return float(planck(lambda_nm, kelvin_) * normalisation_);
}

}  // namespace phos::spectrum
