// pbrt-v4's "subsurface" material as the loader builds it: a dielectric boundary (eta, roughness)
// whose shapes enclose a homogeneous medium from a named measured medium, sigma_a/sigma_s times
// scale, or reflectance/mfp inverted through the photon-beam-diffusion table; the table itself
// against brute-force quadrature of its profile; located errors and the warnings for an open
// surface and a replaced MediumInterface inside.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "io/pbrt/beam_diffusion.h"
#include "pbrt_test_util.h"
#include "scene/scene.h"

namespace phos::io::test {
namespace {

using pbrt::BeamDiffusionTable;

scene::Scene load(PbrtTempDir& dir, const std::string& world, int* warnings = nullptr) {
    QuietLog quiet;
    const int before = log::warning_count();
    scene::Scene s = load_pbrt(dir.write("scene.pbrt", "WorldBegin\n" + world));
    if (warnings) *warnings = log::warning_count() - before;
    return s;
}

void expect_rgb(Rgb got, Rgb want, float tol = 1e-6f) {
    EXPECT_NEAR(got.r, want.r, tol);
    EXPECT_NEAR(got.g, want.g, tol);
    EXPECT_NEAR(got.b, want.b, tol);
}

TEST(PbrtSubsurface, NamedMediumFillsTheShapeUnderADielectric) {
    PbrtTempDir dir;
    int warnings = -1;
    const scene::Scene s = load(dir,
                                "Material \"subsurface\" \"string name\" \"Ketchup\" \"float eta\" 1.4 "
                                "\"float roughness\" 0.1\nShape \"sphere\"\n",
                                &warnings);
    EXPECT_EQ(warnings, 0);
    ASSERT_EQ(s.media.size(), 1u);
    const scene::Medium& m = s.media[0];
    EXPECT_EQ(m.kind, scene::Medium::Kind::Homogeneous);
    // pbrt-v4's table, 1/mm used as 1/scene-unit: sigma_s' as sigma_s, g = 0.
    expect_rgb(m.sigma_a, Rgb(0.061f, 0.97f, 1.45f));
    expect_rgb(m.sigma_s, Rgb(0.18f, 0.07f, 0.03f));
    EXPECT_EQ(m.g, 0.0f);
    EXPECT_EQ(m.scale, 1.0f);
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(s.shapes[0].media.inside, 0);
    EXPECT_EQ(s.shapes[0].media.outside, -1);
    const scene::Material& mat = s.materials.at(size_t(s.shapes[0].material));
    EXPECT_EQ(mat.subsurface_medium, 0);
    EXPECT_FLOAT_EQ(mat.ior, 1.4f);
    expect_rgb(mat.transmission, Rgb(1.0f));
    EXPECT_TRUE(mat.microfacet);
    EXPECT_FLOAT_EQ(mat.roughness_u, 0.1f);
    EXPECT_FLOAT_EQ(mat.roughness_v, 0.1f);
    expect_rgb(mat.diffuse, Rgb(0.0f));

    // Narasimhan et al. 2006's names too; pbrt-v4's default eta 1.33.
    const scene::Scene milk =
        load(dir, "Material \"subsurface\" \"string name\" \"Regular Milk\"\nShape \"sphere\"\n");
    ASSERT_EQ(milk.media.size(), 1u);
    expect_rgb(milk.media[0].sigma_s, Rgb(4.5513f, 5.8294f, 7.136f));
    expect_rgb(milk.media[0].sigma_a, Rgb(0.0015333f, 0.0046f, 0.019933f));
    EXPECT_FLOAT_EQ(milk.materials.at(size_t(milk.shapes[0].material)).ior, 1.33f);
}

TEST(PbrtSubsurface, NamedMediumIgnoresG) {
    PbrtTempDir dir;
    int warnings = -1;
    const scene::Scene s =
        load(dir, "Material \"subsurface\" \"string name\" \"Skin1\" \"float g\" 0.5\nShape \"sphere\"\n",
             &warnings);
    EXPECT_EQ(warnings, 1);
    EXPECT_EQ(s.media.at(0).g, 0.0f);
}

TEST(PbrtSubsurface, SigmaAAndSigmaSTimesScaleWithG) {
    PbrtTempDir dir;
    const scene::Scene s =
        load(dir,
             "Material \"subsurface\" \"rgb sigma_a\" [ 0.1 0.2 0.3 ] \"rgb sigma_s\" [ 1 2 3 ] "
             "\"float scale\" 10 \"float g\" 0.3\nShape \"sphere\"\n");
    const scene::Medium& m = s.media.at(0);
    expect_rgb(m.sigma_a * m.scale, Rgb(1, 2, 3), 1e-5f);
    expect_rgb(m.sigma_s * m.scale, Rgb(10, 20, 30), 1e-5f);
    EXPECT_FLOAT_EQ(m.g, 0.3f);
}

TEST(PbrtSubsurface, DefaultsAreWholeMilk) {
    PbrtTempDir dir;
    const scene::Scene s = load(dir, "Material \"subsurface\"\nShape \"sphere\"\n");
    expect_rgb(s.media.at(0).sigma_a, Rgb(0.0011f, 0.0024f, 0.014f));
    expect_rgb(s.media.at(0).sigma_s, Rgb(2.55f, 3.21f, 3.77f));
}

TEST(PbrtSubsurface, ReflectanceAndMfpInvertTheDiffusionTable) {
    PbrtTempDir dir;
    const scene::Scene s =
        load(dir,
             "Material \"subsurface\" \"rgb reflectance\" [ 0.8 0.5 0.2 ] \"rgb mfp\" [ 1 0.5 "
             "0.25 ] \"float scale\" 2 \"float eta\" 1.5\nShape \"sphere\"\n");
    const scene::Medium& m = s.media.at(0);
    const BeamDiffusionTable table(0.0f, 1.5f);
    const Rgb reflectance(0.8f, 0.5f, 0.2f), mfp(1, 0.5f, 0.25f);
    for (int c = 0; c < 3; ++c) {
        // "scale" multiplies the mean free path (pbrt-v4's GetBSSRDF).
        const float sigma_t = (m.sigma_a[c] + m.sigma_s[c]) * m.scale;
        EXPECT_NEAR(sigma_t, 1 / (2 * mfp[c]), 1e-5f);
        const float rho = m.sigma_s[c] / (m.sigma_a[c] + m.sigma_s[c]);
        EXPECT_NEAR(table.effective_albedo(rho), reflectance[c], 1e-4f) << c;
    }
    EXPECT_GT(m.sigma_s.r / (m.sigma_a.r + m.sigma_s.r), m.sigma_s.b / (m.sigma_a.b + m.sigma_s.b));
}

TEST(PbrtSubsurface, ErrorsAreLocated) {
    PbrtTempDir dir;
    const std::string unknown =
        dir.write("unknown.pbrt", "WorldBegin\nMaterial \"subsurface\" \"string name\" \"Ketchupp\"\n");
    expect_pbrt_error(unknown, 2, 23, "unknown named medium \"Ketchupp\"");
    const std::string half =
        dir.write("half.pbrt", "WorldBegin\nMaterial \"subsurface\" \"rgb sigma_a\" [ 1 1 1 ]\n");
    expect_pbrt_error(half, 2, 23, "\"sigma_a\" needs \"sigma_s\"");
    const std::string negative =
        dir.write("negative.pbrt",
                  "WorldBegin\nMaterial \"subsurface\" \"rgb sigma_a\" [ 1 1 1 ] \"float sigma_s\" -1\n");
    expect_pbrt_error(negative, 2, 1, "must be finite and not negative");
    const std::string textured = dir.write("textured.pbrt",
                                           "WorldBegin\nTexture \"c\" \"spectrum\" \"checkerboard\"\n"
                                           "Material \"subsurface\" \"texture reflectance\" \"c\"\n");
    expect_pbrt_error(textured, 3, 23, "textured \"reflectance\" is not supported");
}

TEST(PbrtSubsurface, ItsMediumReplacesTheDeclaredInside) {
    PbrtTempDir dir;
    int warnings = -1;
    const scene::Scene s = load(dir,
                                "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\n"
                                "MakeNamedMedium \"air\" \"string type\" \"homogeneous\"\n"
                                "MediumInterface \"fog\" \"air\"\n"
                                "Material \"subsurface\" \"string name\" \"Marble\"\nShape \"sphere\"\n",
                                &warnings);
    EXPECT_EQ(warnings, 1);
    ASSERT_EQ(s.media.size(), 3u);
    EXPECT_EQ(s.shapes.at(0).media.inside, 2);
    EXPECT_EQ(s.shapes.at(0).media.outside, 1);
}

TEST(PbrtSubsurface, OpenSurfacesWarnAndMixesReachTheMedium) {
    PbrtTempDir dir;
    const std::string ss = "Material \"subsurface\" \"string name\" \"Apple\"\n";
    const std::string tetrahedron =
        "Shape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 0 0 1 ] \"integer indices\" [ 0 2 1 0 1 3 0 "
        "3 2 1 "
        "2 3 ]\n";
    int warnings = -1;
    load(dir, ss + tetrahedron, &warnings);
    EXPECT_EQ(warnings, 0);
    load(dir,
         ss + "Shape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ] \"integer indices\" [ 0 1 2 ]\n",
         &warnings);
    EXPECT_EQ(warnings, 1);
    load(dir, ss + "Shape \"disk\"\n", &warnings);
    EXPECT_EQ(warnings, 1);
    load(dir, ss + "Shape \"sphere\" \"float zmax\" 0.5\n", &warnings);
    EXPECT_EQ(warnings, 1);
    // A closed mesh whose vertices are repeated at a seam is still closed.
    load(dir,
         ss + "Shape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 ] \"integer indices\" [ 0 "
              "2 1 4 "
              "1 3 0 3 2 1 2 3 ]\n",
         &warnings);
    EXPECT_EQ(warnings, 0);

    const scene::Scene s =
        load(dir,
             "MakeNamedMaterial \"ss\" \"string type\" \"subsurface\"\n"
             "MakeNamedMaterial \"d\" \"string type\" \"diffuse\"\n"
             "MakeNamedMaterial \"m\" \"string type\" \"mix\" \"string materials\" [ \"d\" \"ss\" ]\n"
             "NamedMaterial \"m\"\nShape \"sphere\"\n");
    EXPECT_EQ(s.shapes.at(0).media.inside, 0);
}

// ---- the photon-beam-diffusion table ----

TEST(BeamDiffusion, CatmullRomQuadratureIsExactForLinesOnUnevenKnots) {
    const std::vector<float> x = {0, 0.1f, 0.5f, 0.6f, 2}, f = {1, 1.2f, 2, 2.2f, 5};  // f = 1 + 2x
    EXPECT_NEAR(pbrt::integrate_catmull_rom(x, f), 2 + 4, 1e-5);
    EXPECT_NEAR(pbrt::eval_catmull_rom(x, f, 1.3), 3.6, 1e-5);
}

TEST(BeamDiffusion, EffectiveAlbedoIsMonotoneAndInverts) {
    const BeamDiffusionTable table(0.0f, 1.33f);
    const auto& e = table.effective_albedos();
    EXPECT_EQ(e.front(), 0.0f);
    for (size_t i = 1; i < e.size(); ++i) EXPECT_GT(e[i], e[i - 1]) << i;
    // The diffusion model slightly overshoots at albedo 1 (1.019 at eta 1.33, g 0): a reflectance of
    // 1 maps to an albedo just below 1, as in pbrt-v4.
    EXPECT_GT(e.back(), 0.95f);
    EXPECT_LT(e.back(), 1.05f);
    for (float rho : {0.05f, 0.3f, 0.7f, 0.95f, 0.999f})
        EXPECT_NEAR(table.albedo_for(table.effective_albedo(rho)), rho, 1e-4f) << rho;
    EXPECT_EQ(table.albedo_for(-1), 0.0f);
    EXPECT_EQ(table.albedo_for(2), 1.0f);
}

// The tabulated effective albedo against a fine trapezoidal quadrature of 2 pi r (ss + ms) over
// the same radii: the Catmull-Rom rule over 64 geometric radii must agree to 1 %.
TEST(BeamDiffusion, TableMatchesBruteForceQuadrature) {
    const float eta = 1.33f;
    const BeamDiffusionTable table(0.0f, eta);
    for (size_t i : {size_t(20), size_t(60), size_t(90)}) {
        const float rho = table.albedos()[i];
        const double r_max = table.radii().back();
        const int n = 20000;
        double sum = 0, prev_r = 0, prev_f = 0;
        for (int k = 1; k <= n; ++k) {
            const double r = 1e-5 * std::pow(r_max / 1e-5, double(k - 1) / (n - 1));
            const double f = 2 * 3.14159265358979 * r *
                             (pbrt::beam_diffusion_ss(rho, 1 - rho, 0, eta, float(r)) +
                              pbrt::beam_diffusion_ms(rho, 1 - rho, 0, eta, float(r)));
            sum += 0.5 * (f + prev_f) * (r - prev_r);
            prev_r = r, prev_f = f;
        }
        EXPECT_NEAR(table.effective_albedos()[i], sum, 0.01 * sum + 1e-6) << rho;
    }
}

}  // namespace
}  // namespace phos::io::test
