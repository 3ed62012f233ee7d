// pbrt's `measured` and `hair` materials as the loader reads them: a measured material holds its
// .bsdf file's tables (read once per path, relative to the scene file), a damaged file is an
// error at the file with the scene line that named it; hair takes its absorption from `sigma_a`,
// else `reflectance` (pbrt-v3's `color`), else the melanin concentrations, else eumelanin 1.3,
// warning about what it ignores, as pbrt-v4's HairMaterial does.
#include <gtest/gtest.h>

#include <string>

#include "io/bsdf/rgl_bsdf_file.h"
#include "pbrt_test_util.h"
#include "scene/measured_bsdf.h"
#include "scene/scene.h"
#include "shading/measured_tabulation.h"

namespace phos::io::test {
namespace {

struct Loaded {
    scene::Scene scene;
    int warnings = 0;
};

Loaded load_in(PbrtTempDir& dir, const std::string& text) {
    QuietLog quiet;
    const std::string path = dir.write("scene.pbrt", text);
    const int before = log::warning_count();
    Loaded l{load_pbrt(path), 0};
    l.warnings = log::warning_count() - before;
    return l;
}

const scene::Material& material_of(const Loaded& l, size_t shape) {
    return l.scene.materials[size_t(l.scene.shapes.at(shape).material)];
}

std::string small_lambert_file(PbrtTempDir& dir, const std::string& name) {
    shading::TabulatedModel lambert;
    lambert.kind = shading::TabulatedModel::Kind::Lambert;
    lambert.reflectance = 0.5f;
    shading::TabulationGrid grid;
    grid.n_theta_i = 4;
    grid.ndf_n = 16;
    grid.vndf_n = grid.n = 8;
    // Through TempDir::write, which makes the file's directories.
    return dir.write(name, rgl_bsdf_bytes(shading::tabulate_brdf(lambert, grid)));
}

TEST(PbrtMeasured, ReadsTheFileOncePerPath) {
    PbrtTempDir dir;
    small_lambert_file(dir, "tables/grey.bsdf");
    const Loaded l = load_in(dir, kWorld +
                                      "Material \"measured\" \"string filename\" \"tables/grey.bsdf\"\n"
                                      "Shape \"sphere\"\n"
                                      "Material \"measured\" \"string filename\" \"tables/grey.bsdf\"\n"
                                      "Shape \"sphere\"\n");
    const scene::Material& a = material_of(l, 0);
    const scene::Material& b = material_of(l, 1);
    ASSERT_TRUE(a.measured);
    EXPECT_EQ(a.measured, b.measured);  // one copy of the tables
    EXPECT_EQ(a.measured->tables().theta_i.size(), 4u);
    EXPECT_EQ(l.warnings, 0);
}

TEST(PbrtMeasured, DamagedOrMissingFilesAreErrorsAtTheFile) {
    PbrtTempDir dir;
    const std::string good = small_lambert_file(dir, "good.bsdf");
    const std::string bytes = phos::testing::read_bytes(good);
    dir.write("cut.bsdf", bytes.substr(0, bytes.size() / 2));
    const std::string scene = dir.write(
        "s.pbrt",
        "WorldBegin\nMaterial \"measured\"\n  \"string filename\" \"cut.bsdf\"\nShape \"sphere\"\n");
    try {
        QuietLog quiet;
        load_pbrt(scene);
        FAIL() << "expected a ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.file, dir.file("cut.bsdf"));
        ASSERT_EQ(e.included_from.size(), 1u);
        EXPECT_EQ(e.included_from[0], scene + ":3:3");
    }
    const std::string missing = dir.write(
        "m.pbrt", "WorldBegin\nMaterial \"measured\" \"string filename\" \"none.bsdf\"\nShape \"sphere\"\n");
    EXPECT_THROW(
        {
            QuietLog quiet;
            load_pbrt(missing);
        },
        ParseError);
    expect_pbrt_error(dir.write("n.pbrt", "WorldBegin\nMaterial \"measured\"\nShape \"sphere\"\n"), 2, 1,
                      "missing \"string filename\"");
}

TEST(PbrtHair, AbsorptionAsPbrtV4ReadsIt) {
    PbrtTempDir dir;
    using C = scene::Material::HairColour;
    const Loaded l =
        load_in(dir, kWorld +
                         "Material \"hair\"\nShape \"sphere\"\n"
                         "Material \"hair\" \"rgb sigma_a\" [0.1 0.2 0.3] \"rgb reflectance\" [0.5 "
                         "0.5 0.5]\nShape \"sphere\"\n"
                         "Material \"hair\" \"rgb color\" [0.6 0.4 0.2] \"float eta\" 1.6 "
                         "\"float beta_m\" 0.2 \"float beta_n\" 0.4 \"float alpha\" 3\nShape "
                         "\"sphere\"\n"
                         "Material \"hair\" \"float pheomelanin\" 2\nShape \"sphere\"\n");
    const scene::Material& def = material_of(l, 0);
    EXPECT_TRUE(def.hair);
    EXPECT_EQ(def.hair_colour, C::Melanin);
    EXPECT_FLOAT_EQ(def.hair_eumelanin, 1.3f);
    EXPECT_FLOAT_EQ(def.hair_eta, 1.55f);
    EXPECT_FLOAT_EQ(def.hair_beta_m, 0.3f);
    EXPECT_FLOAT_EQ(def.hair_alpha, 2.0f);
    const scene::Material& sigma = material_of(l, 1);
    EXPECT_EQ(sigma.hair_colour, C::SigmaA);
    EXPECT_EQ(sigma.hair_sigma_a, Rgb(0.1f, 0.2f, 0.3f));
    const scene::Material& colour = material_of(l, 2);  // pbrt-v3's name for reflectance
    EXPECT_EQ(colour.hair_colour, C::Reflectance);
    EXPECT_EQ(colour.hair_reflectance, Rgb(0.6f, 0.4f, 0.2f));
    EXPECT_FLOAT_EQ(colour.hair_eta, 1.6f);
    EXPECT_FLOAT_EQ(colour.hair_beta_m, 0.2f);
    EXPECT_FLOAT_EQ(colour.hair_beta_n, 0.4f);
    EXPECT_FLOAT_EQ(colour.hair_alpha, 3.0f);
    const scene::Material& pheo = material_of(l, 3);  // a concentration given: no default eumelanin
    EXPECT_EQ(pheo.hair_colour, C::Melanin);
    EXPECT_FLOAT_EQ(pheo.hair_eumelanin, 0.0f);
    EXPECT_FLOAT_EQ(pheo.hair_pheomelanin, 2.0f);
    EXPECT_EQ(l.warnings, 1);  // the reflectance ignored since sigma_a is given
    expect_pbrt_error(dir.write("e.pbrt", "WorldBegin\nMaterial \"hair\" \"float eta\" -1\n"), 2, 17,
                      "must be positive");
}

}  // namespace
}  // namespace phos::io::test
