// The AOV pass (--aov albedo,normal,depth): exact albedo, normal and depth on scenes where they
// are known, albedo through a mirror and glass and of the sky, name validation, determinism.
#include "render/aov.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "core/error.h"
#include "core/stats.h"
#include "film/film.h"
#include "render/prepared.h"
#include "support/shapes.h"

namespace phos::render {
namespace {

// A quad of half-size h at depth z, facing +z (towards a camera on the +z side) or -z.
scene::Shape quad_at(float z, float h, bool facing_plus_z, int material) {
    scene::Shape q = facing_plus_z ? testing::quad({-h, -h, z}, {h, -h, z}, {h, h, z}, {-h, h, z})
                                   : testing::quad({-h, -h, z}, {-h, h, z}, {h, h, z}, {h, -h, z});
    q.material = material;
    return q;
}

scene::Camera camera(Vec3 eye, Vec3 forward) {
    scene::Camera cam;
    cam.eye = eye;
    cam.forward = forward;
    cam.up = Vec3(0, 1, 0);
    cam.fov = 0.6f;
    return cam;
}

struct Aovs {
    Image albedo, normal, depth;
};

Aovs render(const scene::Scene& s, std::vector<std::string> names = {"albedo", "normal", "depth"},
            int spp = 4) {
    RenderOptions opt;
    opt.width = 12;
    opt.height = 10;
    opt.spp = spp;
    opt.seed = 5;
    opt.aovs = names;
    Stats stats;
    Prepared P(s, opt, {}, stats);
    film::Film film(opt.width, opt.height);
    render_aovs(P, film);
    Aovs a;
    if (const film::Layer* l = film.find_layer("albedo")) a.albedo = l->image();
    if (const film::Layer* l = film.find_layer("normal")) a.normal = l->image();
    if (const film::Layer* l = film.find_layer("depth")) a.depth = l->image();
    return a;
}

scene::Material diffuse(Rgb kd) {
    scene::Material m;
    m.diffuse = kd;
    return m;
}

TEST(Aov, PlaneFacingTheCamera) {
    const Rgb kd(0.7f, 0.35f, 0.1f);
    scene::Scene s;
    s.materials = {diffuse(kd)};
    s.shapes = {quad_at(-3.0f, 100, true, 0)};
    s.camera = camera({0.1f, -0.2f, 2.0f}, {0, 0, -1});
    const Aovs a = render(s);
    ASSERT_EQ(a.albedo.pixels.size(), 120u);
    for (size_t i = 0; i < a.albedo.pixels.size(); ++i) {
        EXPECT_EQ(a.albedo.pixels[i], kd) << i;
        EXPECT_NEAR(a.normal.pixels[i].r, 0.0f, 1e-6f);
        EXPECT_NEAR(a.normal.pixels[i].g, 0.0f, 1e-6f);
        EXPECT_NEAR(a.normal.pixels[i].b, 1.0f, 1e-6f);
        EXPECT_GT(a.depth.pixels[i].r, 5.0f);  // 5 on the axis, more towards the edges
    }
    // The plane seen from behind: the normal still faces the camera.
    s.shapes = {quad_at(-3.0f, 100, false, 0)};
    const Aovs back = render(s, {"normal"});
    for (const Rgb& n : back.normal.pixels) EXPECT_NEAR(n.b, 1.0f, 1e-6f);
}

TEST(Aov, DepthIsTheDistanceAlongTheCameraRay) {
    // The camera inside a sphere centred on it: every camera ray travels exactly the radius.
    scene::Scene s;
    s.materials = {diffuse(Rgb(0.5f))};
    s.shapes = {testing::sphere({1, 2, 3}, 2.5f, 0)};
    s.camera = camera({1, 2, 3}, {0.3f, -0.2f, -1});
    const Aovs a = render(s);
    for (const Rgb& d : a.depth.pixels) {
        EXPECT_NEAR(d.r, 2.5f, 1e-4f);
        EXPECT_EQ(d.g, d.r);
    }
    // The normal faces the camera: inwards, towards the centre; per sample along -ray, so the
    // pixel mean is a little shorter than 1 but points back at the eye.
    for (const Rgb& n : a.normal.pixels) EXPECT_LT(n.r * 0.3f - n.g * 0.2f - n.b, -0.9f);
}

TEST(Aov, NothingHitGivesZeroNormalAndDepthAndTheSkyAlbedo) {
    scene::Scene s;
    s.materials = {diffuse(Rgb(0.5f))};
    s.shapes = {quad_at(-3.0f, 0.01f, true, 0)};  // a speck, missed by almost every ray
    s.background = Rgb(0.25f, 0.5f, 4.0f);
    s.camera = camera({5, 0, 2}, {0, 0, -1});
    const Aovs a = render(s);
    for (size_t i = 0; i < a.albedo.pixels.size(); ++i) {
        EXPECT_EQ(a.albedo.pixels[i], Rgb(0.25f, 0.5f, 1.0f)) << i;  // clamped to [0, 1]
        EXPECT_EQ(a.normal.pixels[i], Rgb(0.0f)) << i;
        EXPECT_EQ(a.depth.pixels[i], Rgb(0.0f)) << i;
    }
}

TEST(Aov, AlbedoFollowsMirrorsAndGlass) {
    // Camera at the origin looking at a mirror (ks 0.8) at z = -1; behind the camera a wall of
    // kd 0.5 facing it. Through thin glass (kt 1) instead, the same wall on both sides.
    scene::Material mirror;
    mirror.specular = Rgb(0.8f);
    mirror.shininess = scene::Material::kMirrorShininess;
    scene::Material glass;
    glass.transmission = Rgb(1.0f);
    glass.thin = true;
    glass.ior = 1.5f;
    for (const scene::Material& front : {mirror, glass}) {
        scene::Scene s;
        s.materials = {front, diffuse(Rgb(0.5f, 0.25f, 1.0f))};
        s.shapes = {quad_at(-1, 100, true, 0), quad_at(1, 100, false, 1), quad_at(-3, 100, true, 1)};
        s.camera = camera({0, 0, 0}, {0, 0, -1});
        const Aovs a = render(s);
        const float k = front.thin ? 1.0f : 0.8f;
        for (const Rgb& p : a.albedo.pixels) {
            EXPECT_NEAR(p.r, 0.5f * k, 1e-6f);
            EXPECT_NEAR(p.g, 0.25f * k, 1e-6f);
            EXPECT_NEAR(p.b, 1.0f * k, 1e-6f);
        }
        // Normal and depth are the first hit's: the mirror or glass itself.
        for (const Rgb& n : a.normal.pixels) EXPECT_NEAR(n.b, 1.0f, 1e-6f);
        for (const Rgb& d : a.depth.pixels) EXPECT_LT(d.r, 1.1f);
    }
    // A diffuse surface under a mirror coat: kd plus ks times what the mirror shows (black here:
    // the camera looks out of the scene in the reflection).
    scene::Material coated = diffuse(Rgb(0.3f));
    coated.specular = Rgb(0.5f);
    coated.shininess = scene::Material::kMirrorShininess;
    scene::Scene s;
    s.materials = {coated};
    s.shapes = {quad_at(-1, 100, true, 0)};
    s.camera = camera({0, 0, 0}, {0, 0, -1});
    for (const Rgb& p : render(s, {"albedo"}).albedo.pixels) EXPECT_NEAR(p.r, 0.3f, 1e-6f);
    s.background = Rgb(1.0f);
    for (const Rgb& p : render(s, {"albedo"}).albedo.pixels) EXPECT_NEAR(p.r, 0.8f, 1e-6f);
}

TEST(Aov, OnlyTheRequestedLayersAndValidNames) {
    scene::Scene s;
    s.materials = {diffuse(Rgb(0.5f))};
    s.shapes = {quad_at(-3.0f, 100, true, 0)};
    s.camera = camera({0, 0, 2}, {0, 0, -1});
    const Aovs a = render(s, {"depth"});
    EXPECT_TRUE(a.albedo.pixels.empty());
    EXPECT_TRUE(a.normal.pixels.empty());
    EXPECT_FALSE(a.depth.pixels.empty());
    try {
        render(s, {"albedo", "colour"});
        ADD_FAILURE() << "no error for an unknown AOV";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "unknown auxiliary image 'colour' (known: albedo, normal, depth)");
    }
}

TEST(Aov, SameBytesAtAnyThreadCount) {
    scene::Material glass;
    glass.transmission = Rgb(1.0f);
    glass.ior = 1.5f;
    scene::Scene s;
    s.materials = {diffuse(Rgb(0.6f, 0.5f, 0.4f)), glass};
    s.shapes = {quad_at(-3.0f, 100, true, 0), testing::sphere({0, 0, -1}, 0.8f, 1)};
    s.camera = camera({0, 0, 2}, {0, 0, -1});
    Aovs one, two;
    tbb::task_arena(1).execute([&] { one = render(s, {"albedo", "normal", "depth"}, 9); });
    tbb::task_arena(2).execute([&] { two = render(s, {"albedo", "normal", "depth"}, 9); });
    EXPECT_EQ(one.albedo.pixels, two.albedo.pixels);
    EXPECT_EQ(one.normal.pixels, two.normal.pixels);
    EXPECT_EQ(one.depth.pixels, two.depth.pixels);
}

}  // namespace
}  // namespace phos::render
