// Rendering participating media end to end, on scenes built by hand (tests/integrators/
// media_test.cpp has the emitting-sphere furnace; these add independent checks):
//  - a furnace made of a closed box whose walls bound the medium the natural way (outward normals,
//    MediumInterface inside = the fog), where every pixel converges to Le / (1 - rho);
//  - single scattering from a point light in a homogeneous (chromatic) medium against quadrature of
//    its line integral, for `path` (free flights + next-event estimation, max depth 1) and
//    `photonmap` (equiangular sampling, --no-indirect --no-caustic);
//  - photonmap and sppm against a converged `path` on a fog box lit by a point light and on a glass
//    sphere in fog under an area light;
//  - bit-identical images at 1 and 2 threads on a scene with fog, glass and a point light (volume
//    caustic map and projection maps included);
//  - photonmap's beam radiance estimate against ray marching (paired by seed) and path, in
//    homogeneous and grid fog, and bit-identical at 1 and 2 threads with either estimator;
//  - the CLI on a pbrt scene with MakeNamedMedium: no "loaded but not rendered" note, and the fog
//    changes the image.
// Statistical tolerances are 5 standard errors of the image mean, measured from the pixels where
// every pixel has the same expectation (furnace, single scattering) and otherwise from renders
// with different seeds, plus a stated allowance where an estimator is consistent but biased.
// Runtime: ~60 s on 2 cores (Release), most of it in the photon-methods-vs-path comparisons and
// the beam-vs-march ones.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/stats.h"
#include "film/film.h"
#include "integrators/registry.h"
#include "io/image/image_io.h"
#include "render/prepared.h"
#include "spectrum/color.h"
#include "spectrum/rgb_spectrum.h"
#include "support/shapes.h"
#include "test_util.h"

