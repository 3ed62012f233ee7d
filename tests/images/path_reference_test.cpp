// The path integrator against the independent reference of ../shared/bench: cornell-diffuse at
// 256x256 and 64 spp must meet the bound of bench/README.md (relMSE <= 0.02, mean within 2 %).
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

Image render_path(const std::string& scene_file, int spp) {
    const scene::Scene s = io::load_scene(scene_file);
    render::RenderOptions opt;
    opt.width = opt.height = 256;
    opt.spp = spp;
    opt.max_depth = 16;
    opt.seed = 1;
    Stats stats;
    render::Prepared prepared(s, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    Progress progress(false);
    integrators::PathIntegrator().render(prepared, film, progress);
    return film.image();
}

TEST(PathReference, CornellDiffuseScnMatchesPbrtReference) {
    const Image img = render_path(testing::shared_path("bench/scn/cornell-diffuse.scn"), 64);
    const Image ref = io::read_image(testing::shared_path("bench/ref/cornell-diffuse.pfm"));
    const double rel_mse = film::rel_mse(img, ref);
    const double ratio = film::mean_ratio(img, ref);
    RecordProperty("relMSE", std::to_string(rel_mse));
    std::printf("cornell-diffuse path 64 spp: relMSE %.5f mean ratio %.4f\n", rel_mse, ratio);
    EXPECT_LE(rel_mse, 0.02);
    EXPECT_NEAR(ratio, 1.0, 0.02);
}

}  // namespace
}  // namespace phos
