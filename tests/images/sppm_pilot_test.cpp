// SPPM's pilot pass (--radius-photons): the radius rule of pilot_r2, and that the pilot's photons
// never reach the estimate: after one iteration (the pilot) the image is direct light only.
#include <gtest/gtest.h>

#include "core/stats.h"
#include "film/film.h"
#include "film/metrics.h"
#include "integrators/pilot_radius.h"
#include "integrators/sppm.h"
#include "io/load_scene.h"
#include "render/prepared.h"
#include "test_util.h"

namespace phos {
namespace {

using integrators::pilot_r2;
using integrators::PilotRadius;

TEST(SppmPilot, RadiusHoldsKPhotonsWithinBounds) {
    // Bounds 1/16 ... 4 × R₀²; the pilot gathered in 4 R₀² (R₀² = 1).
    const PilotRadius a{64, 1.0 / 16, 4};
    EXPECT_DOUBLE_EQ(pilot_r2(a, 4.0, 128), 2.0);           // twice k photons: half the area
    EXPECT_DOUBLE_EQ(pilot_r2(a, 4.0, 16), 4.0);            // too few: the largest disc
    EXPECT_DOUBLE_EQ(pilot_r2(a, 4.0, 1000000), 1.0 / 16);  // a bright caustic: the smallest
    EXPECT_DOUBLE_EQ(pilot_r2(a, 4.0, 0), 1.0);             // no photons: the automatic radius
}

Image render_sppm(int iterations, double radius_photons) {
    const scene::Scene s = io::load_scene(testing::shared_path("bench/scn/caustic-point.scn"));
    render::RenderOptions opt;
    opt.width = opt.height = 64;
    opt.spp = iterations;
    opt.seed = 5;
    Stats stats;
    render::Prepared prepared(s, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    Progress progress(false);
    integrators::ProgressiveOptions po;
    po.photons_per_iter = 20000;
    po.radius_photons = radius_photons;
    integrators::SppmIntegrator(po).render(prepared, film, progress);
    return film.image();
}

TEST(SppmPilot, PilotPhotonsAreNotInTheEstimate) {
    // Same seed, so both runs trace the same eye paths and direct light; without the pilot the
    // first iteration's photons add the caustic (indirect light, invisible to shadow rays).
    const Image on = render_sppm(1, 64), off = render_sppm(1, 0);
    ASSERT_EQ(on.pixels.size(), off.pixels.size());
    double extra = 0;
    for (size_t i = 0; i < on.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            EXPECT_LE(on.pixels[i][c], off.pixels[i][c]);
            extra += off.pixels[i][c] - on.pixels[i][c];
        }
    EXPECT_GT(extra, 0.05 * on.pixels.size());  // the photons' share, all of it missing with the pilot
    // The caustic window (bench caustic-point at 256 px, here a quarter): photons only.
    const double w_on = film::window_mean(on, 26, 32, 33, 39), w_off = film::window_mean(off, 26, 32, 33, 39);
    std::printf("caustic window after 1 iteration: pilot %.3f, no pilot %.3f\n", w_on, w_off);
    EXPECT_LT(w_on, 0.2 * w_off);
    // Later iterations do use photons: the caustic appears.
    EXPECT_GT(film::window_mean(render_sppm(4, 64), 26, 32, 33, 39), 0.25 * w_off);
}

}  // namespace
}  // namespace phos
