// The pbrt-v4 and .scn versions of each bench scene describe the same scene, so with the same seed
// the path integrator must give the same image up to float rounding: the files differ in how
// numbers are written (fov 38 degrees vs a half angle of 0.331613 rad; sphere centres as a pbrt
// Translate vs .scn coordinates), which moves hit points by ulps and lets a few paths through the
// glass take another branch. We therefore bound the difference far below the render noise
// (relMSE <= 1e-3 while the noise of these renders against the reference is ~0.05 - 0.5).
// cornell-glass-mirror's mirror differs by definition: pbrt's conductor "reflectance" 0.99 is
// pbrt-v4's Fresnel form (eta 1, k from r: 0.99 at normal incidence, more towards grazing), the
// .scn mirror a constant 0.99, so paths that meet the mirror take other Russian-roulette
// decisions: its bound is relMSE 0.05 (two seeds of this render differ by 0.98; a camera or
// geometry mismatch decorrelates every path) with the mean within 0.5 %.
// Also: the pbrt cornell-diffuse renders within the bench bound of the reference.
#include <gtest/gtest.h>

#include "core/stats.h"
#include "film/film.h"
#include "film/metrics.h"
#include "integrators/path.h"
#include "io/image/image_io.h"
#include "io/load_scene.h"
#include "render/prepared.h"
#include "test_util.h"

namespace phos {
namespace {

Image render_path(const std::string& file, int size, int spp) {
    const scene::Scene s = io::load_scene(file);
    render::RenderOptions opt;
    opt.width = opt.height = size;
    opt.spp = spp;
    opt.seed = 9;
    Stats stats;
    render::Prepared prepared(s, opt, {}, stats);
    film::Film film(size, size);
    Progress progress(false);
    integrators::PathIntegrator().render(prepared, film, progress);
    return film.image();
}

TEST(PbrtVsScn, SameImageUpToRounding) {
    for (const std::string name : {"cornell-diffuse", "cornell-glass-mirror", "caustic-point"}) {
        const Image a = render_path(testing::shared_path("bench/scn/" + name + ".scn"), 64, 4);
        const Image b = render_path(testing::shared_path("bench/scenes/" + name + ".pbrt"), 64, 4);
        EXPECT_LE(film::rel_mse(a, b), name == "cornell-glass-mirror" ? 0.05 : 1e-3) << name;
        EXPECT_NEAR(film::mean_ratio(a, b), 1.0, 0.005) << name;
    }
}

TEST(PbrtVsScn, PbrtCornellDiffuseMatchesReference) {
    const Image img = render_path(testing::shared_path("bench/scenes/cornell-diffuse.pbrt"), 256, 64);
    const Image ref = io::read_image(testing::shared_path("bench/ref/cornell-diffuse.pfm"));
    EXPECT_LE(film::rel_mse(img, ref), 0.02);
    EXPECT_NEAR(film::mean_ratio(img, ref), 1.0, 0.02);
}

}  // namespace
}  // namespace phos