namespace phos::integrators {
namespace {

struct MeanAndError {
    double mean, std_error;
};

// Mean over the pixels of channel c (c < 0: the channel average) and its standard error, treating
// the pixels as independent estimates.
MeanAndError image_mean(const Image& img, int c = -1) {
    double sum = 0, sum2 = 0;
    const double n = double(img.pixels.size());
    for (const Rgb& p : img.pixels) {
        const double v = c < 0 ? p.average() : p[c];
        sum += v;
        sum2 += v * v;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

struct RenderSetup {
    int size = 16;
    int spp = 16;
    int max_depth = 100;
    uint64_t seed = 7;
};

Image render(const std::string& name, const scene::Scene& s, const RenderSetup& setup,
             const IntegratorConfig& config = {}) {
    RenderOptions opt;
    opt.width = opt.height = setup.size;
    opt.spp = setup.spp;
    opt.max_depth = setup.max_depth;
    opt.seed = setup.seed;
    Stats stats;
    Prepared prepared(s, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    Progress progress(false);
    make_integrator(integrator_kind(name), config)->render(prepared, film, progress);
    EXPECT_EQ(film.main().rejected(), 0u) << name << ": NaN or infinite samples";
    return film.image();
}

scene::Medium homogeneous(Rgb sigma_a, Rgb sigma_s, float g) {
    scene::Medium m;
    m.name = "fog";
    m.sigma_a = sigma_a;
    m.sigma_s = sigma_s;
    m.g = g;
    return m;
}

// ---------------------------------------------------------------------------------------------
// a. Furnace: a closed box [-1, 1]^3 with outward normals, diffuse reflectance rho, emitting
// radiance Le on both sides (so also towards the inside), its inside (opposite the normal) filled
// with fog; the camera sits inside, in the fog. Without absorption the radiance field is uniform:
// L = Le + rho L at the walls, and scattering without absorption leaves a uniform field unchanged,
// so every pixel converges to Le / (1 - rho).

scene::Scene fog_furnace_box(float rho, float Le, Rgb sigma_a, Rgb sigma_s, float g) {
    scene::Scene s;
    scene::Material wall;
    wall.diffuse = Rgb(rho);
    s.materials.push_back(wall);
    s.media.push_back(homogeneous(sigma_a, sigma_s, g));
    scene::Shape box = testing::box(Vec3(-1.0f), Vec3(1.0f));
    box.material = 0;
    box.media = {0, -1};  // inside = the fog, outside = vacuum
    const int light = s.add_area_light(box, Rgb(Le), /*two_sided=*/true);
    s.lights[size_t(light)].medium = 0;  // photons start inside (both sides emit; the outer ones escape)
    scene::Camera cam;
    cam.eye = Vec3(0.2f, -0.1f, 0.3f);
    cam.forward = Vec3(0.3f, -0.2f, -1.0f);
    cam.fov = 1.4f;
    s.camera = cam;
    s.camera_medium = 0;
    return s;
}

TEST(MediaRender, FurnaceBoxPathConvergesToTheClosedForm) {
    const scene::Scene s = fog_furnace_box(0.5f, 1.0f, Rgb(0.0f), Rgb(2.0f), 0.5f);
    RenderSetup setup;
    setup.spp = 64;
    const Image img = render("path", s, setup);
    const MeanAndError m = image_mean(img);
    std::printf("[ measured ] furnace box, path 16x16x64: %.4f +- %.4f (expected 2)\n", m.mean, m.std_error);
    // Every pixel has the same expectation, so the pixels' spread measures the error of their
    // mean: 5 standard errors plus 0.25 % for float accumulation along long paths.
    EXPECT_NEAR(m.mean, 2.0, 5 * m.std_error + 0.005);
    EXPECT_LT(m.std_error, 0.02);  // the test has power: a 5 % error would be seen
    // Every channel too (a grey scene, but a channel mix-up in the tracking weights would show).
    for (int c = 0; c < 3; ++c) {
        const MeanAndError mc = image_mean(img, c);
        EXPECT_NEAR(mc.mean, 2.0, 5 * mc.std_error + 0.005) << "channel " << c;
    }
}

TEST(MediaRender, FurnaceBoxBidirectionalConvergeToTheClosedForm) {
    // bdpt and vcm: vertices in the fog, connections through it (transmittance), light tracing
    // from fog and walls onto the film; vcm merges on the walls only (docs/bidirectional.md).
    // Tolerance as for path, plus 1 % for vcm's merging kernel (consistent, not unbiased).
    const scene::Scene s = fog_furnace_box(0.5f, 1.0f, Rgb(0.0f), Rgb(2.0f), 0.5f);
    RenderSetup setup;
    setup.spp = 32;
    for (const char* name : {"bdpt", "vcm"}) {
        const MeanAndError m = image_mean(render(name, s, setup));
        std::printf("[ measured ] furnace box, %s 16x16x32: %.4f +- %.4f (expected 2)\n", name, m.mean,
                    m.std_error);
        EXPECT_NEAR(m.mean, 2.0, 5 * m.std_error + 0.005 + (std::string(name) == "vcm" ? 0.02 : 0.0)) << name;
        EXPECT_LT(m.std_error, 0.03) << name << ": the test has power";
    }
}

TEST(MediaRender, FurnaceBoxAbsorptionDarkens) {
    // Half of sigma_t absorbs. Bounds: the image is below the non-absorbing 2 by far more than its
    // noise, and above what the walls alone give through the fog without any in-scattering or
    // inter-reflection: Le exp(-sigma_t * the largest distance to a wall seen, sqrt(12) ~ 3.5).
    const scene::Scene s = fog_furnace_box(0.5f, 1.0f, Rgb(0.5f), Rgb(0.5f), 0.0f);
    RenderSetup setup;
    setup.spp = 16;
    const MeanAndError m = image_mean(render("path", s, setup));
    std::printf("[ measured ] absorbing furnace box, path: %.4f +- %.4f\n", m.mean, m.std_error);
    EXPECT_LT(m.mean + 5 * m.std_error, 1.5);
    EXPECT_GT(m.mean, std::exp(-1.0 * std::sqrt(12.0)));
}

// ---------------------------------------------------------------------------------------------
// b. Single scattering from a point light. The fog fills an invisible sphere of radius R around
// the camera (a medium interface, inside = fog); an orthographic camera with a tiny aperture shoots
// near-parallel rays from the origin along +x; a point light of intensity I sits at distance h
// from the ray. The radiance of a ray is
//   L = int_0^R exp(-sigma_t t) sigma_s p(cos theta(t)) I exp(-sigma_t r(t)) / r(t)^2 dt,
// r(t) = |light - x(t)|, theta the angle between the ray direction and the direction to the light.

constexpr float kSphereR = 30.0f;
const Vec3 kLight(2.0f, 1.0f, 0.0f);  // h = 1 from the ray, foot of the perpendicular at t = 2
const Rgb kIntensity(4.0f, 3.0f, 2.0f);
const Rgb kSigmaA(0.05f, 0.1f, 0.2f), kSigmaS(0.3f, 0.2f, 0.5f);
constexpr float kG = 0.4f;

scene::Scene single_scattering_scene() {
    scene::Scene s;
    scene::Material boundary;
    boundary.interface_only = true;
    s.materials.push_back(boundary);
    s.media.push_back(homogeneous(kSigmaA, kSigmaS, kG));
    scene::Shape sphere = testing::sphere(Vec3(0.0f), kSphereR, 0);
    sphere.media = {0, -1};  // inside = fog
    s.shapes.push_back(sphere);
    scene::Light light;
    light.kind = scene::Light::Kind::Point;
    light.position = kLight;
    light.color = kIntensity;
    light.medium = 0;
    s.lights.push_back(light);
    scene::Camera cam;
    cam.projection = scene::Camera::Projection::Orthographic;
    cam.ortho_half_size = 1e-4f;  // ray offsets <= 1.5e-4: relative change of L ~ 1e-8 (even)
    cam.eye = Vec3(0.0f);
    cam.forward = Vec3(1, 0, 0);
    s.camera = cam;
    s.camera_medium = 0;
    return s;
}

// The integral above at each wavelength, by composite Simpson in double on [0, R] (2e4 intervals;
// the integrand is smooth with a peak of width ~h = 1: error far below 1e-6 relative), with the
// coefficients and the intensity as the renderer reads their RGB (unbounded spectra, an illuminant),
// taken to linear sRGB through the colour-matching functions at 1 nm. Channel c of that colour.
double single_scattering_reference(int c) {
    using spectrum::RgbSpectrum;
    static const Vec3 rgb = [] {
        const RgbSpectrum sa(kSigmaA, RgbSpectrum::Use::Unbounded), ss(kSigmaS, RgbSpectrum::Use::Unbounded);
        const RgbSpectrum I(kIntensity, RgbSpectrum::Use::Illuminant);
        const auto at = [&](double lambda) {
            const double sigma_s = ss(float(lambda)), st = sa(float(lambda)) + sigma_s;
            const int n = 20000;
            const double dt = double(kSphereR) / n;
            double acc = 0;
            for (int i = 0; i <= n; ++i) {
                const double t = i * dt;
                const double lx = kLight.x - t, ly = kLight.y, lz = kLight.z;
                const double r = std::sqrt(lx * lx + ly * ly + lz * lz);
                const double cos_theta = lx / r;  // the ray runs along +x
                const double g = kG;
                const double phase = (1 - g * g) / (4 * M_PI * std::pow(1 + g * g - 2 * g * cos_theta, 1.5));
                const double f = std::exp(-st * t) * sigma_s * phase * std::exp(-st * r) / (r * r);
                acc += f * ((i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2));
            }
            return acc * dt / 3 * I(float(lambda));
        };
        return spectrum::apply(spectrum::xyz_to_srgb(), spectrum::integrate_xyz(at));
    }();
    return rgb[c];
}

TEST(MediaRender, SingleScatteringPathMatchesQuadrature) {
    const scene::Scene s = single_scattering_scene();
    RenderSetup setup;
    setup.size = 8;
    setup.spp = 2048;
    setup.max_depth = 1;  // one scattering event: single scattering only
    const Image img = render("path", s, setup);
    for (int c = 0; c < 3; ++c) {
        const double expected = single_scattering_reference(c);
        const MeanAndError m = image_mean(img, c);
        std::printf("[ measured ] single scattering, path, channel %d: %.5f +- %.5f (quadrature %.5f)\n", c,
                    m.mean, m.std_error, expected);
        EXPECT_NEAR(m.mean, expected, 5 * m.std_error + 1e-5 * expected) << "channel " << c;
        EXPECT_LT(m.std_error, 0.01 * expected) << "channel " << c << ": the test has power";
    }
}

TEST(MediaRender, SingleScatteringPhotonMapMatchesQuadrature) {
    // The photon map's camera rays integrate single scattering over each stretch by equiangular
    // sampling towards the point light; with indirect light and caustics off that is all they add.
    const scene::Scene s = single_scattering_scene();
    RenderSetup setup;
    setup.size = 8;
    setup.spp = 2048;
    IntegratorConfig config;
    config.photon_map.indirect_light = false;
    config.photon_map.caustics = false;
    const Image img = render("photonmap", s, setup, config);
    for (int c = 0; c < 3; ++c) {
        const double expected = single_scattering_reference(c);
        const MeanAndError m = image_mean(img, c);
        std::printf("[ measured ] single scattering, photonmap, channel %d: %.5f +- %.5f (quadrature %.5f)\n",
                    c, m.mean, m.std_error, expected);
        EXPECT_NEAR(m.mean, expected, 5 * m.std_error + 1e-5 * expected) << "channel " << c;
        EXPECT_LT(m.std_error, 0.01 * expected) << "channel " << c << ": the test has power";
    }
}

// ---------------------------------------------------------------------------------------------
// c. Photon mapping against path tracing.

// A closed box [-1, 1]^3 seen from inside (walls: inward normals, diffuse, red left and green right
// walls), filled with fog (walls are no medium transition: the camera and the lights are in it).
scene::Scene fog_box(bool glass_sphere, bool area_light) {
    scene::Scene s;
    scene::Material white, red, green, glass;
    white.diffuse = Rgb(0.6f);
    red.diffuse = Rgb(0.6f, 0.1f, 0.1f);
    green.diffuse = Rgb(0.1f, 0.6f, 0.1f);
    glass.transmission = Rgb(1.0f);
    glass.ior = 1.5f;
    s.materials = {white, red, green, glass};
    s.media.push_back(homogeneous(Rgb(0.05f), Rgb(0.5f), 0.3f));
    const float a = 1.0f;
    // Each wall's vertex order is flipped where needed so that its normal points into the box.
    auto wall = [&](Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, int material) {
        if (dot(cross(p1 - p0, p2 - p0), -p0) < 0) std::swap(p1, p3);
        scene::Shape q = testing::quad(p0, p1, p2, p3);
        q.material = material;
        s.shapes.push_back(q);
    };
    wall({-a, -a, -a}, {a, -a, -a}, {a, -a, a}, {-a, -a, a}, 0);  // floor
    wall({-a, a, -a}, {-a, a, a}, {a, a, a}, {a, a, -a}, 0);      // ceiling
    wall({-a, -a, -a}, {-a, a, -a}, {a, a, -a}, {a, -a, -a}, 0);  // back
    wall({-a, -a, a}, {a, -a, a}, {a, a, a}, {-a, a, a}, 0);      // front (behind the camera)
    wall({-a, -a, -a}, {-a, -a, a}, {-a, a, a}, {-a, a, -a}, 1);  // left (red)
    wall({a, -a, -a}, {a, a, -a}, {a, a, a}, {a, -a, a}, 2);      // right (green)
    if (glass_sphere) {
        scene::Shape sphere = testing::sphere(Vec3(0.0f, -0.45f, -0.1f), 0.4f, 3);
        sphere.media = {-1, 0};  // clear glass inside, fog outside
        s.shapes.push_back(sphere);
    }
    if (area_light) {
        scene::Shape disk = testing::disk(Vec3(0.0f, 0.98f, -0.1f), Vec3(0, -1, 0), 0.35f);
        disk.material = 0;
        const int light = s.add_area_light(disk, Rgb(6.0f));
        s.lights[size_t(light)].medium = 0;
    } else {
        scene::Light light;
        light.kind = scene::Light::Kind::Point;
        light.position = Vec3(0.1f, 0.6f, -0.2f);
        light.color = Rgb(2.0f);
        light.medium = 0;
        s.lights.push_back(light);
    }
    scene::Camera cam;
    cam.eye = Vec3(0.0f, 0.0f, 0.95f);
    cam.forward = Vec3(0, 0, -1);
    cam.fov = 1.3f;
    s.camera = cam;
    s.camera_medium = 0;
    return s;
}

IntegratorConfig photon_budgets() {
    IntegratorConfig c;
    c.photon_map.global.photons = 100000;
    c.photon_map.volume.photons = 100000;
    c.photon_map.caustic.photons = 50000;
    c.photon_map.volume_caustic.photons = 50000;
    c.photon_map.gather_rays = 8;
    c.progressive.photons_per_iter = 50000;
    // A fixed initial radius (volume points start 4x wider: 0.16). The automatic one is a few
    // pixel footprints, and at 16 x 16 pixels a footprint is 0.1 scene units here: volume balls
    // of radius ~1 in a box of side 2 lose the part outside the medium (boundary bias, measured
    // 6 % low on both scenes below at 32 iterations; within 1 % with this radius).
    c.progressive.radius = 0.04f;
    return c;
}

// The image mean of `name` averaged over `runs` renders with different seeds, and its standard
// error from their spread (photon noise is correlated across pixels, so the pixels' spread would
// not measure it).
MeanAndError mean_over_seeds(const std::string& name, const scene::Scene& s, int spp, int runs,
                             const IntegratorConfig& config = {}) {
    double sum = 0, sum2 = 0;
    for (int k = 0; k < runs; ++k) {
        RenderSetup setup;
        setup.spp = spp;
        setup.seed = 100 + uint64_t(k);
        const double m = image_mean(render(name, s, setup, config)).mean;
        sum += m;
        sum2 += m * m;
    }
    const double mean = sum / runs;
    return {mean, std::sqrt(std::max(0.0, (sum2 / runs - mean * mean) / (runs - 1)))};
}

// photonmap and sppm against path. Tolerance: 3 % of the reference for the photon methods' kernel
// bias (they are consistent; with these budgets and radii the offsets measured -1.5 % and +1.4 %
// for photonmap, -0.6 % and -0.1 % for sppm on the two scenes, each within 2 of its standard
// errors), plus 5 combined standard errors of the means compared, measured over the seeds (6 runs
// each, so 5 "standard errors" is a t-value with 5 degrees of freedom, exceeded with probability
// 0.4 %).
void expect_photon_methods_agree_with_path(const char* label, const scene::Scene& s, int path_spp) {
    const MeanAndError path = mean_over_seeds("path", s, path_spp, 6);
    const MeanAndError pm = mean_over_seeds("photonmap", s, 8, 6, photon_budgets());
    const MeanAndError sppm = mean_over_seeds("sppm", s, 32, 6, photon_budgets());
    std::printf(
        "[ measured ] %s: path %.4f +- %.4f, photonmap %.4f +- %.4f (%+.1f %%), sppm %.4f +- %.4f (%+.1f "
        "%%)\n",
        label, path.mean, path.std_error, pm.mean, pm.std_error, 100 * (pm.mean / path.mean - 1), sppm.mean,
        sppm.std_error, 100 * (sppm.mean / path.mean - 1));
    EXPECT_LT(path.std_error, 0.01 * path.mean) << label << ": the reference is converged enough";
    for (const auto& [name, m] : {std::pair{"photonmap", pm}, std::pair{"sppm", sppm}}) {
        EXPECT_LT(m.std_error, 0.02 * path.mean) << label << ", " << name << ": the test has power";
        const double tol = 0.03 * path.mean + 5 * std::hypot(m.std_error, path.std_error);
        EXPECT_NEAR(m.mean, path.mean, tol) << label << ", " << name;
    }
}

TEST(MediaRender, PhotonMethodsAgreeWithPathInAFogBoxWithAPointLight) {
    // path's single scattering near a point light has heavy tails (free-flight distances with
    // next-event estimation, 1/r^2, and four wavelengths per sample): 6 x 320 samples per pixel
    // keep its error under 1 %.
    expect_photon_methods_agree_with_path("fog box, point light", fog_box(false, false), 320);
}

// bdpt (unbiased: 5 combined standard errors over the seeds, plus 0.5 % for float accumulation)
// and vcm (its merging is consistent: 3 % as for the photon methods) against path.
void expect_bidirectional_agree_with_path(const char* label, const scene::Scene& s, int path_spp) {
    const MeanAndError path = mean_over_seeds("path", s, path_spp, 6);
    IntegratorConfig config;
    config.progressive.radius = 0.04f;  // as photon_budgets(): at 16 x 16 pixels the automatic one is wide
    for (const char* name : {"bdpt", "vcm"}) {
        const MeanAndError m = mean_over_seeds(name, s, 64, 6, config);
        std::printf("[ measured ] %s: path %.4f +- %.4f, %s %.6f +- %.4f (%+.2f %%)\n", label, path.mean,
                    path.std_error, name, m.mean, m.std_error, 100 * (m.mean / path.mean - 1));
        EXPECT_LT(m.std_error, 0.02 * path.mean) << label << ", " << name << ": the test has power";
        const double bias = std::string(name) == "vcm" ? 0.03 : 0.005;
        EXPECT_NEAR(m.mean, path.mean, bias * path.mean + 5 * std::hypot(m.std_error, path.std_error))
            << label << ", " << name;
    }
}

TEST(MediaRender, BidirectionalAgreeWithPathInFog) {
    // path converged further than for the photon methods (its heavy tails near the point light and
    // through the glass would otherwise dominate the comparison).
    expect_bidirectional_agree_with_path("fog box, point light", fog_box(false, false), 1024);
    expect_bidirectional_agree_with_path("glass sphere in fog, area light", fog_box(true, true), 256);
}

TEST(MediaRender, PhotonMethodsAgreeWithPathForAGlassSphereInFog) {
    // An area light (path tracing reaches its caustics by BSDF sampling) above a glass sphere in
    // fog: volume and surface caustics, refraction between clear glass and fog.
    expect_photon_methods_agree_with_path("glass sphere in fog, area light", fog_box(true, true), 64);
}

// ---------------------------------------------------------------------------------------------
// d. Determinism: the same image at 1 and 2 threads for every integrator that renders media, on
// a scene with fog, a glass sphere (volume caustic map, projection maps) and a point light.

// The volume cache (photon/volume_cache.h, on with --irradiance-cache) against the full k-nearest
// estimates at every gather ray that scatters in the fog: the same seed, so the two renders share
// their photons and paths and differ only there. Tolerance 1.5 %: the cache's first-order
// expansion of the phase function (g = 0.3 here) and its nearest-point lookup shift the
// secondary estimates by a fraction of their own share of the image.
TEST(MediaRender, VolumeCacheAgreesWithTheFullEstimates) {
    for (const bool glass : {false, true}) {
        const scene::Scene s = fog_box(glass, false);
        IntegratorConfig with = photon_budgets(), without = photon_budgets();
        without.photon_map.irradiance_cache = false;
        RenderSetup setup;
        setup.spp = 8;
        const double a = image_mean(render("photonmap", s, setup, with)).mean;
        const double b = image_mean(render("photonmap", s, setup, without)).mean;
        std::printf("[ measured ] volume cache %s: %.5f vs %.5f without (%+.2f %%)\n",
                    glass ? "glass" : "fog", a, b, 100 * (a / b - 1));
        EXPECT_NEAR(a, b, 0.015 * b) << (glass ? "glass sphere in fog" : "fog box");
    }
}

TEST(MediaRender, BitIdenticalAtOneAndTwoThreads) {
    const scene::Scene s = fog_box(true, false);
    IntegratorConfig config;
    config.photon_map.global.photons = 10000;
    config.photon_map.volume.photons = 10000;
    config.photon_map.caustic.photons = 5000;
    config.photon_map.volume_caustic.photons = 5000;
    config.photon_map.gather_rays = 4;
    config.progressive.photons_per_iter = 10000;
    RenderSetup setup;
    setup.size = 12;
    setup.spp = 2;
    setup.max_depth = 16;
    for (const char* name : {"path", "photonmap", "ppm", "sppm", "bdpt", "vcm"}) {
        Image a, b;
        tbb::task_arena(1).execute([&] { a = render(name, s, setup, config); });
        tbb::task_arena(2).execute([&] { b = render(name, s, setup, config); });
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        size_t differ = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] == b.pixels[i] ? 0 : 1;
        EXPECT_EQ(differ, 0u) << name << ": pixels that differ between 1 and 2 threads";
        EXPECT_GT(image_mean(a).mean, 0.0) << name << ": the image is not black";
    }
}

// An emissive, purely absorbing medium (sigma_a 20, so exp(-sigma_a d) < 1e-8 beyond the unit
// distance from the camera to the black walls) seen from inside: every pixel converges to its
// emitted radiance Le, int_0^d sigma_a Le exp(-sigma_a t) dt = Le (1 - exp(-sigma_a d)). The same
// for a homogeneous medium, a uniform grid of density 1 (emission follows sigma_a through the
// density) and a grid whose "Lescale" doubles it, in every integrator that renders media.
scene::Scene glowing_box(scene::Medium::Kind kind, float le_scale) {
    scene::Scene s;
    s.materials.push_back(scene::Material{});  // black walls
    scene::Medium m = homogeneous(Rgb(20.0f), Rgb(0.0f), 0.0f);
    m.emission = Rgb(0.7f, 0.5f, 0.3f);
    if (kind == scene::Medium::Kind::UniformGrid) {
        m.kind = kind;
        m.nx = m.ny = m.nz = 2;
        m.density.assign(8, 1.0f);
        m.p0 = Vec3(-1.0f);
        m.p1 = Vec3(1.0f);
        if (le_scale != 1.0f) m.emission_scale.assign(8, le_scale);
    }
    s.media.push_back(m);
    scene::Shape box = testing::box(Vec3(-1.0f), Vec3(1.0f));
    box.material = 0;
    box.media = {0, -1};
    s.shapes.push_back(box);
    scene::Light dark;  // a light outside, so that the integrators have one
    dark.color = Rgb(0.0f);
    dark.position = Vec3(5.0f);
    s.lights.push_back(dark);
    scene::Camera cam;
    cam.forward = Vec3(0.3f, -0.2f, -1.0f);
    cam.fov = 1.4f;
    s.camera = cam;
    s.camera_medium = 0;
    return s;
}

TEST(MediaRender, EmissionOfHomogeneousAndGridMedia) {
    using Kind = scene::Medium::Kind;
    struct Case {
        Kind kind;
        float le_scale;
    };
    for (const Case k :
         {Case{Kind::Homogeneous, 1}, Case{Kind::UniformGrid, 1}, Case{Kind::UniformGrid, 2}}) {
        const scene::Scene s = glowing_box(k.kind, k.le_scale);
        for (const char* name : {"path", "photonmap", "sppm"}) {
            RenderSetup setup;
            setup.spp = 8;
            const Image img = render(name, s, setup, photon_budgets());
            for (int c = 0; c < 3; ++c) {
                const double expected = double(s.media[0].emission[c]) * k.le_scale;
                const MeanAndError m = image_mean(img, c);
                // every pixel has the same expectation: 5 standard errors of the pixels' mean plus
                // 0.5 % for float accumulation
                EXPECT_NEAR(m.mean, expected, 5 * m.std_error + 0.005 * expected)
                    << name << ", kind " << int(k.kind) << ", Lescale " << k.le_scale << ", channel " << c;
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// f. The beam radiance estimate (photonmap --volume-estimate beam, photon/beam_estimate.h) against
// ray marching (--volume-estimate march) and path tracing. With one seed both estimators see the
// same photon maps and the same camera and gather samples (a stretch draws one number in either
// mode), so the per-seed difference beam - march measures the estimators' difference alone, with
// far less noise than either image.

// The fog box with its fog replaced by a uniform grid of the same coefficients at density
// 0.4 .. 1.6 (a smooth wave across the box), so camera rays take the grid transmittance table.
scene::Scene grid_fog_box(bool glass_sphere) {
    scene::Scene s = fog_box(glass_sphere, false);
    scene::Medium& m = s.media[0];
    m.kind = scene::Medium::Kind::UniformGrid;
    m.nx = m.ny = m.nz = 12;
    m.p0 = Vec3(-1.25f);  // the half cells at the border fade to 0: keep them outside the box
    m.p1 = Vec3(1.25f);
    for (int z = 0; z < 12; ++z)
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 12; ++x)
                m.density.push_back(1.0f + 0.6f * std::sin(0.9f * float(x) + 0.4f * float(y)) *
                                               std::cos(0.5f * float(z)));
    return s;
}

struct BeamAndMarch {
    MeanAndError beam, march, diff;  // image means over seeds; diff: beam - march, paired by seed
};

BeamAndMarch beam_and_march(const scene::Scene& s, int runs) {
    IntegratorConfig beam = photon_budgets(), march = photon_budgets();
    beam.photon_map.volume_estimate = VolumeEstimate::Beam;
    march.photon_map.volume_estimate = VolumeEstimate::March;
    double sum[3] = {}, sum2[3] = {};
    for (int k = 0; k < runs; ++k) {
        RenderSetup setup;
        setup.spp = 8;
        setup.seed = 100 + uint64_t(k);
        const double b = image_mean(render("photonmap", s, setup, beam)).mean;
        const double m = image_mean(render("photonmap", s, setup, march)).mean;
        const double v[3] = {b, m, b - m};
        for (int i = 0; i < 3; ++i) sum[i] += v[i], sum2[i] += v[i] * v[i];
    }
    MeanAndError out[3];
    for (int i = 0; i < 3; ++i) {
        const double mean = sum[i] / runs;
        out[i] = {mean, std::sqrt(std::max(0.0, (sum2[i] / runs - mean * mean) / (runs - 1)))};
    }
    return {out[0], out[1], out[2]};
}

// Tolerances. Against path: as in c., 3 % for the photon map's kernel bias plus 5 combined
// standard errors over 6 seeds. Beam against march: the two are consistent estimates of the same
// integral whose biases differ (march takes the k nearest photons around each step, a balloon
// estimate that in a uniform density is high by k / (k - 1), 1.7 % of the volume part at k = 60;
// the beam estimate's per-photon radii are unbiased there; near walls the two lose photons
// differently), so 2 % of the image plus 5 standard errors of the paired difference.
void expect_beam_agrees(const char* label, const scene::Scene& s, const MeanAndError* path, int runs = 6) {
    const BeamAndMarch r = beam_and_march(s, runs);
    std::printf(
        "[ measured ] %s: beam %.4f +- %.4f, march %.4f +- %.4f, beam - march %+.4f +- %.4f (%+.2f %%)\n",
        label, r.beam.mean, r.beam.std_error, r.march.mean, r.march.std_error, r.diff.mean, r.diff.std_error,
        100 * r.diff.mean / r.march.mean);
    EXPECT_NEAR(r.diff.mean, 0.0, 0.02 * r.march.mean + 5 * r.diff.std_error) << label << ": beam vs march";
    EXPECT_GT(r.beam.mean, 0.0) << label;
    if (path) {
        std::printf("[ measured ] %s: path %.4f +- %.4f, beam %+.1f %%\n", label, path->mean, path->std_error,
                    100 * (r.beam.mean / path->mean - 1));
        EXPECT_LT(r.beam.std_error, 0.02 * path->mean) << label << ": the test has power";
        EXPECT_NEAR(r.beam.mean, path->mean,
                    0.03 * path->mean + 5 * std::hypot(r.beam.std_error, path->std_error))
            << label << ": beam vs path";
    }
}

TEST(MediaRender, BeamEstimateAgreesWithPathAndMarchInAFogBox) {
    const scene::Scene s = fog_box(false, false);
    const MeanAndError path = mean_over_seeds("path", s, 256, 6);
    expect_beam_agrees("fog box, point light", s, &path);
}

TEST(MediaRender, BeamEstimateAgreesWithMarchInGridFogAndVolumeCaustics) {
    // Volume caustics (glass sphere, point light) in homogeneous fog, and the grid fog.
    expect_beam_agrees("glass sphere in fog, point light", fog_box(true, false), nullptr, 4);
    expect_beam_agrees("grid fog box, point light", grid_fog_box(false), nullptr, 4);
}

TEST(MediaRender, BeamAndMarchBitIdenticalAtOneAndTwoThreads) {
    IntegratorConfig config;
    config.photon_map.global.photons = 10000;
    config.photon_map.volume.photons = 10000;
    config.photon_map.caustic.photons = 5000;
    config.photon_map.volume_caustic.photons = 5000;
    config.photon_map.gather_rays = 4;
    RenderSetup setup;
    setup.size = 12;
    setup.spp = 2;
    setup.max_depth = 16;
    for (const bool grid : {false, true}) {
        const scene::Scene s = grid ? grid_fog_box(true) : fog_box(true, false);
        for (const VolumeEstimate e : {VolumeEstimate::Beam, VolumeEstimate::March}) {
            config.photon_map.volume_estimate = e;
            const char* label = e == VolumeEstimate::Beam ? "beam" : "march";
            Image a, b;
            tbb::task_arena(1).execute([&] { a = render("photonmap", s, setup, config); });
            tbb::task_arena(2).execute([&] { b = render("photonmap", s, setup, config); });
            ASSERT_EQ(a.pixels.size(), b.pixels.size());
            size_t differ = 0;
            for (size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] == b.pixels[i] ? 0 : 1;
            EXPECT_EQ(differ, 0u) << label << (grid ? ", grid" : "") << ": pixels that differ";
            EXPECT_GT(image_mean(a).mean, 0.0) << label;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// e. The CLI on a pbrt scene with a homogeneous medium (a fog-filled Cornell box closed by an
// invisible interface, as ../shared/bench/media/fog-caustic.pbrt, with thicker fog): media are
// rendered (no "loaded but not rendered" note) and change the image.

std::string pbrt_fog_box(bool fog) {
    std::string s =
        "Scale -1 1 1\n"
        "LookAt 0 0.5 1.9   0 0.5 0   0 1 0\n"
        "Camera \"perspective\" \"float fov\" [ 38 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\n"
        "WorldBegin\n";
    if (fog)
        s += "MakeNamedMedium \"fog\" \"string type\" [ \"homogeneous\" ]\n"
             "  \"rgb sigma_a\" [ 0.05 0.05 0.05 ] \"rgb sigma_s\" [ 1.5 1.5 1.5 ] \"float g\" [ 0.3 ]\n"
             "AttributeBegin\n"
             "  MediumInterface \"fog\" \"\"\n"
             "  Material \"interface\"\n"
             "  Shape \"trianglemesh\" \"point3 P\" [ -0.5 0 0.5 0.5 0 0.5 0.5 1 0.5 -0.5 1 0.5 ]\n"
             "    \"integer indices\" [ 0 1 2 0 2 3 ] \"normal N\" [ 0 0 1 0 0 1 0 0 1 0 0 1 ]\n"
             "AttributeEnd\n";
    s += "AttributeBegin\n"
         "  Material \"diffuse\" \"rgb reflectance\" [ 0.8 0.8 0.8 ]\n"
         "  Shape \"trianglemesh\" \"point3 P\" [ -0.5 0 -0.5 -0.5 0 0.5 0.5 0 0.5 0.5 0 -0.5 ]\n"
         "    \"integer indices\" [ 0 1 2 0 2 3 ]\n"
         "  Shape \"trianglemesh\" \"point3 P\" [ -0.5 1 -0.5 0.5 1 -0.5 0.5 1 0.5 -0.5 1 0.5 ]\n"
         "    \"integer indices\" [ 0 1 2 0 2 3 ]\n"
         "  Shape \"trianglemesh\" \"point3 P\" [ -0.5 0 -0.5 0.5 0 -0.5 0.5 1 -0.5 -0.5 1 -0.5 ]\n"
         "    \"integer indices\" [ 0 1 2 0 2 3 ]\n"
         "  Material \"diffuse\" \"rgb reflectance\" [ 0.63 0.065 0.05 ]\n"
         "  Shape \"trianglemesh\" \"point3 P\" [ -0.5 0 -0.5 -0.5 1 -0.5 -0.5 1 0.5 -0.5 0 0.5 ]\n"
         "    \"integer indices\" [ 0 1 2 0 2 3 ]\n"
         "  Material \"diffuse\" \"rgb reflectance\" [ 0.14 0.45 0.091 ]\n"
         "  Shape \"trianglemesh\" \"point3 P\" [ 0.5 0 -0.5 0.5 0 0.5 0.5 1 0.5 0.5 1 -0.5 ]\n"
         "    \"integer indices\" [ 0 1 2 0 2 3 ]\n"
         "AttributeEnd\n"
         "AttributeBegin\n";
    if (fog) s += "  MediumInterface \"\" \"fog\"\n";
    s += "  LightSource \"point\" \"point3 from\" [ 0 0.9 0 ] \"rgb I\" [ 0.5 0.5 0.5 ]\n"
         "AttributeEnd\n";
    return s;
}

TEST(MediaRender, PbrtSceneWithFogRendersMediaThroughTheCli) {
    if (!std::filesystem::exists(PHOS_BINARY))
        GTEST_SKIP() << "the phos binary is not built (" << PHOS_BINARY << "): build the `phos` target";
    testing::TempDir dir;
    ASSERT_TRUE(dir.ok());
    const std::string fog = dir.write("fog.pbrt", pbrt_fog_box(true));
    const std::string clear = dir.write("clear.pbrt", pbrt_fog_box(false));
    for (const char* integrator : {"path", "sppm"}) {
        // sppm with a fixed radius: the automatic one (pixel footprints) is very wide at 16 x 16
        // and biases this thick fog low (see the report).
        const std::string args =
            std::string(" --integrator ") + integrator +
            (std::string(integrator) == "path" ? " --spp 128"
                                               : " --spp 16 --photons-per-iter 20000 --radius 0.01") +
            " --threads 2 --no-progress -o ";
        const testing::CommandResult a = testing::run_phos("render " + fog + args + dir.file("fog.exr"));
        ASSERT_EQ(a.exit_code, 0) << a.output;
        EXPECT_EQ(a.output.find("not rendered"), std::string::npos) << a.output;
        EXPECT_EQ(a.output.find("treated as vacuum"), std::string::npos) << a.output;
        const testing::CommandResult b = testing::run_phos("render " + clear + args + dir.file("clear.exr"));
        ASSERT_EQ(b.exit_code, 0) << b.output;
        const MeanAndError with_fog = image_mean(io::read_image(dir.file("fog.exr")));
        const MeanAndError without = image_mean(io::read_image(dir.file("clear.exr")));
        std::printf("[ measured ] pbrt fog box, %s: with fog %.4f +- %.4f, without %.4f +- %.4f\n",
                    integrator, with_fog.mean, with_fog.std_error, without.mean, without.std_error);
        // sigma_t = 1.55 in a box of side 1: the fog dims the walls and glows around the point
        // light, brighter overall: converged (path 1024 spp, sppm 64 x 1e5 photons, radius 0.01)
        // 0.502 with fog against 0.404 without (+24 %). At these budgets the image mean of one run
        // varies by ~2 % (path) and ~1.5 % (sppm) over seeds, so +10 % is a margin of > 5 of them.
        EXPECT_GT(with_fog.mean, 1.1 * without.mean) << integrator;
    }
}

}  // namespace
}  // namespace phos::integrators
