// Analytic integrator tests: a camera inside a closed diffuse sphere that also emits radiance Le
// towards the inside. Every point sees the same radiance, so the answer is known in closed form:
// path tracing gives Le / (1 - albedo) (all bounces), Whitted gives Le + albedo * Le (one bounce).
#include <gtest/gtest.h>

#include <cmath>

#include "core/stats.h"
#include "film/film.h"
#include "integrators/path.h"
#include "integrators/whitted.h"
#include "render/prepared.h"

namespace phos::integrators {
namespace {

scene::Scene emitting_sphere(float albedo, float Le) {
    scene::Scene s;
    scene::Material m;
    m.diffuse = Rgb(albedo);
    s.materials.push_back(m);
    scene::Shape sphere;
    sphere.kind = scene::Shape::Kind::Sphere;
    sphere.center = Vec3(0.0f);
    sphere.radius = 1.0f;
    sphere.reverse_orientation = true;  // normal points inwards, so it emits and reflects inside
    sphere.material = 0;
    s.add_area_light(sphere, Rgb(Le));
    scene::Camera cam;
    cam.eye = Vec3(0.1f, -0.2f, 0.05f);
    cam.forward = Vec3(0, 0, -1);
    cam.fov = 1.2f;
    s.camera = cam;
    return s;
}

struct MeanAndError {
    double mean, std_error;
};

MeanAndError image_mean(const Image& img) {
    double sum = 0, sum2 = 0;
    const double n = double(img.pixels.size());
    for (const Rgb& p : img.pixels) {
        const double v = p.average();
        sum += v;
        sum2 += v * v;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

Image render(Integrator& integrator, const scene::Scene& s, int spp, int max_depth) {
    RenderOptions opt;
    opt.width = opt.height = 24;
    opt.spp = spp;
    opt.max_depth = max_depth;
    opt.seed = 3;
    Stats stats;
    Prepared prepared(s, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    Progress progress(false);
    integrator.render(prepared, film, progress);
    return film.image();
}

TEST(Furnace, PathTracingSumsAllBounces) {
    const float albedo = 0.5f, Le = 1.0f;
    PathIntegrator path;
    const MeanAndError m = image_mean(render(path, emitting_sphere(albedo, Le), 16, 1000));
    const double expected = Le / (1 - albedo);
    // Pixels are independent estimates; 5 standard errors plus 0.5 % for float accumulation.
    EXPECT_NEAR(m.mean, expected, 5 * m.std_error + 0.005 * expected);
    EXPECT_LT(m.std_error, 0.02 * expected);  // the test has real power
}

TEST(Furnace, PathDepthLimitTruncatesTheSeries) {
    // With max_depth = 2 the series stops after two bounces: Le (1 + a + a^2).
    PathIntegrator path;
    const MeanAndError m = image_mean(render(path, emitting_sphere(0.5f, 1.0f), 16, 2));
    EXPECT_NEAR(m.mean, 1.75, 5 * m.std_error + 0.005);
}

TEST(Furnace, WhittedAddsOneDiffuseBounceOfDirectLight) {
    WhittedIntegrator whitted;
    const MeanAndError m = image_mean(render(whitted, emitting_sphere(0.5f, 1.0f), 16, 8));
    EXPECT_NEAR(m.mean, 1.5, 5 * m.std_error + 0.005);
}

}  // namespace
}  // namespace phos::integrators
