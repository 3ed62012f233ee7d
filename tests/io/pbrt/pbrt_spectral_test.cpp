// The spectra the pbrt loader keeps beside their RGB: light emission (blackbody, named illuminants,
// inline lists, .spd files) normalised as the colour is, so that the spectrum's sRGB is the light's
// colour; pbrt-v3's two-value blackbody; the named metals' measured η and k on conductors; a
// dielectric's dispersion (named glasses, sampled indices); and the film's sensor settings.
#include <gtest/gtest.h>

#include <cmath>

#include "io/pbrt/spectra.h"
#include "pbrt_test_util.h"
#include "spectrum/blackbody.h"
#include "spectrum/color.h"
#include "spectrum/dispersion.h"
#include "spectrum/named_metals.h"
#include "spectrum/standard_illuminants.h"

namespace phos::io::test {
namespace {

using scene::Light;

struct Loaded {
    scene::Scene scene;
    int warnings = 0;
};

// Loads `text` as scene.pbrt in a scratch directory that also holds `files` (name, contents).
Loaded load_text(const std::string& text,
                 const std::vector<std::pair<std::string, std::string>>& files = {}) {
    QuietLog quiet;
    PbrtTempDir dir;
    for (const auto& [name, contents] : files) dir.write(name, contents);
    const std::string path = dir.write("scene.pbrt", text);
    const int before = log::warning_count();
    Loaded l{load_pbrt(path), 0};
    l.warnings = log::warning_count() - before;
    return l;
}

// The spectrum's sRGB is the colour, to 1e-3 of the colour's largest component.
void expect_spectrum_is_colour(const Light& light, const std::string& what) {
    ASSERT_TRUE(light.spectrum.has_value()) << what;
    const Rgb s = light.spectrum->srgb();
    const float tol =
        1e-3f * std::max({std::fabs(light.color.r), std::fabs(light.color.g), std::fabs(light.color.b)});
    EXPECT_NEAR(s.r, light.color.r, tol) << what;
    EXPECT_NEAR(s.g, light.color.g, tol) << what;
    EXPECT_NEAR(s.b, light.color.b, tol) << what;
}

const std::string kQuad =
    "Shape \"trianglemesh\" \"point3 P\" [0 0 0 0.5 0 0 0.5 0 0.1 0 0 0.1] \"integer indices\" [0 1 2 0 2 "
    "3]\n";

// ---- emission ----

TEST(PbrtSpectralLights, BlackbodyLightsKeepTheirSpectrumWhoseSrgbIsTheColour) {
    const Loaded l = load_text(
        "WorldBegin\nLightSource \"point\" \"blackbody I\" 3000 \"float scale\" 2\n"
        "LightSource \"point\" \"blackbody I\" 5000 \"float power\" 100\n"
        "LightSource \"spot\" \"blackbody I\" 4000 \"point3 to\" [0 -1 0] \"float power\" 10\n"
        "LightSource \"distant\" \"blackbody L\" 6500 \"float illuminance\" 3\n"
        "LightSource \"infinite\" \"blackbody L\" 8000 \"float scale\" 0.5\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"blackbody L\" 2700 \"float scale\" 4\n" +
        kQuad + "AreaLightSource \"diffuse\" \"blackbody L\" 6500 \"float power\" 10\n" + kQuad +
        "AttributeEnd\n");
    ASSERT_EQ(l.scene.lights.size(), 7u);
    EXPECT_EQ(l.warnings, 0);
    for (size_t i = 0; i < l.scene.lights.size(); ++i)
        expect_spectrum_is_colour(l.scene.lights[i], "light " + std::to_string(i));
    // The spectrum is the peak-normalised Planckian scaled to luminance 1, then by `scale`: its
    // luminance is the scale and its shape Planck's.
    const spectrum::Distribution& warm = *l.scene.lights[0].spectrum;
    EXPECT_NEAR(warm.xyz().y, 2.0f, 1e-4f);
    const spectrum::Blackbody planck(3000);
    EXPECT_NEAR(warm(450) / warm(650), planck(450) / planck(650), 1e-4f);
    EXPECT_NEAR(l.scene.lights[1].spectrum->xyz().y * 4 * kPi, 100.0f, 1e-2f);  // 4 pi I = power
    const Light& area = l.scene.lights[6];
    EXPECT_EQ(area.kind, Light::Kind::Area);
    EXPECT_NEAR(area.spectrum->xyz().y * kPi * 0.05f, 10.0f, 1e-3f);  // pi A L = power
    EXPECT_NEAR(l.scene.lights[5].spectrum->xyz().y, 4.0f, 1e-4f);
}

TEST(PbrtSpectralLights, TwoValueBlackbodyOfPbrtV3Multiplies) {
    const Loaded l = load_text(
        "WorldBegin\nLightSource \"point\" \"blackbody I\" [6500 3]\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"blackbody L\" [2700 5] \"float scale\" 2\n" +
        kQuad + "AttributeEnd\n");
    ASSERT_EQ(l.scene.lights.size(), 2u);
    const Rgb one = pbrt::blackbody_rgb(6500);
    EXPECT_NEAR(l.scene.lights[0].color.g, 3 * one.g, 1e-5f);
    EXPECT_NEAR(l.scene.lights[0].color.luminance(), 3.0f, 0.02f);
    expect_spectrum_is_colour(l.scene.lights[0], "point");
    EXPECT_NEAR(l.scene.lights[1].spectrum->xyz().y, 10.0f, 1e-3f);
    expect_spectrum_is_colour(l.scene.lights[1], "area");
}

TEST(PbrtSpectralLights, NamedIlluminantsInlineListsAndSpdFiles) {
    const std::string spd = "# a made-up lamp\n400 0.5\n500 1.0 # peak\n600 0.75\n700 0.25\n";
    const Loaded l = load_text(
        "WorldBegin\nLightSource \"point\" \"spectrum I\" \"stdillum-D65\" \"float scale\" 4\n"
        "LightSource \"point\" \"spectrum I\" \"stdillum-A\"\n"
        "LightSource \"point\" \"spectrum I\" [400 0.5 500 1 600 0.75 700 0.25] \"float scale\" 3\n"
        "LightSource \"point\" \"spectrum I\" \"lamp.spd\" \"float scale\" 3\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"spectrum L\" \"lamp.spd\"\n" +
            kQuad + "AttributeEnd\n",
        {{"lamp.spd", spd}});
    ASSERT_EQ(l.scene.lights.size(), 5u);
    for (size_t i = 0; i < l.scene.lights.size(); ++i)
        expect_spectrum_is_colour(l.scene.lights[i], "light " + std::to_string(i));
    EXPECT_EQ(l.scene.lights[0].color, Rgb(4.0f));  // D65 is the sRGB white
    // stdillum-A: the CIE table (spectrum/standard_illuminants.h), scaled to luminance 1.
    const auto a = spectrum::standard_illuminant("A");
    const spectrum::Distribution& A = *l.scene.lights[1].spectrum;
    EXPECT_NEAR(A.xyz().y, 1.0f, 1e-4f);
    EXPECT_NEAR(A(450) / A(650), a->value[30] / a->value[70], 1e-5f);  // 450 and 650 nm
    // The inline list and the file are the same table: linear between the points, luminance 3.
    for (size_t i : {2u, 3u}) {
        const spectrum::Distribution& s = *l.scene.lights[i].spectrum;
        EXPECT_NEAR(s.xyz().y, 3.0f, 1e-4f);
        EXPECT_NEAR(s(450) / s(500), 0.75f, 1e-5f);
        EXPECT_NEAR(s(650) / s(500), 0.5f, 1e-5f);
    }
    EXPECT_EQ(l.scene.lights[2].color, l.scene.lights[3].color);
    EXPECT_NEAR(l.scene.lights[4].spectrum->xyz().y, 1.0f, 1e-4f);
}

TEST(PbrtSpectralLights, RgbAndFloatEmissionHaveNoSpectrum) {
    const Loaded l = load_text(
        "WorldBegin\nLightSource \"point\" \"rgb I\" [1 2 3]\nLightSource \"point\"\n"
        "LightSource \"distant\" \"float L\" 2\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [4 4 "
        "4]\n" +
        kQuad + "AttributeEnd\n");
    ASSERT_EQ(l.scene.lights.size(), 4u);
    for (const Light& light : l.scene.lights) EXPECT_FALSE(light.spectrum.has_value());
}

// ---- conductors ----

const scene::Material& material_of(const Loaded& l, size_t shape) {
    return l.scene.materials[size_t(l.scene.shapes[shape].material)];
}

void expect_table(const std::optional<spectrum::Distribution>& s, const char* metal, bool eta) {
    ASSERT_TRUE(s.has_value()) << metal;
    const auto m = spectrum::named_metal(metal);
    ASSERT_TRUE(m.has_value());
    for (float lambda : {380.0f, 452.5f, 550.0f, 633.0f, 700.0f, 800.0f})
        EXPECT_FLOAT_EQ((*s)(lambda), eta ? m->eta(lambda) : m->k(lambda)) << metal << " at " << lambda;
}

TEST(PbrtSpectralMaterials, NamedMetalsKeepTheirMeasuredEtaAndK) {
    const Loaded l = load_text(
        "WorldBegin\nMaterial \"conductor\" \"spectrum eta\" \"metal-Au-eta\" \"spectrum k\" \"metal-Au-k\"\n"
        "Shape \"sphere\"\nMaterial \"conductor\"\nShape \"sphere\"\n"
        "Material \"coatedconductor\" \"spectrum conductor.eta\" \"metal-Ag-eta\" \"spectrum conductor.k\" "
        "\"metal-Ag-k\"\nShape \"sphere\"\n"
        "Material \"conductor\" \"rgb eta\" [0.2 0.9 1.1] \"spectrum k\" [400 3 700 4]\nShape \"sphere\"\n"
        "Material \"conductor\" \"spectrum eta\" \"metal-CuZn-eta\" \"spectrum k\" \"metal-CuZn-k\"\n"
        "Shape \"sphere\"\nMaterial \"conductor\" \"spectrum eta\" \"metal-Al-eta\"\nShape \"sphere\"\n");
    const scene::Material& au = material_of(l, 0);
    expect_table(au.conductor_eta_spectrum, "Au", true);
    expect_table(au.conductor_k_spectrum, "Au", false);
    // The RGB values stay the RGB approximation.
    EXPECT_EQ(au.conductor_eta, *pbrt::named_spectrum_rgb("metal-Au-eta", pbrt::SpectrumUse::Unbounded));
    // pbrt-v4's default conductor is copper.
    expect_table(material_of(l, 1).conductor_eta_spectrum, "Cu", true);
    expect_table(material_of(l, 1).conductor_k_spectrum, "Cu", false);
    expect_table(material_of(l, 2).conductor_eta_spectrum, "Ag", true);
    expect_table(material_of(l, 2).conductor_k_spectrum, "Ag", false);
    // An RGB eta has no spectrum; an inline k is its table.
    const scene::Material& mixed = material_of(l, 3);
    EXPECT_FALSE(mixed.conductor_eta_spectrum.has_value());
    ASSERT_TRUE(mixed.conductor_k_spectrum.has_value());
    EXPECT_FLOAT_EQ((*mixed.conductor_k_spectrum)(550), 3.5f);
    expect_table(material_of(l, 4).conductor_eta_spectrum, "CuZn", true);
    expect_table(material_of(l, 4).conductor_k_spectrum, "CuZn", false);
    // eta given, k defaulted: aluminium's eta with copper's k, as pbrt-v4 reads it.
    expect_table(material_of(l, 5).conductor_eta_spectrum, "Al", true);
    expect_table(material_of(l, 5).conductor_k_spectrum, "Cu", false);
}

// ---- dispersion ----

TEST(PbrtSpectralMaterials, NamedGlassesAreSellmeierDispersion) {
    const Loaded l = load_text(
        "WorldBegin\nMaterial \"dielectric\" \"spectrum eta\" \"glass-F10\"\nShape \"sphere\"\n"
        "Material \"thindielectric\" \"spectrum eta\" \"glass-BK7\"\nShape \"sphere\"\n"
        "Material \"dielectric\" \"float eta\" 1.33\nShape \"sphere\"\n"
        "Material \"dielectric\"\nShape \"sphere\"\n");
    EXPECT_EQ(l.warnings, 0);  // dispersion is kept, not warned about
    for (const spectrum::NamedGlass& g : spectrum::named_glasses()) {
        if (g.name != "glass-F10" && g.name != "glass-BK7") continue;
        const scene::Material& m = material_of(l, g.name == "glass-F10" ? 0 : 1);
        ASSERT_TRUE(m.ior_spectrum.has_value()) << g.name;
        EXPECT_NEAR((*m.ior_spectrum)(587.56f), g.n_d, 1e-4) << g.name;
        EXPECT_NEAR(m.ior, g.n_d, 1e-4) << g.name;
        // Normal dispersion: blue bends more.
        EXPECT_GT((*m.ior_spectrum)(450), (*m.ior_spectrum)(650)) << g.name;
        EXPECT_FLOAT_EQ((*m.ior_spectrum)(500), float(g.sellmeier.ior(500))) << g.name;
    }
    EXPECT_TRUE(material_of(l, 1).thin);
    EXPECT_FALSE(material_of(l, 2).ior_spectrum.has_value());
    EXPECT_FLOAT_EQ(material_of(l, 2).ior, 1.33f);
    EXPECT_FALSE(material_of(l, 3).ior_spectrum.has_value());
    EXPECT_FLOAT_EQ(material_of(l, 3).ior, 1.5f);
}

TEST(PbrtSpectralMaterials, SampledIndicesAreTabulatedDispersion) {
    const Loaded l = load_text(
        "WorldBegin\nMaterial \"dielectric\" \"spectrum eta\" [400 1.60 587.5618 1.55 700 1.54]\n"
        "Shape \"sphere\"\nMaterial \"dielectric\" \"spectrum eta\" \"water.spd\"\nShape \"sphere\"\n",
        {{"water.spd", "400 1.343\n700 1.331\n"}});
    const scene::Material& a = material_of(l, 0);
    ASSERT_TRUE(a.ior_spectrum.has_value());
    EXPECT_NEAR(a.ior, 1.55f, 1e-6f);  // the value at the d line
    EXPECT_NEAR((*a.ior_spectrum)(500), 1.60f - 0.05f * 100 / 187.5618f, 1e-5f);
    const scene::Material& w = material_of(l, 1);
    ASSERT_TRUE(w.ior_spectrum.has_value());
    EXPECT_NEAR((*w.ior_spectrum)(550), 1.337f, 1e-5f);
    EXPECT_NEAR(w.ior, 1.343f - 0.012f * (587.5618f - 400) / 300, 1e-5f);
}

// ---- film ----

TEST(PbrtSpectralFilm, IsoShutterAndWhiteBalance) {
    const Loaded l = load_text(
        "Film \"rgb\" \"float iso\" 400 \"float whitebalance\" 3200 \"string sensor\" \"cie1931\"\n"
        "Camera \"perspective\" \"float shutteropen\" 0 \"float shutterclose\" 0.5\nWorldBegin\n");
    EXPECT_EQ(l.warnings, 0);
    EXPECT_FLOAT_EQ(l.scene.film_response.exposure, 2.0f);  // 0.5 s x ISO 400 / 100
    EXPECT_FLOAT_EQ(l.scene.film_response.white_balance_kelvin, 3200.0f);

    const Loaded d = load_text("Film \"rgb\"\nWorldBegin\n");
    EXPECT_FLOAT_EQ(d.scene.film_response.exposure, 1.0f);
    EXPECT_FLOAT_EQ(d.scene.film_response.white_balance_kelvin, 0.0f);

    // A camera sensor phos does not model: one warning, the CIE observer balanced for 6500 K as
    // pbrt-v4 balances camera sensors by default.
    const Loaded s =
        load_text("Film \"rgb\" \"string sensor\" \"canon_eos_5d_mkiv\" \"float iso\" 50\nWorldBegin\n");
    EXPECT_EQ(s.warnings, 1);
    EXPECT_FLOAT_EQ(s.scene.film_response.white_balance_kelvin, 6500.0f);
    EXPECT_FLOAT_EQ(s.scene.film_response.exposure, 0.5f);
}

}  // namespace
}  // namespace phos::io::test
