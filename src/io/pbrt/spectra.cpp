// Spectra of the pbrt loader: their RGB, integrated once at load time through the spectral layer's
// CIE tables, Planck's law and named glasses (src/spectrum, docs/spectral.md), and the spectra
// themselves as spectrum::Distribution.
#include "io/pbrt/spectra.h"

#include <cmath>
#include <map>

#include "spectrum/blackbody.h"
#include "spectrum/cie_tables.h"
#include "spectrum/color.h"
#include "spectrum/dispersion.h"
#include "spectrum/named_metals.h"
#include "spectrum/piecewise_linear.h"
#include "spectrum/standard_illuminants.h"

namespace phos::io::pbrt {
namespace {

Rgb xyz_to_linear_srgb(Vec3 c) {
    const Vec3 rgb = spectrum::apply(spectrum::xyz_to_srgb(), c);
    return {rgb.x, rgb.y, rgb.z};
}

Rgb normalise(Vec3 xyz, SpectrumUse use) {
    if (use == SpectrumUse::Illuminant) {
        if (!(xyz.y > 0)) return Rgb(0.0f);
        return xyz_to_linear_srgb(xyz / xyz.y);
    }
    // Reflectance-like: divide by the response to a flat spectrum of 1, so grey stays grey
    // (a von Kries-style white balance from the equal-energy white to RGB white).
    static const Rgb white = xyz_to_linear_srgb(spectrum::integrate_xyz([](double) { return 1.0; }));
    return xyz_to_linear_srgb(xyz) / white;
}

// Complex indices of refraction of pbrt-v4's named metals reduced to linear-sRGB triples (the usual
// values from measured data at the red, green and blue primaries; approximate by nature).
struct Metal {
    Rgb eta, k;
};
const std::map<std::string, Metal>& metals() {
    static const std::map<std::string, Metal> m = {
        {"Cu", {{0.2004f, 0.9240f, 1.1022f}, {3.9129f, 2.4528f, 2.1421f}}},
        {"Au", {{0.1431f, 0.3749f, 1.4424f}, {3.9831f, 2.3857f, 1.6032f}}},
        {"Ag", {{0.1552f, 0.1167f, 0.1383f}, {4.8283f, 3.1222f, 2.1469f}}},
        {"Al", {{1.6574f, 0.8803f, 0.5212f}, {9.2238f, 6.2695f, 4.8370f}}},
        {"CuZn", {{0.444f, 0.527f, 1.094f}, {3.695f, 2.765f, 1.829f}}},
        {"MgO", {{1.732f, 1.738f, 1.752f}, {0.0f, 0.0f, 0.0f}}},
        {"TiO2", {{2.554f, 2.651f, 2.872f}, {0.0f, 0.0f, 0.0f}}},
    };
    return m;
}

// Refractive index of one of pbrt-v4's named glasses at the d line (587.6 nm), from its Sellmeier
// coefficients (spectrum/dispersion.h).
std::optional<float> glass_index(const std::string& name) {
    if (const auto g = spectrum::named_glass(name)) return float(g->ior(spectrum::kLineD));
    return std::nullopt;
}

// pbrt-v4's names for the standard illuminants other than D65 ("stdillum-A", "stdillum-F11",
// "illum-acesD60"); nullopt for any other name.
std::optional<spectrum::StandardIlluminant> standard_illuminant_of(const std::string& name) {
    if (name.rfind("stdillum-", 0) != 0 && name != "illum-acesD60") return std::nullopt;
    return spectrum::standard_illuminant(name);
}

}  // namespace

Rgb blackbody_rgb(float kelvin) {
    if (!(kelvin > 0)) return Rgb(0.0f);
    const spectrum::Blackbody b(kelvin);
    return normalise(spectrum::integrate_xyz([&](double nm) { return double(b(float(nm))); }),
                     SpectrumUse::Illuminant);
}

float sampled_spectrum_at(const std::vector<float>& lambda, const std::vector<float>& value, float nm) {
    return spectrum::piecewise_linear(
        lambda.size(), [&](size_t i) { return lambda[i]; }, [&](size_t i) { return value[i]; }, nm);
}

Rgb sampled_spectrum_rgb(const std::vector<float>& lambda, const std::vector<float>& value, SpectrumUse use) {
    return normalise(spectrum::integrate_xyz(
                         [&](double nm) { return double(sampled_spectrum_at(lambda, value, float(nm))); }),
                     use);
}

std::optional<Rgb> named_spectrum_rgb(const std::string& name, SpectrumUse use) {
    if (name.rfind("metal-", 0) == 0) {
        const size_t dash = name.rfind('-');
        const std::string metal = name.substr(6, dash - 6), part = name.substr(dash + 1);
        const auto it = metals().find(metal);
        if (it == metals().end() || (part != "eta" && part != "k")) return std::nullopt;
        return part == "eta" ? it->second.eta : it->second.k;
    }
    if (const auto g = glass_index(name)) return Rgb(*g);
    // Standard illuminants: luminance 1 with their colour (D65 is the sRGB white). The same colour
    // serves for any use, since pbrt normalises emission spectra to 1 nit anyway.
    (void)use;
    if (name == "stdillum-D65") return Rgb(1.0f);
    if (const auto s = standard_illuminant_of(name))
        return sampled_spectrum_rgb(s->wavelengths(), s->value, SpectrumUse::Illuminant);
    return std::nullopt;
}

std::optional<float> named_spectrum_value(const std::string& name) {
    if (const auto g = glass_index(name)) return *g;
    if (const auto c = named_spectrum_rgb(name, SpectrumUse::Unbounded)) return c->g;
    return std::nullopt;
}

spectrum::Distribution luminance_1(const spectrum::Distribution& d) {
    const float y = d.xyz().y;
    if (!(y > 0)) return spectrum::Distribution::constant(0.0f);
    return d.scaled(1.0f / y);
}

std::optional<spectrum::Distribution> named_illuminant(const std::string& name) {
    using spectrum::Distribution;
    // D65 at the CIE table's own 1 nm samples (the sRGB white exactly).
    static const Distribution d65 = [] {
        std::vector<float> lambda, value;
        for (int l = spectrum::kCieMin; l <= spectrum::kCieMax; ++l)
            lambda.push_back(float(l)), value.push_back(spectrum::d65(float(l)));
        return Distribution::tabulated(std::move(lambda), std::move(value));
    }();
    if (name == "stdillum-D65") return d65;
    if (const auto s = standard_illuminant_of(name))
        return Distribution::tabulated(s->wavelengths(), s->value);
    return std::nullopt;
}

std::optional<spectrum::Distribution> named_material_spectrum(const std::string& name) {
    if (const auto g = spectrum::named_glass(name)) return spectrum::Distribution::sellmeier(*g);
    if (name.rfind("metal-", 0) != 0) return std::nullopt;
    const size_t dash = name.rfind('-');
    const std::string part = name.substr(dash + 1);
    const auto metal = spectrum::named_metal(name);
    if (!metal || (part != "eta" && part != "k")) return std::nullopt;
    std::vector<float> lambda, value;
    for (const spectrum::OpticalConstant& c : metal->table)
        lambda.push_back(c.lambda), value.push_back(part == "eta" ? c.eta : c.k);
    return spectrum::Distribution::tabulated(std::move(lambda), std::move(value));
}

}  // namespace phos::io::pbrt
