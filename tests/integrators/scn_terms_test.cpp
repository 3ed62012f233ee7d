// The .scn surface terms (glow `e` and, with --ambient, ka x ambient) are seen by camera rays and
// by rays after mirror / glass bounces, in every integrator alike, and never by rays that sampled a
// diffuse lobe. Scenes without lights, so nothing else contributes.
#include <gtest/gtest.h>

#include "core/stats.h"
#include "film/film.h"
#include "integrators/registry.h"
#include "render/prepared.h"
#include "support/shapes.h"

namespace phos::integrators {
namespace {

// A quad of half-size `h` at depth z facing `facing_z` (+1 or -1).
scene::Shape quad_at(float z, float h, float facing_z, int material) {
    scene::Shape q = facing_z > 0 ? testing::quad({-h, -h, z}, {h, -h, z}, {h, h, z}, {-h, h, z})
                                  : testing::quad({-h, -h, z}, {-h, h, z}, {h, h, z}, {h, -h, z});
    q.material = material;
    return q;
}

// The camera at the origin looks down -z at `front` (a quad at z = -1); behind the camera, at
// z = +1, a large wall that shows ka = 0.5 and glow e = 0.25 to whoever sees it.
scene::Scene scene_with_front(const scene::Material& front) {
    scene::Scene s;
    scene::Material wall;
    wall.ambient = Rgb(0.5f);
    wall.emission = Rgb(0.25f);
    s.materials = {front, wall};
    s.shapes = {quad_at(-1, 100, +1, 0), quad_at(+1, 100, -1, 1)};
    s.ambient = Rgb(1.0f, 0.5f, 0.25f);
    scene::Camera cam;
    cam.eye = Vec3(0.0f);
    cam.forward = Vec3(0, 0, -1);
    cam.up = Vec3(0, 1, 0);
    cam.fov = 0.5f;
    s.camera = cam;
    return s;
}

Rgb mean_pixel(const std::string& integrator, const scene::Scene& s, bool ambient) {
    RenderOptions opt;
    opt.width = opt.height = 8;
    opt.spp = 2;
    opt.ambient = ambient;
    Stats stats;
    Prepared P(s, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    Progress progress(false);
    IntegratorConfig config;
    config.photon_map.global.photons = 100;
    config.photon_map.caustic.photons = 100;
    config.progressive.photons_per_iter = 100;
    make_integrator(integrator_kind(integrator), config)->render(P, film, progress);
    Rgb sum(0.0f);
    const Image img = film.image();
    for (const Rgb& p : img.pixels) sum += p;
    return sum * (1.0f / float(img.pixels.size()));
}

const char* const kIntegrators[] = {"whitted", "path", "photonmap", "ppm", "sppm"};

TEST(ScnTerms, SeenThroughAMirror) {
    scene::Material mirror;
    mirror.specular = Rgb(1.0f);
    mirror.shininess = scene::Material::kMirrorShininess;
    const scene::Scene s = scene_with_front(mirror);
    for (const char* name : kIntegrators) {
        // glow + ka x ambient of the wall seen in the mirror (the mirror's own terms are zero)
        const Rgb with = mean_pixel(name, s, true), without = mean_pixel(name, s, false);
        EXPECT_NEAR(with.r, 0.25f + 0.5f, 1e-5f) << name;
        EXPECT_NEAR(with.g, 0.25f + 0.25f, 1e-5f) << name;
        EXPECT_NEAR(with.b, 0.25f + 0.125f, 1e-5f) << name;
        EXPECT_NEAR(without.r, 0.25f, 1e-5f) << name;
        EXPECT_NEAR(without.b, 0.25f, 1e-5f) << name;
    }
}

TEST(ScnTerms, SeenThroughGlass) {
    // Thin glass, kt = 1: every sample either reflects or passes; the far side of the glass is the
    // wall at z = -3 below (the camera's view beyond the glass), the reflection the wall behind.
    scene::Material glass;
    glass.transmission = Rgb(1.0f);
    glass.thin = true;
    glass.ior = 1.5f;
    scene::Scene s = scene_with_front(glass);
    s.shapes.push_back(quad_at(-3, 100, +1, 1));
    for (const char* name : kIntegrators) {
        const Rgb with = mean_pixel(name, s, true);
        EXPECT_NEAR(with.r, 0.75f, 1e-5f) << name;
        EXPECT_NEAR(with.b, 0.375f, 1e-5f) << name;
    }
}

TEST(ScnTerms, NotSeenAfterADiffuseBounce) {
    // A diffuse front surface: the wall's terms must not come back through it (no lights, so the
    // image is the front's own terms, here zero).
    scene::Material diffuse;
    diffuse.diffuse = Rgb(0.8f);
    const scene::Scene s = scene_with_front(diffuse);
    for (const char* name : kIntegrators) {
        const Rgb with = mean_pixel(name, s, true);
        EXPECT_EQ(with.r, 0.0f) << name;
        EXPECT_EQ(with.g, 0.0f) << name;
    }
    // ...while its own terms are seen directly.
    scene::Material lit = diffuse;
    lit.ambient = Rgb(0.4f);
    lit.emission = Rgb(0.1f);
    for (const char* name : kIntegrators) {
        const Rgb with = mean_pixel(name, scene_with_front(lit), true);
        EXPECT_NEAR(with.r, 0.4f + 0.1f, 1e-5f) << name;
        EXPECT_NEAR(with.b, 0.1f + 0.1f, 1e-5f) << name;
    }
}

TEST(ScnTerms, NotSeenThroughAMirrorAfterADiffuseBounce) {
    // The front glows and is diffuse; behind the camera a mirror shows it to itself. Path tracing
    // reaches the glow again by diffuse-then-mirror paths: the glow is "not a light", so they must
    // add nothing and every integrator sees just the front's own terms.
    scene::Material lit;
    lit.diffuse = Rgb(0.8f);
    lit.ambient = Rgb(0.4f);
    lit.emission = Rgb(0.1f);
    scene::Scene s = scene_with_front(lit);
    s.materials[1] = scene::Material{};
    s.materials[1].specular = Rgb(1.0f);
    s.materials[1].shininess = scene::Material::kMirrorShininess;
    for (const char* name : kIntegrators) {
        const Rgb with = mean_pixel(name, s, true);
        EXPECT_NEAR(with.r, 0.4f + 0.1f, 1e-5f) << name;
        EXPECT_NEAR(with.b, 0.1f + 0.1f, 1e-5f) << name;
    }
}

}  // namespace
}  // namespace phos::integrators
