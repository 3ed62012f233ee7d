// Dispersive dielectrics: the index of refraction as a function of wavelength, by the Sellmeier
// equation n²(λ) = 1 + Σ B_i λ² / (λ² − C_i) (λ in µm, C_i in µm²), and the named optical glasses
// pbrt-v4 scenes use ("glass-BK7", "glass-BAF10", "glass-FK51A", "glass-LASF9", "glass-F5" /
// "glass-SF5", "glass-F10" / "glass-SF10", "glass-F11" / "glass-SF11") with the coefficients of
// the SCHOTT optical glass data sheets and the catalogue's n_d and Abbe number V_d for checking.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace phos::spectrum {

struct Sellmeier {
    std::array<double, 3> B{}, C{};  // C in µm²
    double ior(double lambda_nm) const;
};

// The Fraunhofer lines the catalogue's figures use (nm): d (helium, 587.5618), F (hydrogen,
// 486.1327), C (hydrogen, 656.2725).
inline constexpr double kLineD = 587.5618, kLineF = 486.1327, kLineC = 656.2725;
// The Abbe number V_d = (n_d − 1) / (n_F − n_C) of a dispersion curve.
double abbe_number(const Sellmeier& s);

struct NamedGlass {
    std::string name;  // as pbrt-v4 names it: "glass-BK7"
    Sellmeier sellmeier;
    double n_d, v_d;  // the catalogue's refractive index at the d line and Abbe number
};

// Every named glass (aliases included: "glass-F5" and "glass-SF5" are the same glass).
const std::vector<NamedGlass>& named_glasses();
std::optional<Sellmeier> named_glass(const std::string& name);

}  // namespace phos::spectrum
