// pbrt-v4's "subsurface" material rendered by `phos render` (a random walk in the material's
// medium under its dielectric boundary), a sphere filling the view under a uniform white sky:
//  - white furnace: with no absorption, every path that enters the sphere leaves it again, so the
//    sphere is exactly as bright as the sky (the path tracer's weights are 1 through a smooth
//    dielectric and a grey non-absorbing medium; only Russian roulette adds noise); tolerance 5
//    standard errors of the image mean plus 0.5 % for the truncation at the maximum depth, with
//    path's default --regularize (which leaves subsurface boundaries unwidened: widened, the
//    walk's many crossings lost 7 % at 256 samples per pixel);
//  - with absorption it is darker;
//  - pbrt-v4's named media in their albedos' order: skim milk (red albedo 0.998) brighter in red
//    than ketchup (0.75), and ketchup redder than it is blue (albedo 0.02), at scale 10.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "io/image/image_io.h"
#include "test_util.h"

namespace phos {
namespace {

using testing::run_phos;
using testing::TempDir;

struct Mean {
    Rgb rgb;
    double mean, std_error;  // over the pixels' channel averages
};

// Renders the unit sphere with `material` (none: the sky alone) seen orthographically from +z,
// the view [-0.5, 0.5]^2 inside its silhouette.
Mean render(TempDir& dir, const std::string& name, const std::string& material) {
    const std::string text = R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "orthographic" "float screenwindow" [ -0.5 0.5 -0.5 0.5 ]
PixelFilter "box"
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
)" + (material.empty() ? std::string()
                       : "Material \"subsurface\" " + material + "\nShape \"sphere\" \"float radius\" 1\n");
    const std::string scene = dir.write(name + ".pbrt", text);
    const std::string out = dir.file(name + "_out.pfm");
    const auto r = run_phos("render " + scene +
                            " --spp 128 --integrator path --max-depth 10000 --seed 3 --quiet -o " + out);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const Image img = io::read_image(out, false);
    Mean m{Rgb(0.0f), 0, 0};
    double sum = 0, sum2 = 0;
    for (const Rgb& p : img.pixels) {
        m.rgb = m.rgb + p;
        sum += p.average();
        sum2 += double(p.average()) * p.average();
    }
    const double n = double(img.pixels.size());
    m.rgb = m.rgb / float(n);
    m.mean = sum / n;
    m.std_error = std::sqrt(std::max(0.0, sum2 / n - m.mean * m.mean) / n);
    return m;
}

TEST(PbrtSubsurfaceRender, WhiteFurnaceAbsorptionAndNamedMedia) {
    TempDir dir;
    const Mean sky = render(dir, "sky", "");
    ASSERT_GT(sky.mean, 0.1);
    const Mean furnace =
        render(dir, "furnace", "\"rgb sigma_a\" [ 0 0 0 ] \"rgb sigma_s\" [ 2 2 2 ] \"float eta\" 1.33");
    EXPECT_NEAR(furnace.mean / sky.mean, 1.0, 5 * furnace.std_error / sky.mean + 0.005)
        << "furnace " << furnace.mean << " +- " << furnace.std_error << ", sky " << sky.mean;
    const Mean absorbing = render(
        dir, "absorbing", "\"rgb sigma_a\" [ 0.5 0.5 0.5 ] \"rgb sigma_s\" [ 2 2 2 ] \"float eta\" 1.33");
    EXPECT_LT(absorbing.mean, 0.9 * furnace.mean);

    const Mean milk = render(dir, "milk", "\"string name\" \"Skimmilk\" \"float scale\" 10");
    const Mean ketchup = render(dir, "ketchup", "\"string name\" \"Ketchup\" \"float scale\" 10");
    // Measured (128 spp): skim milk's red 1.12, ketchup's red 0.086 and blue 0.021.
    EXPECT_GT(milk.rgb.r, ketchup.rgb.r + 0.5f) << milk.rgb.r << " " << ketchup.rgb.r;
    EXPECT_GT(ketchup.rgb.r, 2 * ketchup.rgb.b) << ketchup.rgb.r << " " << ketchup.rgb.b;
}

}  // namespace
}  // namespace phos
