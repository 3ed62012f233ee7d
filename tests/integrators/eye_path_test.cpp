// The eye path of ppm and sppm (integrators/eye_path.h) in a medium: single scattering along each
// stretch is the mean of `direct_samples` estimates, as direct light at a surface visible point is.
// A PPM hit point keeps its eye path's value for the whole render, so a single heavy-tailed sample
// (a camera ray passing just under an area light inside smoke) stays in the image for good: the
// agreement matrix found ppm's image mean 5 % off on such a scene from one such pixel. Here a
// camera ray runs just below a small area light inside fog, in a black box: the value is single
// scattering alone, unbiased with 1 or 16 samples (same mean), and 16 samples cut its variance
// about 16-fold.
#include "integrators/eye_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/rng.h"
#include "core/stats.h"
#include "render/prepared.h"
#include "support/shapes.h"

namespace phos::integrators {
namespace {

scene::Scene fog_under_a_light() {
    scene::Scene s;
    scene::Material black;
    black.diffuse = Rgb(0.0f);
    s.materials.push_back(black);
    scene::Medium fog;
    fog.sigma_a = Rgb(0.1f);
    fog.sigma_s = Rgb(0.5f);
    s.media.push_back(fog);
    scene::Shape box = testing::box(Vec3(-1.0f), Vec3(1.0f));
    box.material = 0;
    box.media = {0, -1};  // fog inside
    s.shapes.push_back(box);
    scene::Shape light =
        testing::quad({-0.1f, 0.9f, -0.1f}, {0.1f, 0.9f, -0.1f}, {0.1f, 0.9f, 0.1f}, {-0.1f, 0.9f, 0.1f});
    light.material = 0;
    const int l = s.add_area_light(light, Rgb(20.0f), true);
    s.lights[size_t(l)].medium = 0;
    scene::Camera cam;
    cam.eye = Vec3(-0.9f, 0.8f, 0.0f);
    cam.forward = Vec3(1, 0, 0);
    cam.fov = 0.5f;
    s.camera = cam;
    s.camera_medium = 0;
    return s;
}

struct Moments {
    double mean, variance;
};

Moments eye_path_moments(const render::Prepared& P, int direct_samples, int n) {
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        Sampler sampler(7, 0x657965ULL, uint64_t(i));
        VisiblePoint vp;
        RayCounts rays;
        const Ray ray{Vec3(-0.9f, 0.8f, 0.0f), Vec3(1, 0, 0)};
        const double v = trace_eye_path(P, ray, sampler, direct_samples, vp, rays).average();
        sum += v;
        sum2 += v * v;
    }
    const double mean = sum / n;
    return {mean, sum2 / n - mean * mean};
}

TEST(EyePath, SingleScatteringAveragesTheDirectSamples) {
    const scene::Scene s = fog_under_a_light();
    render::RenderOptions opt;
    opt.width = opt.height = 8;
    opt.max_depth = 0;  // the camera stretch alone: no visible point adds anything
    Stats stats;
    const render::Prepared P(s, opt, {}, stats);
    const int n = 20000;
    const Moments one = eye_path_moments(P, 1, n), sixteen = eye_path_moments(P, 16, n);
    std::printf("[ measured ] 1 sample: mean %.5f, variance %.3g; 16 samples: mean %.5f, variance %.3g\n",
                one.mean, one.variance, sixteen.mean, sixteen.variance);
    ASSERT_GT(one.mean, 0.0);
    // The same expectation (5 standard errors of the difference).
    const double se = std::sqrt((one.variance + sixteen.variance) / n);
    EXPECT_NEAR(sixteen.mean, one.mean, 5 * se);
    // The variance of a 16-sample mean: 1/16 of one sample's (the sample variance's own noise in a
    // heavy-tailed estimate allows a factor of two).
    EXPECT_LT(sixteen.variance, one.variance / 8);
}

}  // namespace
}  // namespace phos::integrators
