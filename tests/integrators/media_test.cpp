// Integrators in participating media on an analytic scene: a camera inside a closed, emitting,
// diffuse sphere (radiance Le towards the inside, albedo a) filled with a non-absorbing medium.
// Scattering without absorption moves light around but cannot change a uniform radiance field, so
// every pixel converges to Le / (1 - a) in every integrator that renders media correctly (the
// photon methods too: a uniform field has no kernel bias). Also: absorption darkens it, and the
// images are bit-identical for 1 and 2 threads.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdio>

#include "core/stats.h"
#include "film/film.h"
#include "integrators/registry.h"
#include "render/prepared.h"

namespace phos::integrators {
namespace {

scene::Scene fog_furnace(float albedo, float Le, Rgb sigma_a, Rgb sigma_s, float g) {
    scene::Scene s;
    scene::Material m;
    m.diffuse = Rgb(albedo);
    s.materials.push_back(m);
    scene::Medium fog;
    fog.sigma_a = sigma_a;
    fog.sigma_s = sigma_s;
    fog.g = g;
    s.media.push_back(fog);
    scene::Shape sphere;
    sphere.kind = scene::Shape::Kind::Sphere;
    sphere.center = Vec3(0.0f);
    sphere.radius = 1.0f;
    sphere.reverse_orientation = true;  // normal points inwards: it emits and reflects inside
    sphere.material = 0;
    sphere.media = {-1, 0};  // the outside (the normal's side, here the interior) is fog
    const int light = s.add_area_light(sphere, Rgb(Le));
    s.lights[size_t(light)].medium = 0;
    scene::Camera cam;
    cam.eye = Vec3(0.1f, -0.2f, 0.05f);
    cam.forward = Vec3(0, 0, -1);
    cam.fov = 1.2f;
    s.camera = cam;
    s.camera_medium = 0;
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

Image render(const std::string& name, const scene::Scene& s, int spp, const IntegratorConfig& config = {}) {
    RenderOptions opt;
    opt.width = opt.height = 16;
    opt.spp = spp;
    opt.max_depth = 200;
    opt.seed = 5;
    Stats stats;
    Prepared prepared(s, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    Progress progress(false);
    make_integrator(integrator_kind(name), config)->render(prepared, film, progress);
    return film.image();
}

IntegratorConfig small_budgets() {
    IntegratorConfig c;
    c.photon_map.global.photons = 40000;
    c.photon_map.volume.photons = 40000;
    c.photon_map.gather_rays = 16;
    c.progressive.photons_per_iter = 20000;
    return c;
}

TEST(MediaFurnace, PathConvergesToTheClosedForm) {
    const scene::Scene s = fog_furnace(0.5f, 1.0f, Rgb(0.0f), Rgb(2.0f), 0.5f);
    const MeanAndError m = image_mean(render("path", s, 32));
    // Pixels are independent estimates: 5 standard errors plus 0.5 % for float accumulation.
    EXPECT_NEAR(m.mean, 2.0, 5 * m.std_error + 0.01);
    EXPECT_LT(m.std_error, 0.04);  // the test has power
}

TEST(MediaFurnace, ChromaticMediumKeepsEveryChannelAtTheClosedForm) {
    // Different scattering per channel, no absorption: each channel still converges to 2.
    const scene::Scene s = fog_furnace(0.5f, 1.0f, Rgb(0.0f), Rgb(0.5f, 2.0f, 4.0f), -0.3f);
    const Image img = render("path", s, 128);
    for (int c = 0; c < 3; ++c) {
        double sum = 0, sum2 = 0;
        for (const Rgb& p : img.pixels) sum += p[c], sum2 += double(p[c]) * p[c];
        const double n = double(img.pixels.size()), mean = sum / n;
        const double error = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
        std::printf("[ measured ] chromatic furnace, channel %d: %.4f +- %.4f (expected 2)\n", c, mean,
                    error);
        // Pixels are independent estimates: 5 standard errors plus 0.5 % for float accumulation.
        EXPECT_NEAR(mean, 2.0, 5 * error + 0.01) << "channel " << c;
        EXPECT_LT(error, 0.04) << "channel " << c << ": the test has power";
    }
}

TEST(MediaFurnace, AbsorptionDarkens) {
    const scene::Scene s = fog_furnace(0.5f, 1.0f, Rgb(1.0f), Rgb(1.0f), 0.0f);
    const MeanAndError m = image_mean(render("path", s, 16));
    // sigma_t = 2 over the ~1 unit to the wall keeps about exp(-2) of the wall's light, and
    // scattering cannot make up for the absorbed half: far below the non-absorbing 2.
    EXPECT_LT(m.mean, 1.0);
    EXPECT_GT(m.mean, 0.1);
}

TEST(MediaFurnace, SppmConvergesToTheClosedForm) {
    // A uniform field leaves no kernel bias inside the medium; what remains is photon noise
    // correlated across pixels (so the per-pixel error underestimates it): 4 % of the answer.
    // 64 iterations: seeds 1-10 gave 1.94-1.99 (at 16 iterations the spread over seeds reached
    // 1.91-2.01, too close to the bound for a fixed seed to say anything).
    // (photonmap and ppm measure 1.87 and 1.75 here: their volume estimates lose the part of the
    // kernel that reaches through the wall next to it -- a known boundary bias, see docs/media.md.)
    const scene::Scene s = fog_furnace(0.5f, 1.0f, Rgb(0.0f), Rgb(2.0f), 0.5f);
    const MeanAndError m = image_mean(render("sppm", s, 64, small_budgets()));
    EXPECT_NEAR(m.mean, 2.0, 0.08);
}

TEST(MediaDeterminism, IdenticalAtOneAndTwoThreads) {
    const scene::Scene s = fog_furnace(0.5f, 1.0f, Rgb(0.1f), Rgb(1.0f), 0.3f);
    for (const char* name : {"path", "photonmap", "ppm", "sppm"}) {
        Image a, b;
        tbb::task_arena(1).execute([&] { a = render(name, s, 2, small_budgets()); });
        tbb::task_arena(2).execute([&] { b = render(name, s, 2, small_budgets()); });
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        bool same = true;
        for (size_t i = 0; i < a.pixels.size(); ++i) same &= a.pixels[i] == b.pixels[i];
        EXPECT_TRUE(same) << name;
    }
}

}  // namespace
}  // namespace phos::integrators
