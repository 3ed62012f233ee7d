// pbrt-v3 files read directly (io/pbrt/upgrade_v3.h): each rule against the pbrt-v4 file pbrt-v4's
// `--upgrade` writes for it, loaded side by side (same materials, lights and film), plus the cases
// the rules refuse, located at their parameter.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/pbrt/upgrade_writer.h"
#include "pbrt_test_util.h"
#include "scene/scene.h"
#include "support/mesh_writers.h"

namespace phos::io::pbrt {
namespace {

using test::PbrtTempDir;
using test::QuietLog;

scene::Scene load(const std::string& text) {
    QuietLog quiet;
    PbrtTempDir dir;
    return load_pbrt(dir.write("scene.pbrt", text));
}

// The world of both files: a camera-less scene with one sphere per material.
std::string world(const std::string& body) { return "WorldBegin\n" + body; }

void expect_same_material(const scene::Material& a, const scene::Material& b) {
    EXPECT_EQ(a.diffuse, b.diffuse);
    EXPECT_EQ(a.specular, b.specular);
    EXPECT_EQ(a.shininess, b.shininess);
    EXPECT_EQ(a.microfacet, b.microfacet);
    EXPECT_EQ(a.roughness_u, b.roughness_u);
    EXPECT_EQ(a.roughness_v, b.roughness_v);
    EXPECT_EQ(a.remap_roughness, b.remap_roughness);
    EXPECT_EQ(a.conductor_from_reflectance, b.conductor_from_reflectance);
    EXPECT_EQ(a.layered, b.layered);
    EXPECT_EQ(a.coat_eta, b.coat_eta);
    EXPECT_EQ(a.transmission, b.transmission);
    EXPECT_EQ(a.ior, b.ior);
    EXPECT_EQ(a.conductor, b.conductor);
    EXPECT_EQ(a.conductor_eta, b.conductor_eta);
    EXPECT_EQ(a.conductor_k, b.conductor_k);
    EXPECT_EQ(a.conductor_eta_spectrum.has_value(), b.conductor_eta_spectrum.has_value());
    EXPECT_EQ(a.diffuse_transmission, b.diffuse_transmission);
    EXPECT_EQ(a.interface_only, b.interface_only);
}

// Each pbrt-v3 material next to its pbrt-v4 form (as pbrt-v4's upgrade writes it).
TEST(PbrtV3, MaterialsBecomeTheirPbrtV4Forms) {
    const std::pair<std::string, std::string> cases[] = {
        {"Material \"matte\" \"rgb Kd\" [0.2 0.4 0.6] \"float sigma\" 20",
         "Material \"diffuse\" \"rgb reflectance\" [0.2 0.4 0.6]"},
        {"Material \"plastic\" \"color Kd\" [0.5 0.1 0.1] \"color Ks\" [0.25 0.25 0.25] \"float roughness\" "
         "0.05",
         "Material \"coateddiffuse\" \"rgb reflectance\" [0.5 0.1 0.1] \"float roughness\" 0.05"},
        {"Material \"plastic\" \"rgb Kd\" [0.5 0.1 0.1] \"rgb Ks\" [0 0 0] \"float roughness\" 0.05",
         "Material \"diffuse\" \"rgb reflectance\" [0.5 0.1 0.1]"},
        {"Material \"uber\" \"rgb Kd\" [0.3 0.3 0.1] \"rgb Ks\" [0.1 0.1 0.1] \"float index\" 1.4",
         "Material \"coateddiffuse\" \"rgb reflectance\" [0.3 0.3 0.1] \"float eta\" 1.4"},
        {"Material \"substrate\" \"rgb Kd\" [0.6 0.5 0.4] \"float uroughness\" 0.1 \"float vroughness\" 0.1",
         "Material \"coateddiffuse\" \"rgb reflectance\" [0.6 0.5 0.4] \"float uroughness\" 0.1 \"float "
         "vroughness\" 0.1"},
        {"Material \"glass\" \"float index\" 1.7 \"rgb Kr\" [1 1 1]",
         "Material \"dielectric\" \"float eta\" 1.7"},
        {"Material \"metal\" \"spectrum eta\" \"metal-Au-eta\" \"spectrum k\" \"metal-Au-k\" \"float "
         "roughness\" 0.01",
         "Material \"conductor\" \"spectrum eta\" \"metal-Au-eta\" \"spectrum k\" \"metal-Au-k\" \"float "
         "roughness\" 0.01"},
        {"Material \"mirror\" \"rgb Kr\" [0.9 0.9 0.9]",
         "Material \"conductor\" \"float roughness\" 0 \"spectrum eta\" \"metal-Ag-eta\" \"spectrum k\" "
         "\"metal-Ag-k\""},
        {"Material \"translucent\" \"rgb Kd\" [0.4 0.5 0.6] \"rgb reflect\" [0 0 0] \"rgb transmit\" [1 1 1]",
         "Material \"diffusetransmission\" \"rgb transmittance\" [0.4 0.5 0.6]"},
        {"Material \"none\"", "Material \"interface\""},
    };
    for (const auto& [v3, v4] : cases) {
        const scene::Scene a = load(world(v3 + "\nShape \"sphere\"\n"));
        const scene::Scene b = load(world(v4 + "\nShape \"sphere\"\n"));
        ASSERT_EQ(a.materials.size(), b.materials.size()) << v3;
        SCOPED_TRACE(v3);
        expect_same_material(a.materials.back(), b.materials.back());
    }
    // The v3 forms are no longer grey: matte's colour arrives.
    const scene::Scene m = load(world("Material \"matte\" \"rgb Kd\" [0.2 0.4 0.6]\nShape \"sphere\"\n"));
    EXPECT_EQ(m.materials.back().diffuse, Rgb(0.2f, 0.4f, 0.6f));
}

// A named pbrt-v3 material ("string type" "plastic") and mix's namedmaterial1/2 (order swapped:
// pbrt-v3 weights namedmaterial1 by amount, pbrt-v4 its second material).
TEST(PbrtV3, NamedMaterialsAndMixFollowTheRules) {
    const scene::Scene a = load(
        world("MakeNamedMaterial \"red\" \"string type\" \"matte\" \"rgb Kd\" [0.8 0.1 0.1]\n"
              "MakeNamedMaterial \"gold\" \"string type\" \"metal\" \"spectrum eta\" \"metal-Au-eta\" "
              "\"spectrum k\" "
              "\"metal-Au-k\"\n"
              "MakeNamedMaterial \"both\" \"string type\" \"mix\" \"string namedmaterial1\" \"red\" \"string "
              "namedmaterial2\" \"gold\" \"rgb amount\" [0.5 0.5 0.5]\nNamedMaterial \"both\"\nShape "
              "\"sphere\"\n"));
    const scene::Scene b =
        load(world("MakeNamedMaterial \"red\" \"string type\" \"diffuse\" \"rgb reflectance\" [0.8 0.1 0.1]\n"
                   "MakeNamedMaterial \"gold\" \"string type\" \"conductor\" \"spectrum eta\" "
                   "\"metal-Au-eta\" \"spectrum "
                   "k\" \"metal-Au-k\"\n"
                   "MakeNamedMaterial \"both\" \"string type\" \"mix\" \"string materials\" [\"gold\" "
                   "\"red\"] \"float amount\" "
                   "0.5\nNamedMaterial \"both\"\nShape \"sphere\"\n"));
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i) expect_same_material(a.materials[i], b.materials[i]);
}

const scene::Light& only_light(const scene::Scene& s) {
    EXPECT_EQ(s.lights.size(), 1u);
    return s.lights.at(0);
}

// pbrt-v3 light scales: a grey "rgb"/"color"/"spectrum"-less scale multiplies, a coloured one
// multiplies an RGB emission channel by channel; "samples" is dropped without a warning.
TEST(PbrtV3, SpectralLightScalesMultiplyTheEmission) {
    const scene::Light p = only_light(load(
        world("LightSource \"point\" \"color I\" [1 2 3] \"color scale\" [2 2 2] \"integer samples\" 4\n")));
    EXPECT_EQ(p.color, Rgb(2, 4, 6));
    const scene::Light q =
        only_light(load(world("LightSource \"point\" \"rgb I\" [1 2 3] \"rgb scale\" [1 0.5 2]\n")));
    EXPECT_EQ(q.color, Rgb(1, 1, 6));
    const scene::Light v4 =
        only_light(load(world("LightSource \"point\" \"rgb I\" [1 2 3] \"float scale\" 2\n")));
    EXPECT_EQ(v4.color, Rgb(2, 4, 6));
    // A coloured scale on a spectral emission has no RGB to multiply: refused at the scale.
    PbrtTempDir dir;
    const std::string bad = dir.write(
        "bad.pbrt", "WorldBegin\nLightSource \"point\" \"blackbody I\" [3000]\n  \"rgb scale\" [1 0.5 2]\n");
    test::expect_pbrt_error(bad, 3, 3, "can only multiply an \"rgb\" emission");
}

// AreaLightSource "area" is pbrt-v4's "diffuse": the shapes after it emit (before, the scene had no
// light and rendered black).
TEST(PbrtV3, AreaLightSourceAreaEmits) {
    const scene::Scene s =
        load(world("AttributeBegin\nAreaLightSource \"area\" \"color L\" [4 4 4] \"integer nsamples\" 8\n"
                   "Shape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n"));
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].kind, scene::Light::Kind::Area);
    EXPECT_EQ(s.lights[0].color, Rgb(4.0f));
}

