// --layers for path, whitted, photonmap, bdpt and vcm: the component layers sum to the image, the image is
// the same bytes with or without them, and each component holds what its definition says
// (path_radiance.h): checked on closed boxes with and without mirrors and glass.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/log.h"
#include "core/stats.h"
#include "film/film.h"
#include "integrators/registry.h"
#include "render/prepared.h"
#include "support/shapes.h"

namespace phos::integrators {
namespace {

using testing::quad;

// A closed 2 x 2 x 2 box (inside [-1, 1] x [0, 2] x [-1, 1]) of white diffuse walls lit by a
// square area light under the ceiling, the camera inside near the front wall. With `specular`, a
// mirror sphere and a glass sphere stand on the floor.
scene::Scene box(bool specular, bool light = true) {
    scene::Scene s;
    scene::Material white, mirror, glass, black;
    white.diffuse = Rgb(0.7f, 0.6f, 0.5f);
    mirror.specular = Rgb(0.95f);
    mirror.shininess = scene::Material::kMirrorShininess;
    glass.transmission = Rgb(1.0f);
    glass.ior = 1.5f;
    glass.transmission_shininess = scene::Material::kMirrorShininess;
    s.materials = {white, mirror, glass, black};
    const auto wall = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
        scene::Shape q = quad(a, b, c, d);
        q.material = 0;
        s.shapes.push_back(q);
    };
    // Counter-clockwise seen from inside.
    wall({-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});    // floor
    wall({-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1});    // ceiling
    wall({-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1});  // back
    wall({-1, 0, 1}, {-1, 2, 1}, {1, 2, 1}, {1, 0, 1});      // front
    wall({-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1}, {-1, 0, 1});  // left
    wall({1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1});      // right
    if (specular) {
        s.shapes.push_back(testing::sphere({-0.45f, 0.4f, -0.3f}, 0.4f, 1));
        s.shapes.push_back(testing::sphere({0.45f, 0.4f, 0.2f}, 0.4f, 2));
    }
    if (light) {
        scene::Shape l =
            quad({-0.3f, 1.99f, -0.3f}, {0.3f, 1.99f, -0.3f}, {0.3f, 1.99f, 0.3f}, {-0.3f, 1.99f, 0.3f});
        l.material = 3;
        s.add_area_light(l, Rgb(10.0f));
    }
    scene::Camera cam;
    cam.eye = Vec3(0, 1, 0.95f);
    cam.forward = Vec3(0, -0.15f, -1);
    cam.up = Vec3(0, 1, 0);
    cam.fov = 1.4f;
    s.camera = cam;
    return s;
}

struct Result {
    Image image;
    std::map<std::string, Image> layers;
    std::string stats;
};

Result render(const std::string& integrator, const scene::Scene& s, bool layers, int spp = 4,
              int max_depth = 16, int size = 16) {
    RenderOptions opt;
    opt.width = opt.height = size;
    opt.spp = spp;
    opt.max_depth = max_depth;
    opt.seed = 7;
    opt.layers = layers;
    Stats stats;
    Prepared P(s, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    Progress progress(false);
    IntegratorConfig config;
    config.photon_map.global.photons = 20000;
    config.photon_map.caustic.photons = 20000;
    make_integrator(integrator_kind(integrator), config)->render(P, film, progress);
    Result r{film.image(), {}, stats.report()};
    for (const std::string& name : film.layer_names()) r.layers[name] = film.find_layer(name)->image();
    return r;
}

double mean(const Image& img) {
    double sum = 0;
    for (const Rgb& p : img.pixels) sum += double(p.r) + double(p.g) + double(p.b);
    return sum / (3.0 * double(img.pixels.size()));
}

bool is_black(const Image& img) {
    for (const Rgb& p : img.pixels)
        if (!p.is_black()) return false;
    return true;
}

// The layers sum to the image (float rounding only) and the image is the same bytes as without
// layers.
void expect_sums_to_image(const std::string& integrator, const Result& with, const Result& without,
                          const std::vector<std::string>& names) {
    ASSERT_EQ(with.layers.size(), names.size()) << integrator;
    for (const std::string& n : names) ASSERT_TRUE(with.layers.count(n)) << integrator << " " << n;
    EXPECT_TRUE(without.layers.empty()) << integrator;
    ASSERT_EQ(with.image.pixels.size(), without.image.pixels.size());
    for (size_t i = 0; i < with.image.pixels.size(); ++i) {
        const Rgb a = with.image.pixels[i], b = without.image.pixels[i];
        ASSERT_TRUE(a.r == b.r && a.g == b.g && a.b == b.b) << integrator << " pixel " << i;
        Rgb sum(0.0f);
        for (const std::string& n : names) sum += with.layers.at(n).pixels[i];
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(sum[c], a[c], 1e-5f * std::max(1.0f, a[c])) << integrator << " pixel " << i;
    }
}

const std::vector<std::string> kFour = {"caustic", "direct", "indirect", "specular"};

TEST(Layers, SumToTheUnchangedImage) {
    const scene::Scene s = box(true);
    expect_sums_to_image("path", render("path", s, true), render("path", s, false), kFour);
    expect_sums_to_image("photonmap", render("photonmap", s, true), render("photonmap", s, false), kFour);
    expect_sums_to_image("whitted", render("whitted", s, true), render("whitted", s, false),
                         {"direct", "specular"});
}

TEST(Layers, PathOneBounceIsAllDirect) {
    // max_depth 1: emission seen, light sampled at the first surface and the emission its BSDF
    // sample finds; nothing else. Every contribution is direct, in the same order as the image's.
    const Result r = render("path", box(false), true, 4, 1);
    EXPECT_GT(mean(r.image), 0.0);
    EXPECT_EQ(r.layers.at("direct").pixels, r.image.pixels);
    EXPECT_TRUE(is_black(r.layers.at("caustic")));
    EXPECT_TRUE(is_black(r.layers.at("indirect")));
    EXPECT_TRUE(is_black(r.layers.at("specular")));
}

TEST(Layers, PathWithoutDeltaSurfacesHasNoCausticOrSpecular) {
    const Result r = render("path", box(false), true);
    EXPECT_GT(mean(r.layers.at("direct")), 0.0);
    EXPECT_GT(mean(r.layers.at("indirect")), 0.0);
    EXPECT_TRUE(is_black(r.layers.at("caustic")));
    EXPECT_TRUE(is_black(r.layers.at("specular")));
    const Result w = render("whitted", box(false), true);
    EXPECT_TRUE(is_black(w.layers.at("specular")));
    EXPECT_EQ(w.layers.at("direct").pixels, w.image.pixels);
}

TEST(Layers, ComponentsMeanTheSameInEveryIntegrator) {
    // The same split estimated three ways: path (unbiased), whitted (direct by light sampling of
    // every light) and the photon map (photon estimates for caustics and indirect light).
    const scene::Scene s = box(true);
    const Result path = render("path", s, true, 256);
    const Result whitted = render("whitted", s, true, 64);
    // 64 samples: the photon map's image is 2.6 % dark here (its converged mean, kernel bias at
    // 20,000 photons); at 16 samples the pixel and gather noise adds about +-1 %.
    const Result pm = render("photonmap", s, true, 64);
    const double d = mean(path.layers.at("direct"));
    std::printf("direct: path %.4f whitted %.4f photonmap %.4f\n", d, mean(whitted.layers.at("direct")),
                mean(pm.layers.at("direct")));
    std::printf("caustic: path %.4f photonmap %.4f\n", mean(path.layers.at("caustic")),
                mean(pm.layers.at("caustic")));
    std::printf("indirect: path %.4f photonmap %.4f\n", mean(path.layers.at("indirect")),
                mean(pm.layers.at("indirect")));
    std::printf("specular: path %.4f photonmap %.4f\n", mean(path.layers.at("specular")),
                mean(pm.layers.at("specular")));
    std::printf("image: path %.4f photonmap %.4f\n", mean(path.image), mean(pm.image));
    EXPECT_NEAR(mean(whitted.layers.at("direct")), d, 0.02 * d);
    EXPECT_NEAR(mean(pm.layers.at("direct")), d, 0.02 * d);
    // The photon map's caustic and indirect estimates are blurred and biased, so looser bounds;
    // light counted in the wrong component would still break them (caustic is 1.5 % of the image).
    for (const char* n : {"caustic", "indirect", "specular"}) {
        const double p = mean(path.layers.at(n));
        EXPECT_GT(p, 0.0) << n;
        EXPECT_NEAR(mean(pm.layers.at(n)), p, (n[0] == 'c' ? 0.3 : 0.12) * p) << n;
    }
    EXPECT_NEAR(mean(pm.image), mean(path.image), 0.03 * mean(path.image));
}

TEST(Layers, BidirectionalComponentsMatchPath) {
    // bdpt and vcm classify each strategy's contribution by the path it completes (light tracing
    // and merging by the light vertex's history): the same split as path's. Both unbiased here
    // except vcm's merging, so 5 % bounds on direct, indirect and specular (a component landing
    // in the wrong layer moves one of them by far more) and 15 % on the small caustic layer
    // (1.5 % of the image, noisy at these sample counts). 128 iterations: at 64 the specular layer
    // (caustics seen in the mirror sphere) strays by up to 6 % with some sample sequences; at 256
    // bdpt's is within 1 % of path's.
    const scene::Scene s = box(true);
    const Result path = render("path", s, true, 256);
    for (const char* name : {"bdpt", "vcm"}) {
        const Result r = render(name, s, true, 128);
        expect_sums_to_image(name, r, render(name, s, false, 128), kFour);
        for (const char* n : {"direct", "caustic", "indirect", "specular"}) {
            const double p = mean(path.layers.at(n)), b = mean(r.layers.at(n));
            std::printf("%s %s: %.4f (path %.4f)\n", name, n, b, p);
            EXPECT_NEAR(b, p, (n[0] == 'c' ? 0.15 : 0.05) * p) << name << " " << n;
        }
    }
}

TEST(Layers, PhotonMapWithoutLightsDoesNotBlameTheEmissionCap) {
    const int before = log::warning_count();
    const Result r = render("photonmap", box(false, false), false, 1);
    EXPECT_EQ(log::warning_count(), before);
    EXPECT_NE(r.stats.find("(no lights)"), std::string::npos) << r.stats;
    EXPECT_EQ(r.stats.find("emission cap"), std::string::npos) << r.stats;
}

}  // namespace
}  // namespace phos::integrators
