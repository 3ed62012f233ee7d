// SPPM and PPM against the independent references of ../shared/bench (256x256): the error falls as
// iterations grow on all three bench scenes, the point-light caustic (which path tracing cannot
// render) converges to the reference's window mean, and the image is bit-identical for 1 and 2
// threads. Photon counts are reduced (50k per iteration) to keep the test short; relMSE is taken
// on the full image (no downsampling).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstring>

#include "core/stats.h"
#include "film/film.h"
#include "film/metrics.h"
#include "integrators/path.h"
#include "integrators/ppm.h"
#include "integrators/sppm.h"
#include "io/image/image_io.h"
#include "io/load_scene.h"
#include "render/prepared.h"
#include "test_util.h"

namespace phos {
namespace {

Image render(const std::string& name, const std::string& integrator, int iterations, int size = 256,
             uint64_t photons = 50000) {
    const scene::Scene s = io::load_scene(testing::shared_path("bench/scn/" + name + ".scn"));
    render::RenderOptions opt;
    opt.width = opt.height = size;
    opt.spp = iterations;
    opt.seed = 3;
    opt.regularize = 0;  // plain path tracing: the point light's caustic is out of its reach
    Stats stats;
    render::Prepared prepared(s, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    Progress progress(false);
    integrators::ProgressiveOptions po;
    po.photons_per_iter = photons;
    if (integrator == "sppm") integrators::SppmIntegrator(po).render(prepared, film, progress);
    if (integrator == "ppm") integrators::PpmIntegrator(po).render(prepared, film, progress);
    if (integrator == "path") integrators::PathIntegrator().render(prepared, film, progress);
    return film.image();
}

Image reference(const std::string& name) {
    return io::read_image(testing::shared_path("bench/ref/" + name + ".pfm"));
}

void expect_converging(const std::string& name, double max_final) {
    const Image ref = reference(name);
    const double e4 = film::rel_mse(render(name, "sppm", 4), ref);
    const double e16 = film::rel_mse(render(name, "sppm", 16), ref);
    std::printf("%s sppm relMSE: 4 it %.5f, 16 it %.5f\n", name.c_str(), e4, e16);
    EXPECT_LT(e16, 0.7 * e4);
    EXPECT_LT(e16, max_final);
}

TEST(SppmReference, CornellDiffuseConverges) { expect_converging("cornell-diffuse", 0.02); }
TEST(SppmReference, CornellGlassMirrorConverges) { expect_converging("cornell-glass-mirror", 0.03); }
TEST(SppmReference, CausticPointConverges) { expect_converging("caustic-point", 0.1); }

TEST(SppmReference, PointLightCausticConvergesWherePathTracingFails) {
    const Image sppm = render("caustic-point", "sppm", 16, 256, 100000);
    const Image path = render("caustic-point", "path", 4);
    const Image ref = reference("caustic-point");
    const double w_sppm = film::window_mean(sppm, 104, 128, 132, 156);
    const double w_path = film::window_mean(path, 104, 128, 132, 156);
    const double w_ref = film::window_mean(ref, 104, 128, 132, 156);
    std::printf("caustic window: sppm %.3f, path %.3f, reference %.3f\n", w_sppm, w_path, w_ref);
    EXPECT_NEAR(w_ref, 4.58, 0.05);
    EXPECT_NEAR(w_sppm / 4.58, 1.0, 0.15);
    EXPECT_LT(w_path, 0.5 * 4.58);
    EXPECT_NEAR(film::mean_ratio(sppm, ref), 1.0, 0.03);
}

TEST(SppmReference, PpmRendersTheCausticAndConverges) {
    const Image ref = reference("caustic-point");
    const Image a = render("caustic-point", "ppm", 4);
    const Image b = render("caustic-point", "ppm", 16);
    const double ea = film::rel_mse(a, ref), eb = film::rel_mse(b, ref);
    const double w = film::window_mean(b, 104, 128, 132, 156);
    std::printf("caustic-point ppm relMSE: 4 it %.5f, 16 it %.5f, window %.3f\n", ea, eb, w);
    EXPECT_LT(eb, 0.8 * ea);
    EXPECT_NEAR(w / 4.58, 1.0, 0.15);
}

bool identical(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(a.pixels[0])) == 0;
}

TEST(SppmDeterminism, SameImageForOneAndTwoThreads) {
    for (const char* integrator : {"sppm", "ppm"}) {
        Image one, two;
        {
            tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
            one = render("cornell-glass-mirror", integrator, 3, 96, 20000);
        }
        {
            tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
            two = render("cornell-glass-mirror", integrator, 3, 96, 20000);
        }
        EXPECT_TRUE(identical(one, two)) << integrator;
        EXPECT_GT(film::mean_value(one), 0.01);
    }
}

}  // namespace
}  // namespace phos
