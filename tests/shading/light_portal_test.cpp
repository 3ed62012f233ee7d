// pbrt-v4's portal infinite light (shading/light_portal.h): directions sampled through the portal
// from a point integrate to 1 and follow their pdf (chi-square), a constant sky through the portal
// gives Lambert's closed-form irradiance, escaped rays see radiance only through the portal, and
// photons start on the portal with weights averaging to its flux and pdfs matching pdf_Le.
#include <gtest/gtest.h>

#include <memory>

#include "core/rng.h"
#include "core/transform.h"
#include "core/warp.h"
#include "light_test_util.h"
#include "shading/infinite_light.h"
#include "support/chi_square.h"

namespace phos::shading {
namespace {

using test::expect_mean;
using test::image_texture;
using test::RunningStat;
using test::varied_map;

const SceneSphere kSphere{{0, 0, 0}, 4.0f};
const Wavelengths& kLambda = spectral::fixed_lambda();

// A 2 x 1.5 window in the plane y = 1, the sky above it (+y): (p3 - p0) x (p1 - p0) = +y.
const std::vector<Vec3> kWindow = {{-1, 1, -0.5f}, {1, 1, -0.5f}, {1, 1, 1.0f}, {-1, 1, 1.0f}};

scene::Light portal_light(int texture) {
    scene::Light rec;
    rec.kind = scene::Light::Kind::Infinite;
    rec.texture = texture;
    rec.equal_area = texture >= 0;
    rec.to_world = Transform::rotate(30, {0, 1, 1});
    rec.portal = kWindow;
    return rec;
}

// A ray from p along w passes through the window rectangle.
bool through_window(Vec3 p, Vec3 w) {
    if (!(w.y > 0) || !(p.y < 1)) return false;
    const float t = (1 - p.y) / w.y;
    const Vec3 q = p + w * t;
    return q.x >= -1 && q.x <= 1 && q.z >= -0.5f && q.z <= 1;
}

TEST(PortalLight, PdfIntegratesToOneAndVanishesOutsideThePortal) {
    constexpr int n = 16;
    const std::vector<scene::Texture> textures = {image_texture(n, n, varied_map(n))};
    const InfiniteLight light(portal_light(0), textures, kSphere);
    for (const Vec3 p : {Vec3(0, 0, 0), Vec3(0.7f, 0.4f, -0.3f), Vec3(-2, -1, 2)}) {
        SCOPED_TRACE(::testing::Message() << "p = " << p.x << " " << p.y << " " << p.z);
        const double total = phos::test::integrate_sphere(
            [&](Vec3 w) {
                const float pdf = light.pdf_Li(p, w, {}, {});
                EXPECT_TRUE(pdf == 0 || through_window(p, w)) << w.x << " " << w.y << " " << w.z;
                return double(pdf);
            },
            M_PI, 2048, 512);
        EXPECT_NEAR(total, 1.0, 0.01);
    }
    // Behind the portal (outside, above y = 1) nothing is sampled.
    Sampler rng(3);
    EXPECT_EQ(light.sample_Li({0, 2, 0}, rng.next2(), kLambda).pdf, 0.0f);
    EXPECT_EQ(light.pdf_Li({0, 2, 0}, {0, 1, 0}, {}, {}), 0.0f);
    // The photons' direction density over the sphere.
    const double photons = phos::test::integrate_sphere(
        [&](Vec3 w) {
            float pos = 0, dir = 0;
            light.pdf_Le({}, -w, pos, dir);
            return double(dir);
        },
        M_PI, 2048, 512);
    EXPECT_NEAR(photons, 1.0, 0.01);
}

TEST(PortalLight, SampledDirectionsFollowThePdfByChiSquare) {
    constexpr int n = 16;
    const std::vector<scene::Texture> textures = {image_texture(n, n, varied_map(n))};
    const InfiniteLight light(portal_light(0), textures, kSphere);
    const Vec3 p(0.3f, 0.2f, 0.1f);
    // Histogram around +y (the portal's normal): theta from +y up to where the window ends.
    const Frame around(Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0));
    phos::test::DirectionHistogram hist(16, 32, 0.5 * M_PI);
    Sampler rng(11);
    constexpr int kSamples = 100000;
    for (int i = 0; i < kSamples; ++i) {
        const LightLiSample s = light.sample_Li(p, rng.next2(), kLambda);
        if (!(s.pdf > 0)) {
            hist.add_residual();
            continue;
        }
        ASSERT_TRUE(through_window(p, s.wi));
        ASSERT_NEAR(light.pdf_Li(p, s.wi, {}, {}), s.pdf, 2e-3f * s.pdf);
        hist.add(around.to_local(s.wi));
    }
    hist.total = kSamples;
    const auto expected =
        hist.expected([&](Vec3 w) { return double(light.pdf_Li(p, around.to_world(w), {}, {})); });
    const phos::test::ChiSquareResult r = phos::test::chi_square(hist.counts, expected);
    EXPECT_TRUE(r.passed) << r.detail;
}

// A constant sky L through the window: the irradiance at a point facing it is Lambert's polygon
// formula with the window as the polygon; an escaped ray sees L only through the window.
TEST(PortalLight, ConstantSkyGivesLambertsIrradianceThroughTheWindow) {
    scene::Light rec = portal_light(-1);
    rec.color = Rgb(1, 2, 4);
    const InfiniteLight light(rec, {}, kSphere);
    const Vec3 p(0.4f, -0.5f, 0.2f), n = normalize(Vec3(0.2f, 1, -0.1f));
    Sampler rng(5);
    RunningStat irradiance;
    for (int i = 0; i < 40000; ++i) {
        const LightLiSample s = light.sample_Li(p, rng.next2(), kLambda);
        ASSERT_GT(s.pdf, 0);
        irradiance.add(double(light.Le_rgb(s.wi).g) * std::max(0.0f, dot(s.wi, n)) / s.pdf);
    }
    expect_mean(irradiance, test::lambert_irradiance(kWindow, p, n, 2.0), "irradiance through the window");
    const Vec3 in = normalize(Vec3(0.1f, 1, 0.1f)), beside = normalize(Vec3(2, 1, 0));
    EXPECT_GT(light.escaped_Le(p, in, kLambda).max(), 0.0f);
    EXPECT_TRUE(light.escaped_Le(p, beside, kLambda).is_black());
    EXPECT_TRUE(light.escaped_Le({0, 2, 0}, in, kLambda).is_black());  // outside, beyond the portal
}

// Photons start on the window, travel into the room, average the portal's flux, and their pdfs are
// pdf_Le's.
TEST(PortalLight, PhotonsStartOnThePortalWithItsFlux) {
    constexpr int n = 16;
    const std::vector<scene::Texture> textures = {image_texture(n, n, varied_map(n))};
    const InfiniteLight light(portal_light(0), textures, kSphere);
    Sampler rng(29);
    RunningStat flux;
    int none = 0;
    for (int i = 0; i < 100000; ++i) {
        const LightLeSample s = light.sample_Le(rng.next2(), rng.next2(), kLambda);
        if (s.weight.is_black()) {  // no photon (a zero-pdf direction)
            flux.add(0);
            ++none;
            continue;
        }
        ASSERT_NEAR(s.ray.origin.y, 1.0f, 1e-5f);
        ASSERT_TRUE(s.ray.origin.x >= -1 - 1e-5f && s.ray.origin.x <= 1 + 1e-5f);
        ASSERT_TRUE(s.ray.origin.z >= -0.5f - 1e-5f && s.ray.origin.z <= 1 + 1e-5f);
        ASSERT_LT(s.ray.dir.y, 0);
        float pos = 0, dir = 0;
        light.pdf_Le(s.n, s.ray.dir, pos, dir);
        ASSERT_NEAR(pos, s.pdf_pos, 1e-4f * pos);
        ASSERT_NEAR(dir, s.pdf_dir, 2e-3f * dir);
        flux.add(double(light.Le_rgb(-s.ray.dir).g) / (double(s.pdf_pos) * s.pdf_dir));
    }
    EXPECT_LT(none, 10);
    // power() sums the pixels at their centres: within 2 % of the photons' mean.
    EXPECT_NEAR(flux.mean(), light.power().g, 0.02 * light.power().g + 5 * flux.std_error());
}

}  // namespace
}  // namespace phos::shading
