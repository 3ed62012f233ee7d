// Lights driven by images in pbrt-v4's conventions: the equal-area environment map (lookup, the
// pixel distribution by chi-square, a constant map against a constant L, a one-hot map lighting a
// plane from its pixel's direction), the goniometric light (the map's direction, power, photon
// weights) and the projection light (the slide's orientation, pdf_Le integrating to 1 and matching
// sample_Le, power).
#include <gtest/gtest.h>

#include <memory>

#include "accel/embree_scene.h"
#include "core/equal_area.h"
#include "core/error.h"
#include "core/transform.h"
#include "core/warp.h"
#include "light_test_util.h"
#include "shading/area_light.h"
#include "shading/equal_area_map.h"
#include "shading/goniometric_light.h"
#include "shading/infinite_light.h"
#include "shading/projection_light.h"
#include "support/chi_square.h"

namespace phos::shading {
namespace {

using test::expect_mean;
using test::expect_means;
using test::image_texture;
using test::RunningStat;
using test::SpectralStat;
using test::varied_map;

const SceneSphere kSphere{{0, 0, 0}, 2.0f};
const Wavelengths& kLambda = spectral::fixed_lambda();

Spectrum texel_spectrum(Rgb c, const Wavelengths& lambda) {
    return spectrum::RgbSpectrum(c, spectrum::RgbSpectrum::Use::Illuminant, spectrum::RgbSpectrum::Fit::Table)
        .sample(lambda);
}

TEST(EqualAreaMap, SamplingMatchesThePixelsByChiSquare) {
    constexpr int n = 16;
    const std::vector<Rgb> texels = varied_map(n);
    const EqualAreaMap map(texels, n);
    double sum = 0;
    for (const Rgb& c : texels) sum += c.average();
    const int N = 200000;
    std::vector<double> observed(n * n, 0.0), expected(n * n, 0.0);
    for (int k = 0; k < n * n; ++k) expected[size_t(k)] = N * texels[size_t(k)].average() / sum;
    Sampler rng(3);
    RunningStat inv_pdf;
    for (int i = 0; i < N; ++i) {
        float pdf = 0;
        const Vec3 w = map.sample(rng.next2(), &pdf);
        ASSERT_GT(pdf, 0);
        // The pixel the direction lands in, found by the mapping alone.
        const Vec2 uv = equal_area_sphere_to_square(w);
        const int x = std::min(int(uv.x * n), n - 1), y = std::min(int(uv.y * n), n - 1);
        observed[size_t(y * n + x)] += 1;
        // The solid-angle pdf is the pixel's share over its solid angle 4 pi / n^2.
        const double share = texels[size_t(y * n + x)].average() / sum;
        ASSERT_NEAR(map.pdf(w), share / (4 * M_PI / (n * n)), 1e-4 * map.pdf(w) + 1e-9);
        ASSERT_EQ(map.lookup(w), texels[size_t(y * n + x)]);
        inv_pdf.add(1 / map.pdf(w));
    }
    const phos::test::ChiSquareResult r = phos::test::chi_square(observed, expected);
    EXPECT_TRUE(r.passed) << r.detail;
    // E[1/pdf] is the solid angle of the lit pixels.
    int lit = 0;
    for (const Rgb& c : texels) lit += c.average() > 0;
    expect_mean(inv_pdf, 4 * M_PI * lit / (n * n), "E[1/pdf]");
}

// An equal-area map of one colour is the constant light of that colour: same radiance colour,
// power and irradiance estimate, whatever the rotation.
TEST(InfiniteLightEqualArea, ConstantMapEqualsConstantL) {
    constexpr int n = 8;
    std::vector<scene::Texture> textures = {image_texture(n, n, std::vector<Rgb>(n * n, Rgb(0.5f, 1, 2)))};
    scene::Light map_rec;
    map_rec.kind = scene::Light::Kind::Infinite;
    map_rec.texture = 0;
    map_rec.equal_area = true;
    map_rec.color = Rgb(2.0f);
    map_rec.to_world = Transform::rotate(40, {1, 1, 0});
    scene::Light const_rec;
    const_rec.kind = scene::Light::Kind::Infinite;
    const_rec.color = Rgb(1, 2, 4);
    const InfiniteLight map(map_rec, textures, kSphere), constant(const_rec, {}, kSphere);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(map.power()[c], constant.power()[c], 1e-5 * constant.power()[c]);
    Sampler rng(5);
    SpectralStat irr;
    const Vec3 normal = normalize(Vec3(0.2f, 1, -0.3f));
    for (int i = 0; i < 20000; ++i) {
        const Vec3 w = warp::uniform_sphere(rng.next2());
        ASSERT_EQ(map.Le_rgb(w), Rgb(1, 2, 4));
        ASSERT_NEAR(map.pdf_direction(w), 1 / (4 * kPi), 1e-6f);
        const LightLiSample s = map.sample_Li({0, 0, 0}, rng.next2(), kLambda);
        ASSERT_GT(s.pdf, 0);
        irr.add(s.L * (std::max(0.0f, dot(s.wi, normal)) / s.pdf));
    }
    expect_means(irr, texel_spectrum(Rgb(1, 2, 4), kLambda) * kPi, "irradiance pi L");
}

// One lit pixel: every direction sample_Li returns lies in that pixel's direction (rotated by the
// light's transform), and a plane facing it receives L (4 pi / N) cos from there; sample_Le's
// photons all travel away from that direction and carry the light's power on average.
TEST(InfiniteLightEqualArea, OneHotMapLightsFromItsPixel) {
    constexpr int n = 16, hx = 12, hy = 5;
    std::vector<Rgb> texels(n * n, Rgb(0.0f));
    texels[size_t(hy * n + hx)] = Rgb(3, 3, 3);
    std::vector<scene::Texture> textures = {image_texture(n, n, texels)};
    scene::Light rec;
    rec.kind = scene::Light::Kind::Infinite;
    rec.texture = 0;
    rec.equal_area = true;
    rec.color = Rgb(1.0f);
    const Transform rot = Transform::rotate(-70, {0, 1, 1});
    rec.to_world = rot;
    const InfiniteLight light(rec, textures, kSphere);
    const Vec3 sun = normalize(rot.vector(equal_area_square_to_sphere({(hx + 0.5f) / n, (hy + 0.5f) / n})));
    const float pixel_radius = 2 * std::sqrt(4 * kPi / (n * n));  // generous angular radius of a pixel
    const Vec3 normal = sun;                                      // a plane facing the sun pixel
    Sampler rng(9);
    RunningStat irr, cos_theta;
    for (int i = 0; i < 20000; ++i) {
        const LightLiSample s = light.sample_Li({0, 0, 0}, rng.next2(), kLambda);
        ASSERT_GT(s.pdf, 0);
        ASSERT_LT(std::acos(std::min(1.0f, dot(s.wi, sun))), pixel_radius);
        ASSERT_NEAR(s.pdf, float(n * n) / (4 * kPi), 1e-3f * s.pdf);
        const Rgb L = light.Le_rgb(s.wi);
        ASSERT_EQ(L, Rgb(3.0f));
        irr.add(L.g * std::max(0.0f, dot(s.wi, normal)) / s.pdf);
        cos_theta.add(dot(s.wi, normal));
    }
    // E = L x solid angle x mean cos over the pixel.
    expect_mean(irr, 3.0 * 4 * M_PI / (n * n) * cos_theta.mean(), "irradiance from the pixel");
    EXPECT_GT(cos_theta.mean(), 0.98);
    // The opposite direction is dark.
    EXPECT_EQ(light.Le_rgb(-sun), Rgb(0.0f));
    EXPECT_EQ(light.pdf_direction(-sun), 0.0f);
    SpectralStat weight;
    for (int i = 0; i < 20000; ++i) {
        const LightLeSample s = light.sample_Le(rng.next2(), rng.next2(), kLambda);
        ASSERT_LT(std::acos(std::min(1.0f, dot(-s.ray.dir, sun))), pixel_radius);
        weight.add(s.weight);
    }
    expect_means(weight, texel_spectrum(Rgb(3.0f), kLambda) * float(4 * kPi / (n * n) * kPi * 4), "power");
    EXPECT_NEAR(light.power().g, 3 * 4 * kPi / (n * n) * kPi * 4, 1e-4);
}

TEST(InfiniteLightEqualArea, NonSquareMapIsAnInputError) {
    std::vector<scene::Texture> textures = {image_texture(4, 2, std::vector<Rgb>(8, Rgb(1.0f)))};
    scene::Light rec;
    rec.kind = scene::Light::Kind::Infinite;
    rec.texture = 0;
    rec.equal_area = true;
    EXPECT_THROW(InfiniteLight(rec, textures, kSphere), InputError);
}

// Goniometric: the map's pixel in light space gives the intensity, power 4 pi I mean, photons
// distributed by the map with weights averaging to the power.
TEST(GoniometricLight, IntensityFollowsTheMap) {
    constexpr int n = 16;
    std::vector<Rgb> texels = varied_map(n);
    std::vector<scene::Texture> textures = {image_texture(n, n, texels)};
    scene::Light rec;
    rec.kind = scene::Light::Kind::Goniometric;
    rec.texture = 0;
    rec.color = Rgb(2.0f);
    const Transform to_world = Transform::translate({1, 2, 3}) * Transform::rotate(35, {1, 0, 1});
    rec.to_world = to_world;
    const GoniometricLight light(rec, textures);
    EXPECT_TRUE(light.is_delta());
    double mean = 0;
    for (const Rgb& c : texels) mean += c.average();
    mean /= n * n;
    EXPECT_NEAR(light.power().r, 2 * 4 * M_PI * mean, 1e-4 * 2 * 4 * M_PI * mean);
    Sampler rng(21);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 ref = Vec3(1, 2, 3) + warp::uniform_sphere(rng.next2()) * 2.0f;
        const LightLiSample s = light.sample_Li(ref, rng.next2(), kLambda);
        ASSERT_EQ(s.pdf, 1.0f);
        ASSERT_NEAR(s.distance, 2.0f, 1e-4f);
        const Vec3 local = normalize(to_world.inverse().vector(-s.wi));
        const Vec2 uv = equal_area_sphere_to_square(local);
        const Rgb c = texels[size_t(std::min(int(uv.y * n), n - 1) * n + std::min(int(uv.x * n), n - 1))];
        const Spectrum expected = spectral::illuminant(Rgb(2.0f), kLambda) * (c.average() / 4.0f);
        ASSERT_TRUE(spectral::spectra_near(s.L, expected, 1e-4)) << i;
    }
    SpectralStat weight;
    RunningStat pdf_check;
    for (int i = 0; i < 40000; ++i) {
        const LightLeSample s = light.sample_Le(rng.next2(), rng.next2(), kLambda);
        ASSERT_GT(s.pdf_dir, 0);
        float pp = 0, pd = 0;
        light.pdf_Le(s.n, s.ray.dir, pp, pd);
        ASSERT_NEAR(pd, s.pdf_dir, 1e-5f * pd);
        ASSERT_NEAR(length(s.ray.origin - Vec3(1, 2, 3)), 0.0f, 1e-5f);
        weight.add(s.weight);
    }
    expect_means(weight, spectral::illuminant(Rgb(2.0f), kLambda) * float(4 * M_PI * mean), "photon weights");
    // pdf_Le integrates to 1 over the sphere (uniform directions: E[pdf / (1 / 4 pi)] = 1).
    for (int i = 0; i < 40000; ++i) {
        float pp = 0, pd = 0;
        light.pdf_Le({}, warp::uniform_sphere(rng.next2()), pp, pd);
        pdf_check.add(pd * 4 * M_PI);
    }
    expect_mean(pdf_check, 1.0, "integral of pdf_Le");
}

// Projection: a 4 x 2 slide (top row red, bottom row blue; right half twice as bright). In light
// space the light looks down +z; the top row lands on -y (the builder's flip makes it +y), the
// right columns on +x.
TEST(ProjectionLight, SlideOrientationPdfAndPower) {
    std::vector<Rgb> texels = {Rgb(1, 0, 0), Rgb(1, 0, 0), Rgb(2, 0, 0), Rgb(2, 0, 0),
                               Rgb(0, 0, 1), Rgb(0, 0, 1), Rgb(0, 0, 2), Rgb(0, 0, 2)};
    std::vector<scene::Texture> textures = {image_texture(4, 2, texels)};
    scene::Light rec;
    rec.kind = scene::Light::Kind::Projection;
    rec.texture = 0;
    rec.color = Rgb(3.0f);
    rec.fov = 60 * kPi / 180;
    const Transform rot = Transform::rotate(25, {0, 1, 0});
    rec.to_world = rot;
    const ProjectionLight light(rec, textures);
    auto world = [&](Vec3 local) { return normalize(rot.vector(local)); };
    EXPECT_EQ(light.intensity_rgb(world({0.5f, -0.2f, 1})), Rgb(6, 0, 0));   // top right
    EXPECT_EQ(light.intensity_rgb(world({-0.5f, -0.2f, 1})), Rgb(3, 0, 0));  // top left
    EXPECT_EQ(light.intensity_rgb(world({0.5f, 0.2f, 1})), Rgb(0, 0, 6));    // bottom right
    EXPECT_EQ(light.intensity_rgb(world({0, 0.2f, -1})), Rgb(0.0f));         // behind
    // The half-angle 30 degrees spans the shorter side (y); x reaches 2 tan(30) on the plane z = 1.
    const float t = std::tan(kPi / 6);
    EXPECT_GT(light.intensity_rgb(world({1.9f * t, 0.9f * t, 1})).r +
                  light.intensity_rgb(world({1.9f * t, 0.9f * t, 1})).b,
              0);
    EXPECT_EQ(light.intensity_rgb(world({2.1f * t, 0, 1})), Rgb(0.0f));
    EXPECT_EQ(light.intensity_rgb(world({0, 1.1f * t, 1})), Rgb(0.0f));
    // Flux by brute force: the intensity integrated over the sphere (uniform directions).
    Sampler rng(31);
    RunningStat flux_r, flux_b, pdf_integral;
    for (int i = 0; i < 200000; ++i) {
        const Vec3 w = warp::uniform_sphere(rng.next2());
        const Rgb I = light.intensity_rgb(w);
        flux_r.add(I.r * 4 * M_PI);
        flux_b.add(I.b * 4 * M_PI);
        float pp = 0, pd = 0;
        light.pdf_Le({}, w, pp, pd);
        pdf_integral.add(pd * 4 * M_PI);
    }
    expect_mean(pdf_integral, 1.0, "integral of pdf_Le");
    // power() is exact: the pixels' closed-form solid angles.
    EXPECT_NEAR(light.power().r, flux_r.mean(), test::kSigmas * flux_r.std_error());
    EXPECT_NEAR(light.power().b, flux_b.mean(), test::kSigmas * flux_b.std_error());
    // Photons: directions inside the slide, pdf as pdf_Le says, weights averaging to the flux.
    RunningStat weight_r, weight_b;
    const int N = 40000;
    for (int i = 0; i < N; ++i) {
        const Wavelengths li = spectral::stratified_lambda(i, N);
        const LightLeSample s = light.sample_Le(rng.next2(), rng.next2(), li);
        ASSERT_GT(s.pdf_dir, 0);
        float pp = 0, pd = 0;
        light.pdf_Le({}, s.ray.dir, pp, pd);
        ASSERT_NEAR(pd, s.pdf_dir, 1e-5f * pd);
        ASSERT_GT(light.intensity_rgb(s.ray.dir).max(), 0);
        const Rgb c = spectrum::to_srgb(s.weight, li);
        weight_r.add(c.r);
        weight_b.add(c.b);
    }
    // Through the film (the colour of the spectra), against the flux (3% for the spectral round
    // trip of saturated primaries).
    EXPECT_NEAR(weight_r.mean(), light.power().r, 0.03 * light.power().r);
    EXPECT_NEAR(weight_b.mean(), light.power().b, 0.03 * light.power().b);
}

// An image area light on a unit square mesh with uvs: radiance bilinear in the image at (u, 1 - v),
// flux pi A mean, photon weights averaging to it, sample_Li's radiance the image at the point.
TEST(AreaLightImage, RadianceFollowsTheImageOverUv) {
    // 2 x 2 image: top row (v near 1 after the flip) 1 and 2, bottom row 3 and 4 (grey).
    std::vector<scene::Texture> textures = {
        image_texture(2, 2, {Rgb(1.0f), Rgb(2.0f), Rgb(3.0f), Rgb(4.0f)})};
    scene::Shape quad;
    quad.kind = scene::Shape::Kind::Mesh;
    // The square [0,1]^2 at z = 0 facing +z, uv = (x, y).
    quad.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    quad.mesh.indices = {0, 1, 2, 0, 2, 3};
    scene::Light rec;
    rec.kind = scene::Light::Kind::Area;
    rec.shape = 0;
    rec.texture = 0;
    rec.color = Rgb(2.0f);
    const AreaLight light(rec, quad, &textures);
    // Pixel centres: (0.25, 0.25) is the bottom-left pixel (3), (0.75, 0.75) the top-right (2).
    EXPECT_EQ(light.radiance_rgb({0.25f, 0.25f}), Rgb(6.0f));
    EXPECT_EQ(light.radiance_rgb({0.75f, 0.75f}), Rgb(4.0f));
    EXPECT_EQ(light.radiance_rgb({0.25f, 0.75f}), Rgb(2.0f));
    EXPECT_NEAR(light.radiance_rgb({0.5f, 0.5f}).g, 2 * 2.5f, 1e-5f);  // the bilinear middle
    EXPECT_EQ(light.radiance_rgb({0.0f, 1.0f}), Rgb(2.0f));            // clamped corner
    EXPECT_NEAR(light.power().g, kPi * 1 * 2 * 2.5f, 1e-4f);
    // sample_Li: the radiance at the sampled point is the image at that point's uv = (x, y).
    Sampler rng(41);
    for (int i = 0; i < 2000; ++i) {
        const LightLiSample s = light.sample_Li({0.3f, 0.6f, 2}, rng.next2(), kLambda);
        ASSERT_GT(s.pdf, 0);
        const Rgb c = light.radiance_rgb({s.p_light.x, s.p_light.y});
        ASSERT_TRUE(spectral::spectra_near(s.L, texel_spectrum(c, kLambda), 1e-4));
        ASSERT_TRUE(spectral::spectra_near(
            light.surface_Le({0, 0, 1}, {s.p_light.x, s.p_light.y}, -s.wi, kLambda), s.L, 1e-6));
    }
    // The back does not emit.
    EXPECT_EQ(light.surface_Le({0, 0, 1}, {0.5f, 0.5f}, {0, 0, -1}, kLambda), Spectrum(0.0f));
    RunningStat weight;
    const int N = 40000;
    for (int i = 0; i < N; ++i) {
        const Wavelengths li = spectral::stratified_lambda(i, N);
        const LightLeSample s = light.sample_Le(rng.next2(), rng.next2(), li);
        weight.add(spectrum::to_srgb(s.weight, li).g);
    }
    // Through the film: a grey image's flux pi A 2 x 2.5 (1e-2 for the spectral round trip).
    EXPECT_NEAR(weight.mean(), light.power().g, test::kSigmas * weight.std_error() + 1e-2 * light.power().g);
    // A box has no (u, v) for an image (the loader has no boxes).
    EXPECT_THROW(AreaLight(rec, phos::testing::box({0, 0, 0}, {1, 1, 1}), &textures), InputError);
}

// An image on a disk, a sphere and a capped cylinder: the radiance sample_Li and sample_Le give at a
// sampled point is the image at the (u, v) a ray hitting that point gets from the accel layer.
TEST(AreaLightImage, AnalyticShapesUseTheirHitsUv) {
    std::vector<Rgb> texels;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
            texels.push_back(Rgb(1.0f + float(x), 0.5f + float(y), x < 4 ? 3.0f : 0.2f));
    const std::vector<scene::Texture> textures = {image_texture(8, 4, texels)};
    scene::Shape sphere = test::sphere({0.2f, 0.1f, 0}, 0.8f);
    sphere.pbrt_uv = true;
    sphere.axis = Vec3(0, 0, 1);
    for (const scene::Shape& shape :
         {test::disk({0, 0, 0}, normalize(Vec3(0.2f, 0.1f, 1)), 1, 0.3f), sphere,
          phos::testing::cylinder({0, 0, 0}, normalize(Vec3(0.3f, 1, 0.2f)), 0.5f, 1.2f, true)}) {
        SCOPED_TRACE(int(shape.kind));
        scene::Scene sc;
        sc.shapes.push_back(shape);
        sc.textures = textures;
        const accel::EmbreeScene es(sc);
        scene::Light rec;
        rec.kind = scene::Light::Kind::Area;
        rec.shape = 0;
        rec.texture = 0;
        rec.color = Rgb(1.5f);
        rec.two_sided = true;
        const AreaLight light(rec, sc.shapes[0], &sc.textures);
        Sampler rng(43);
        int checked = 0;
        for (int i = 0; i < 400; ++i) {
            const Vec3 ref(3 * (rng.next() - 0.5f), 3 * (rng.next() - 0.5f), 3);
            const LightLiSample s = light.sample_Li(ref, rng.next2(), kLambda);
            if (!(s.pdf > 0)) continue;
            accel::SurfaceHit h;
            if (!es.intersect({ref, s.wi}, h) || std::fabs(h.t - s.distance) > 1e-3f * s.distance) continue;
            ASSERT_TRUE(spectral::spectra_near(s.L, light.surface_Le(h.ng, h.uv, -s.wi, kLambda), 2e-3))
                << h.uv.x << " " << h.uv.y;
            ++checked;
        }
        EXPECT_GT(checked, 100);
        // Photons: the radiance at their start is the image at the point's hit uv, seen from along the ray.
        checked = 0;
        for (int i = 0; i < 400; ++i) {
            const LightLeSample s = light.sample_Le(rng.next2(), rng.next2(), kLambda);
            if (!(s.pdf_pos > 0)) continue;
            const Vec3 from = s.ray.origin + s.ray.dir * 5.0f;
            accel::SurfaceHit h;
            if (!es.intersect({from, -s.ray.dir}, h) || length(h.p - s.ray.origin) > 1e-3f) continue;
            ASSERT_TRUE(spectral::spectra_near(s.Le, light.surface_Le(h.ng, h.uv, s.ray.dir, kLambda), 2e-3))
                << h.uv.x << " " << h.uv.y;
            ++checked;
        }
        EXPECT_GT(checked, 100);
    }
}

TEST(ProjectionLight, MissingImageIsAnInputError) {
    scene::Light rec;
    rec.kind = scene::Light::Kind::Projection;
    EXPECT_THROW(ProjectionLight(rec, {}), InputError);
    scene::Light g;
    g.kind = scene::Light::Kind::Goniometric;
    EXPECT_THROW(GoniometricLight(g, {}), InputError);
}

}  // namespace
}  // namespace phos::shading
