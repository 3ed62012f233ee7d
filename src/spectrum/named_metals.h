// Conductors' and oxides' measured optical constants as pbrt-v4 scenes name them
// ("metal-Au-eta" / "metal-Au-k" for Ag, Al, Au, Cu, CuZn, MgO, TiO2): the complex index η + ik
// over wavelength, tabulated (named_metals_data.cpp has the sources) and interpolated linearly.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace phos::spectrum {

struct OpticalConstant {
    float lambda;  // nm
    float eta, k;
};

struct NamedMetal {
    std::string name;                    // "Au"
    std::vector<OpticalConstant> table;  // increasing lambda, covering [360, 830] nm

    float eta(float lambda) const;
    float k(float lambda) const;
    // Reflectance at normal incidence, ((η − 1)² + k²) / ((η + 1)² + k²).
    float normal_reflectance(float lambda) const;
};

const std::vector<NamedMetal>& named_metals();
// "Au" or pbrt-v4's "metal-Au-eta" / "metal-Au-k" (which part is asked is the caller's: see
// NamedMetal); nullopt for an unknown name.
std::optional<NamedMetal> named_metal(const std::string& name);

}  // namespace phos::spectrum
