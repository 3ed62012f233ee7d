// pbrt-v4's image texture filters end to end, rendered in process: a ground plane receding to the
// horizon under a fine checkerboard image (4-texel cells, tiled 100 times), seen by a 64 x 64
// camera at one sample per pixel; the albedo image (render_aovs) is the texture as each pixel
// filters it. Far from the camera, where a pixel covers many cells, "trilinear" and "ewa" show
// the checkerboard's mean in every pixel, while the default "bilinear" (no footprint) shows
// single cells: black and white. A default-filtered scene renders the same bits with or without a
// footprint-reading texture elsewhere in the scene, and with "bilinear" written out.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/stats.h"
#include "film/film.h"
#include "io/pbrt/pbrt_loader.h"
#include "render/aov.h"
#include "render/prepared.h"
#include "test_util.h"

namespace phos {
namespace {

using testing::TempDir;

constexpr int kSize = 64;

void write_checker_pfm(const std::string& path, int n) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fprintf(f, "PF\n%d %d\n-1\n", n, n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const float v = float((x / 4 + y / 4) % 2);
            const float rgb[3] = {v, v, v};
            std::fwrite(rgb, sizeof(float), 3, f);
        }
    std::fclose(f);
}

std::string scene_text(const std::string& filter_param, const std::string& extra = "") {
    return R"(LookAt 0 1 0  0 0.6 -10  0 1 0
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 64 "integer yresolution" 64
WorldBegin
Texture "checks" "spectrum" "imagemap" "string filename" "checker.pfm" "float uscale" 100 "float vscale" 100 )" +
           filter_param + "\n" + extra + R"(
Material "diffuse" "texture reflectance" "checks"
Shape "trianglemesh" "point3 P" [ -100 0 0  100 0 0  100 0 -200  -100 0 -200 ]
  "point2 uv" [ 0 0  1 0  1 1  0 1 ] "integer indices" [ 0 1 2  0 2 3 ]
)";
}

Image albedo(TempDir& dir, const std::string& name, const std::string& text) {
    const std::string path = dir.write(name + ".pbrt", text);
    const scene::Scene scene = io::load_pbrt(path);
    render::RenderOptions opt;
    opt.width = opt.height = kSize;
    opt.spp = 1;
    opt.seed = 3;
    opt.aovs = {"albedo"};
    Stats stats;
    const render::Prepared P(scene, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    render::render_aovs(P, film);
    return film.find_layer("albedo")->image();
}

// Rows whose ground lies 15 to 45 units away: the horizon is 3.6 pixel rows above the centre
// (the view looks down by atan(0.4 / 10)), a row k pixels below it sees the ground at about
// 90 / k units.
constexpr int kFarRowFirst = 30, kFarRowLast = 33;

TEST(PbrtTextureFilter, FarGroundIsTheMeanUnderTrilinearAndEwaButAliasedUnderBilinear) {
    TempDir dir;
    write_checker_pfm(dir.file("checker.pfm"), 64);
    const Image bilinear = albedo(dir, "bilinear", scene_text(""));
    const Image trilinear = albedo(dir, "trilinear", scene_text("\"string filter\" \"trilinear\""));
    const Image ewa = albedo(dir, "ewa", scene_text("\"string filter\" \"ewa\""));
    int extreme = 0, n = 0;
    for (int y = kFarRowFirst; y <= kFarRowLast; ++y)
        for (int x = 0; x < kSize; ++x) {
            ++n;
            EXPECT_NEAR(trilinear.at(x, y).average(), 0.5f, 0.06f) << x << " " << y;
            EXPECT_NEAR(ewa.at(x, y).average(), 0.5f, 0.06f) << x << " " << y;
            const float b = bilinear.at(x, y).average();
            if (std::fabs(b - 0.5f) > 0.3f) ++extreme;
        }
    // Bilinear lookups at one point per pixel: mostly near-black or near-white cells.
    EXPECT_GT(extreme, n / 3) << extreme << " of " << n;
    // Near the camera (the bottom rows, 3 units away) pixels still cover a few cells: the filtered
    // images are smooth there too, and the three agree on the mean over the row.
    for (const Image* img : {&trilinear, &ewa, &bilinear}) {
        double row = 0;
        for (int x = 0; x < kSize; ++x) row += img->at(x, kSize - 1).average() / kSize;
        EXPECT_NEAR(row, 0.5, 0.15);
    }
}

TEST(PbrtTextureFilter, DefaultBilinearIsUnchangedByFootprints) {
    TempDir dir;
    write_checker_pfm(dir.file("checker.pfm"), 64);
    const Image plain = albedo(dir, "plain", scene_text(""));
    const Image written = albedo(dir, "written", scene_text("\"string filter\" \"bilinear\""));
    // An unused EWA texture makes the renderer compute footprints for every textured hit.
    const Image with_footprints =
        albedo(dir, "footprints",
               scene_text("",
                          "Texture \"unused\" \"spectrum\" \"imagemap\" \"string filename\" \"checker.pfm\" "
                          "\"string filter\" \"ewa\""));
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            ASSERT_EQ(plain.at(x, y).r, written.at(x, y).r);
            ASSERT_EQ(plain.at(x, y).r, with_footprints.at(x, y).r) << x << " " << y;
            ASSERT_EQ(plain.at(x, y).g, with_footprints.at(x, y).g);
        }
}

}  // namespace
}  // namespace phos