// An infinite light's "mapname" is its "filename", the constant L folded into the scale.
TEST(PbrtV3, InfiniteLightMapnameIsItsImage) {
    QuietLog quiet;
    PbrtTempDir dir;
    dir.write("sky.pfm", std::string("PF\n2 1\n-1\n") + std::string(24, '\0'));
    const scene::Scene a = load_pbrt(dir.write(
        "a.pbrt", world("LightSource \"infinite\" \"string mapname\" \"sky.pfm\" \"rgb L\" [3 3 3]\n")));
    const scene::Scene b = load_pbrt(dir.write(
        "b.pbrt", world("LightSource \"infinite\" \"string filename\" \"sky.pfm\" \"float scale\" 3\n")));
    const scene::Light& la = only_light(a);
    const scene::Light& lb = only_light(b);
    EXPECT_GE(la.texture, 0);
    EXPECT_EQ(la.texture, lb.texture);
    EXPECT_EQ(la.color, lb.color);
}

// Film "image": an "rgb" film whose "scale" multiplies the image (pbrt-v4: iso = 100 × scale).
TEST(PbrtV3, ImageFilmScaleIsTheExposure) {
    const scene::Scene s = load(
        "Film \"image\" \"integer xresolution\" 64 \"integer yresolution\" 32 \"float scale\" "
        "2.5 \"float maxsampleluminance\" 10\n" +
        world(""));
    EXPECT_EQ(s.settings.width, 64);
    EXPECT_FLOAT_EQ(s.film_response.exposure, 2.5f);
}

