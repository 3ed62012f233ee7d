// pbrt's `measured` and `hair` materials rendered by the phos binary, as white furnaces: under a
// constant white sky a convex object of a non-absorbing material reflects the sky's radiance back
// in every direction, so every pixel it covers reads its directional albedo. A sphere of a
// Lambertian (R = 0.8) tabulated as an RGL .bsdf file reads 0.8 with every integrator (the table's
// own interpolation error is below 1 %: tests/shading/measured_bxdf_test.cpp); a cylindrical
// curve of lossless hair (sigma_a = 0) reads 1 (Chiang et al.'s fibre conserves energy: R, TT,
// TRT and the residual lobe together carry all of it) and a dark one (eumelanin 8) far less. vcm
// renders a smooth-coated sphere as path does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "io/bsdf/rgl_bsdf_file.h"
#include "io/image/image_io.h"
#include "shading/measured_tabulation.h"
#include "test_util.h"

namespace phos::testing {
namespace {

const std::string kView =
    "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\nWorldBegin\n"
    "LightSource \"infinite\" \"rgb L\" [1 1 1]\n";

class PbrtMeasuredHairRender : public ::testing::Test {
protected:
    Image render(const std::string& scene, const std::string& integrator, const std::string& budget) {
        const std::string out = dir.file("out.pfm");
        std::filesystem::remove(out);
        const auto r = run_phos("render " + scene + " --resolution 24 24 --seed 3 --quiet --integrator " +
                                integrator + " " + budget + " -o " + out);
        EXPECT_EQ(r.exit_code, 0) << integrator << "\n" << r.output;
        return io::read_image(out);
    }
    // The mean over the central 8 x 8 pixels (inside the object's outline), per channel.
    static Rgb centre_mean(const Image& img) {
        Rgb sum(0.0f);
        for (int y = 8; y < 16; ++y)
            for (int x = 8; x < 16; ++x) sum += img.at(x, y);
        return sum / 64.0f;
    }
    TempDir dir;
};

TEST_F(PbrtMeasuredHairRender, TabulatedLambertSphereReadsItsAlbedoInEveryIntegrator) {
    shading::TabulatedModel lambert;
    lambert.kind = shading::TabulatedModel::Kind::Lambert;
    lambert.reflectance = 0.8f;
    // The default grid: a coarser one (16 x 16 reduced BRDF) is a few percent from reciprocal,
    // which photon estimates (that read it from the other side) show.
    io::write_rgl_bsdf(dir.file("white.bsdf"), shading::tabulate_brdf(lambert, shading::TabulationGrid{}));
    const std::string scene =
        dir.write("s.pbrt", kView +
                                "Material \"measured\" \"string filename\" \"white.bsdf\"\nShape \"sphere\" "
                                "\"float radius\" 0.6\n");
    for (const auto& [integrator, budget] : {std::pair<std::string, std::string>{"path", "--spp 64"},
                                             {"bdpt", "--spp 32"},
                                             {"photonmap", "--spp 16 --photons 100000"},
                                             {"sppm", "--iterations 16 --photons-per-iter 50000"},
                                             {"vcm", "--spp 32"}}) {
        const Rgb m = centre_mean(render(scene, integrator, budget));
        // 0.8 to the table's 1 % and the noise of 64 pixels (a few 1e-3).
        for (float c : {m.r, m.g, m.b}) EXPECT_NEAR(c, 0.8f, 0.02f) << integrator;
        std::printf("[ measured ] %s: %.4f %.4f %.4f\n", integrator.c_str(), m.r, m.g, m.b);
    }
}

TEST_F(PbrtMeasuredHairRender, LosslessHairConservesEnergyAndMelaninDarkensIt) {
    const std::string curve =
        "Shape \"curve\" \"string type\" \"cylinder\" \"point3 P\" [0 -2 0  0 -0.7 0  0 0.7 0  0 2 0] "
        "\"float width\" 1.2\n";
    const std::string white =
        dir.write("white.pbrt", kView + "Material \"hair\" \"rgb sigma_a\" [0 0 0]\n" + curve);
    const std::string dark =
        dir.write("dark.pbrt", kView + "Material \"hair\" \"float eumelanin\" 8\n" + curve);
    for (const auto& [integrator, budget] :
         {std::pair<std::string, std::string>{"path", "--spp 64"}, {"bdpt", "--spp 32"}}) {
        const Rgb w = centre_mean(render(white, integrator, budget));
        for (float c : {w.r, w.g, w.b}) EXPECT_NEAR(c, 1.0f, 0.03f) << integrator;
        const Rgb d = centre_mean(render(dark, integrator, budget));
        EXPECT_LT(d.average(), 0.5f * w.average()) << integrator;
        EXPECT_GT(d.average(), 0.0f) << integrator;  // its surface reflection (R) remains
    }
}

// vcm's extra camera samples (which stop at their first non-delta vertex) go on through a delta
// lobe of that vertex: a smooth coat over a red diffuse base reflects the white sky in its coat
// (a delta part) and shows its walk (a diffuse part) at one vertex. The sky's reflection is most
// of the sphere's green and blue, and vcm lost half of it when only the full camera sample went on
// through the coat (green 0.046 against path's 0.069).
TEST_F(PbrtMeasuredHairRender, VcmFollowsTheDeltaPartOfAMixedVertexWithEveryCameraSample) {
    const std::string scene =
        dir.write("coat.pbrt", kView +
                                   "Material \"coateddiffuse\" \"rgb reflectance\" [0.7 0.08 0.06] \"float "
                                   "roughness\" 0\nShape \"sphere\" \"float radius\" 0.6\n");
    const Rgb path = centre_mean(render(scene, "path", "--spp 256"));
    const Rgb vcm = centre_mean(render(scene, "vcm", "--spp 64"));
    std::printf("[ measured ] coated red: path %.4f %.4f %.4f, vcm %.4f %.4f %.4f\n", path.r, path.g, path.b,
                vcm.r, vcm.g, vcm.b);
    EXPECT_NEAR(vcm.r, path.r, 0.03f * path.r);
    EXPECT_NEAR(vcm.g, path.g, 0.05f * path.g);
    EXPECT_NEAR(vcm.b, path.b, 0.05f * path.b);
}

}  // namespace
}  // namespace phos::testing
