// Regression test: direct light sampled from points lying ON an inward-emitting sphere light (hits
// on the emitter itself, accurate only to a few ulps) must see the whole interior. Rounding puts
// half of such points "outside", where they would receive no light at all.
#include <gtest/gtest.h>

#include "core/rng.h"
#include "core/warp.h"
#include "shading/lights.h"
#include "spectral_test_util.h"

namespace phos::shading {
namespace {

TEST(SphereLight, PointsOnTheSurfaceSeeTheWholeInterior) {
    scene::Scene s;
    s.materials.emplace_back();
    scene::Shape sphere;
    sphere.kind = scene::Shape::Kind::Sphere;
    sphere.radius = 1;
    sphere.reverse_orientation = true;  // emits inwards
    s.add_area_light(sphere, Rgb(1.0f));
    Bounds b;
    b.extend(Vec3(-1.0f));
    b.extend(Vec3(1.0f));
    const LightSet lights(s, b);
    Sampler points(5);
    constexpr int kPoints = 500, kSamples = 400;
    for (int k = 0; k < kPoints; ++k) {
        const Vec3 n = warp::uniform_sphere(points.next2());  // |n| = 1 up to rounding, either side
        Sampler sampler(11, uint64_t(k));
        const Wavelengths lambda = spectral::stratified_lambda(k, kPoints);
        Spectrum E(0.0f);
        for (int i = 0; i < kSamples; ++i) {
            const LightLiSample ls = lights[0].sample_Li(n, sampler.next2(), lambda);
            const float c = dot(ls.wi, -n);
            if (ls.pdf > 0 && c > 0) E += ls.L * (c / ls.pdf);
        }
        // Irradiance from a uniform hemisphere of radiance L is pi L (here L is RGB white read as
        // an illuminant). Inside a sphere, uniform area sampling makes cos_x cos_l / d^2 constant
        // (= 1 / 4r^2), so every sample returns exactly pi L: the tolerance only covers float
        // rounding.
        EXPECT_TRUE(
            spectral::spectra_near(E / float(kSamples), spectral::illuminant(Rgb(1.0f), lambda) * kPi, 1e-3))
            << "point " << k;
    }
}

}  // namespace
}  // namespace phos::shading