// Textures: the "scale" texture's tex1/tex2 (a spectrum one with its grey "rgb" as the float scale)
// and imagemap's "gamma" as an encoding load as their pbrt-v4 forms.
TEST(PbrtV3, TexturesFollowTheRules) {
    QuietLog quiet;
    PbrtTempDir dir;
    dir.write("t.pfm", std::string("PF\n2 1\n-1\n") + std::string(24, '\0'));
    const std::string v3 =
        "WorldBegin\nTexture \"c\" \"color\" \"checkerboard\" \"color tex1\" [1 0 0] \"color tex2\" [0 0 1]\n"
        "Texture \"s\" \"color\" \"scale\" \"texture tex1\" \"c\" \"color tex2\" [0.5 0.5 0.5]\n"
        "Texture \"f\" \"float\" \"scale\" \"float tex1\" 2 \"float tex2\" 3\n"
        "Texture \"i\" \"color\" \"imagemap\" \"string filename\" \"t.pfm\" \"bool gamma\" false\n";
    const std::string v4 =
        "WorldBegin\nTexture \"c\" \"spectrum\" \"checkerboard\" \"rgb tex1\" [1 0 0] \"rgb tex2\" [0 0 1]\n"
        "Texture \"s\" \"spectrum\" \"scale\" \"texture tex\" \"c\" \"float scale\" 0.5\n"
        "Texture \"f\" \"float\" \"scale\" \"float tex\" 2 \"float scale\" 3\n"
        "Texture \"i\" \"spectrum\" \"imagemap\" \"string filename\" \"t.pfm\" \"string encoding\" "
        "\"linear\"\n";
    const int before = log::warning_count();
    const scene::Scene a = load_pbrt(dir.write("a.pbrt", v3));
    EXPECT_EQ(log::warning_count(), before);  // every v3 parameter read (none left unused)
    const scene::Scene b = load_pbrt(dir.write("b.pbrt", v4));
    ASSERT_EQ(a.textures.size(), b.textures.size());
    for (size_t i = 0; i < a.textures.size(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(a.textures[i].kind, b.textures[i].kind);
        EXPECT_EQ(a.textures[i].value, b.textures[i].value);
        EXPECT_EQ(a.textures[i].tex1, b.textures[i].tex1);
        EXPECT_EQ(a.textures[i].tex2, b.textures[i].tex2);
    }
    const std::string two = dir.write(
        "two.pbrt",
        "WorldBegin\nTexture \"s\" \"color\" \"scale\" \"color tex1\" [1 1 1] \"color tex2\" [2 2 2]\n");
    test::expect_pbrt_error(two, 2, 50, "two \"rgb\" values");
}

// Integrators, media and filters: directlighting is path with maxdepth 1, SPPM's numiterations its
// iterations (whatever the Sampler says), "heterogeneous" a uniform grid, xwidth the filter radius.
TEST(PbrtV3, IntegratorMediumAndFilterFollowTheRules) {
    const scene::Scene d = load("Integrator \"directlighting\" \"integer maxdepth\" 5\n" + world(""));
    EXPECT_EQ(d.settings.integrator, "path");
    ASSERT_EQ(d.settings.integrator_parameters.size(), 1u);
    EXPECT_EQ(d.settings.integrator_parameters[0].name, "maxdepth");
    EXPECT_EQ(d.settings.integrator_parameters[0].values, std::vector<std::string>{"1"});
    const scene::Scene s = load(
        "Integrator \"sppm\" \"integer numiterations\" 70 \"float rrthreshold\" 0.5\n"
        "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" 4\n" +
        world(""));
    EXPECT_EQ(s.settings.integrator, "sppm");
    EXPECT_EQ(s.settings.spp, 70);
    const scene::Scene m = load(world(
        "MakeNamedMedium \"smoke\" \"string type\" \"heterogeneous\" \"integer nx\" 1 \"integer ny\" 1 "
        "\"integer nz\" 2 \"float density\" [0.5 1] \"rgb sigma_a\" [1 1 1] \"rgb sigma_s\" [2 2 2]\n"));
    ASSERT_EQ(m.media.size(), 1u);
    EXPECT_EQ(m.media[0].kind, scene::Medium::Kind::UniformGrid);
    QuietLog quiet;
    const int before = log::warning_count();
    load("PixelFilter \"box\" \"float xwidth\" 0.5 \"float ywidth\" 0.5\n" + world(""));
    EXPECT_EQ(log::warning_count(), before);  // read as xradius/yradius: nothing unused
}

// `phos upgrade`'s writer: a pbrt-v3 scene with an include in another folder naming a PLY mesh,
// written as one pbrt-v4 file elsewhere, loads to the same scene as the original (materials, lights,
// meshes, film), with the mesh path rewritten for the new folder and no pbrt-v3 construct left;
// writing the result again changes nothing.
TEST(PbrtV3, UpgradeWritesOnePbrtV4FileThatLoadsToTheSameScene) {
    QuietLog quiet;
    PbrtTempDir dir;
    const scene::TriangleMesh quad = phos::testing::unit_quad();
    phos::testing::write_ply(dir.write("in/geo/quad.ply", ""), quad, false);
    dir.write("in/geo/part.pbrt",
              "AttributeBegin\nMaterial \"plastic\" \"color Kd\" [0.5 0.2 0.1] \"color Ks\" "
              "[0.3 0.3 0.3]\nTranslate 0 0 2.5\nShape \"plymesh\" \"string filename\" "
              "\"quad.ply\"\nAttributeEnd\n");
    const std::string v3 =
        dir.write("in/scene.pbrt",
                  "Film \"image\" \"integer xresolution\" 32 \"integer yresolution\" 16 \"float scale\" 2\n"
                  "LookAt 0 0.3 1.9  0 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" 40\nWorldBegin\n"
                  "Include \"geo/part.pbrt\"\nMaterial \"matte\" \"rgb Kd\" [0.1 0.6 0.2]\n"
                  "AttributeBegin\nAreaLightSource \"area\" \"color L\" [2 2 2] \"rgb scale\" [3 3 3]\n"
                  "Shape \"sphere\" \"float radius\" 0.25\nAttributeEnd\nLightSource \"point\" \"blackbody "
                  "I\" [3000 2]\n"
                  "WorldEnd\n");
    const std::string out = dir.file("out/v4.pbrt");
    std::filesystem::create_directories(dir.file("out"));
    const std::string text = upgrade_pbrt(v3, out);
    dir.write("out/v4.pbrt", text);
    for (const char* v3_only :
         {"matte", "plastic", "\"area\"", "\"image\"", "Kd", "color", "WorldEnd", "Include"})
        EXPECT_EQ(text.find(v3_only), std::string::npos) << v3_only << " left in:\n" << text;
    EXPECT_NE(text.find("\"../in/geo/quad.ply\""), std::string::npos) << text;

    const scene::Scene a = load_pbrt(v3), b = load_pbrt(out);
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i) expect_same_material(a.materials[i], b.materials[i]);
    ASSERT_EQ(a.lights.size(), b.lights.size());
    for (size_t i = 0; i < a.lights.size(); ++i) {
        EXPECT_EQ(a.lights[i].color, b.lights[i].color) << i;
        EXPECT_EQ(a.lights[i].spectrum.has_value(), b.lights[i].spectrum.has_value()) << i;
    }
    ASSERT_EQ(a.shapes.size(), b.shapes.size());
    EXPECT_EQ(a.shapes[0].mesh.positions, b.shapes[0].mesh.positions);
    EXPECT_EQ(a.film_response.exposure, b.film_response.exposure);
    EXPECT_EQ(a.settings.width, b.settings.width);
    ASSERT_TRUE(a.camera && b.camera);
    EXPECT_EQ(a.camera->eye, b.camera->eye);

    const std::string again = upgrade_pbrt(out, dir.file("out/v4-again.pbrt"));
    EXPECT_EQ(again.substr(again.find('\n')), text.substr(text.find('\n')));  // but the first (comment) line
}

// A realistic camera's lens file and stop image move with the scene; a named stop shape does not.
TEST(PbrtV3, UpgradeMovesTheRealisticCamerasFiles) {
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string in = dir.write(
        "in/scene.pbrt",
        "Camera \"realistic\" \"string lensfile\" \"lenses/wide.dat\" \"string aperture\" \"stop.pfm\"\n"
        "WorldBegin\n");
    const std::string named =
        dir.write("in/named.pbrt",
                  "Camera \"realistic\" \"string lensfile\" \"wide.dat\" \"string aperture\" \"pentagon\"\n"
                  "WorldBegin\n");
    std::filesystem::create_directories(dir.file("out"));
    const std::string text = upgrade_pbrt(in, dir.file("out/v4.pbrt"));
    EXPECT_NE(text.find("\"../in/lenses/wide.dat\""), std::string::npos) << text;
    EXPECT_NE(text.find("\"../in/stop.pfm\""), std::string::npos) << text;
    const std::string kept = upgrade_pbrt(named, dir.file("out/named.pbrt"));
    EXPECT_NE(kept.find("\"pentagon\""), std::string::npos) << kept;
}

}  // namespace
}  // namespace phos::io::pbrt
