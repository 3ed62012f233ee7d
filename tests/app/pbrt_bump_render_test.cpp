// pbrt materials' bump and normal maps rendered by `phos render`: a diffuse floor under an
// overhead distant light, seen straight down, with a linear-ramp "displacement" or a tilted
// "normalmap", is dimmed by exactly the cosine of the tilt the closed form gives.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "io/image/image_io.h"
#include "test_util.h"

namespace phos {
namespace {

using testing::run_phos;
using testing::TempDir;

// A PFM of w x h pixels (grey or RGB triples), top row first in `rgb`.
void write_pfm(const std::string& path, int w, int h, const std::vector<float>& rgb) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fprintf(f, "PF\n%d %d\n-1\n", w, h);
    for (int y = h - 1; y >= 0; --y) std::fwrite(&rgb[size_t(3 * y * w)], sizeof(float), size_t(3 * w), f);
    std::fclose(f);
}

// The floor [-1, 1]^2 at y = 0 with uv over it (dp/du = (2, 0, 0), dp/dv = (0, 0, 2)); the camera
// sees its middle, u and v in [0.25, 0.75], where the clamped 2 x 2 ramp image below is exactly
// d = 2u (texel centres at u = 1/4, 3/4 hold 1/2, 3/2).
std::string scene_text(const std::string& material) {
    return R"(LookAt 0 5 0  0 0 0  0 0 1
Camera "orthographic" "float screenwindow" [ -0.5 0.5 -0.5 0.5 ]
PixelFilter "box"
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin
LightSource "distant" "point3 from" [ 0 1 0 ] "point3 to" [ 0 0 0 ] "rgb L" [ 1 1 1 ]
Texture "ramp" "float" "imagemap" "string filename" "ramp.pfm" "string wrap" "clamp"
)" + material +
           "\nShape \"trianglemesh\" \"point3 P\" [ -1 0 -1  1 0 -1  1 0 1  -1 0 1 ] \"point2 uv\" [ 0 0 1 0 "
           "1 1 0 1 ] "
           "\"integer indices\" [ 0 1 2 0 2 3 ]\n";
}

double render_mean(TempDir& dir, const std::string& name, const std::string& material) {
    const std::string scene = dir.write(name + ".pbrt", scene_text(material));
    const std::string out = dir.file(name + "_out.pfm");
    const auto r = run_phos("render " + scene + " --spp 4 --integrator path --seed 1 --quiet -o " + out);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const Image img = io::read_image(out, false);
    double sum = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            sum += (double(img.at(x, y).r) + img.at(x, y).g + img.at(x, y).b) / 3;
    return sum / (double(img.width) * img.height);
}

TEST(PbrtBumpRender, RampAndNormalMapDimTheFloorByTheTiltsCosine) {
    TempDir dir;
    write_pfm(dir.file("ramp.pfm"), 2, 2,
              {0.5f, 0.5f, 0.5f, 1.5f, 1.5f, 1.5f, 0.5f, 0.5f, 0.5f, 1.5f, 1.5f, 1.5f});
    const float t = 0.5f;  // the normal map's tilt about dp/du
    write_pfm(dir.file("normals.pfm"), 1, 1, {0.5f + 0.5f * std::sin(t), 0.5f, 0.5f + 0.5f * std::cos(t)});
    const std::string diffuse = "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]";
    const double flat = render_mean(dir, "flat", diffuse);
    ASSERT_GT(flat, 0.05);
    // d = 2u over dp/du = (2, 0, 0): dp/du' = (2, 0, 2) against dp/dv = (0, 0, 2), a tilt of 45
    // degrees; the overhead light's cosine is 1/sqrt(2). Direct light only, a delta light: the
    // ratio is exact up to rounding.
    EXPECT_NEAR(render_mean(dir, "bump", diffuse + " \"texture displacement\" \"ramp\"") / flat,
                1 / std::sqrt(2.0), 1e-4);
    EXPECT_NEAR(render_mean(dir, "nmap", diffuse + " \"string normalmap\" \"normals.pfm\"") / flat,
                std::cos(t), 1e-4);
}

}  // namespace
}  // namespace phos
