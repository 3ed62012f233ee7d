// Spectral transport through every integrator, against closed forms:
// - the white furnace stays white: a closed box of grey reflectance rho emitting grey radiance Le
//   on its inside converges to Le / (1 - rho) in every colour channel, though each sample sees
//   four wavelengths of a D65-shaped illuminant (the grey RGB read as an emitter);
// - a light given as a spectrum keeps its colour: the same box emitting a 2700 K blackbody (scaled
//   to luminance 1) converges to that spectrum's colour over (1 - rho), the colour-matching
//   functions' integral of the blackbody, in every channel.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/stats.h"
#include "film/film.h"
#include "integrators/registry.h"
#include "render/prepared.h"
#include "spectrum/distribution.h"
#include "support/shapes.h"

namespace phos::integrators {
namespace {

constexpr float kRho = 0.5f;

scene::Scene furnace(const std::optional<spectrum::Distribution>& spectrum) {
    scene::Scene s;
    scene::Material wall;
    wall.diffuse = Rgb(kRho);
    s.materials.push_back(wall);
    scene::Shape box = testing::box(Vec3(-1.0f), Vec3(1.0f));
    box.material = 0;
    Rgb L(1.0f);
    if (spectrum) L = spectrum->srgb();
    s.add_area_light(box, L, /*two_sided=*/true, spectrum);
    scene::Camera cam;
    cam.eye = Vec3(0.2f, -0.1f, 0.3f);
    cam.forward = Vec3(0.3f, -0.2f, -1.0f);
    cam.fov = 1.4f;
    s.camera = cam;
    return s;
}

// Channel c's mean over the pixels and its standard error (each pixel an independent estimate of
// the same value).
void channel_mean(const Image& img, int c, double& mean, double& error) {
    double sum = 0, sum2 = 0;
    const double n = double(img.pixels.size());
    for (const Rgb& p : img.pixels) sum += p[c], sum2 += double(p[c]) * p[c];
    mean = sum / n;
    error = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
}

Image render(const std::string& name, const scene::Scene& s) {
    RenderOptions opt;
    opt.width = opt.height = 16;
    // The progressive photon mappers' per-pixel estimates need more iterations to show a 2 % error.
    const bool progressive = name == "ppm" || name == "sppm";
    opt.spp = progressive ? 256 : 32;
    opt.max_depth = 100;
    opt.seed = 3;
    Stats stats;
    Prepared prepared(s, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    Progress progress(false);
    IntegratorConfig config;
    config.photon_map.global.photons = 100000;
    config.progressive.photons_per_iter = 20000;
    // PPM keeps each pixel's one hit point, and its direct light, for the whole render.
    if (name == "ppm") config.progressive.direct_samples = 512;
    make_integrator(integrator_kind(name), config)->render(prepared, film, progress);
    EXPECT_EQ(film.main().rejected(), 0u) << name;
    return film.image();
}

// Every pixel of every integrator converges to `expected` in each channel: within 5 standard
// errors of the pixels' mean plus 1 % (the photon map's and vcm's merging kernels are exact in a
// uniform field; the 1 % covers float accumulation over long paths and the photon maps' noise,
// which is common to all pixels and so not in the standard error).
void expect_furnace(const scene::Scene& s, Rgb expected, const char* what) {
    for (const char* name : {"path", "photonmap", "ppm", "sppm", "bdpt", "vcm"}) {
        const Image img = render(name, s);
        for (int c = 0; c < 3; ++c) {
            double mean, error;
            channel_mean(img, c, mean, error);
            std::printf("[ measured ] %s, %s, channel %d: %.4f +- %.4f (expected %.4f)\n", what, name, c,
                        mean, error, double(expected[c]));
            EXPECT_NEAR(mean, expected[c], 5 * error + 0.01 * expected[c]) << what << " " << name << " " << c;
            EXPECT_LT(error, 0.04 * expected[c]) << name << ": the test has power (a 20 % error would show)";
        }
    }
}

TEST(SpectralRender, WhiteFurnaceStaysWhiteInEveryIntegrator) {
    expect_furnace(furnace(std::nullopt), Rgb(1 / (1 - kRho)), "white furnace");
}

TEST(SpectralRender, BlackbodyFurnaceKeepsTheSpectrumsColourInEveryIntegrator) {
    const spectrum::Distribution bb = spectrum::Distribution::blackbody(2700.0f);
    const spectrum::Distribution L = bb.scaled(1 / bb.xyz().y);  // luminance 1, as pbrt-v4 scales it
    const Rgb colour = L.srgb();
    // A warm colour: the check has something to see.
    ASSERT_GT(colour.r, 1.5f * colour.b);
    expect_furnace(furnace(L), colour * (1 / (1 - kRho)), "2700 K furnace");
}

}  // namespace
}  // namespace phos::integrators
