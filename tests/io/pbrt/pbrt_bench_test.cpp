// Every bench scene in pbrt form loads with the camera, settings, lights, shapes and materials the
// bench README describes.
#include <gtest/gtest.h>

#include <cmath>

#include "io/pbrt/pbrt_loader.h"
#include "pbrt_test_util.h"
#include "support/bench_checks.h"

namespace phos::io {
namespace {

using scene::Light;
using scene::Shape;

const std::string kScenes = std::string(PHOS_SHARED_DIR) + "/bench/scenes/";

scene::Scene load_bench(const std::string& name) {
    const int before = log::warning_count();
    scene::Scene s = load_pbrt(kScenes + name + ".pbrt");
    // The bench files are plain pbrt-v4 that phos supports fully: the loader warns about nothing
    // (the bdpt integrator one of them asks for is phos's own bdpt).
    EXPECT_EQ(log::warning_count() - before, 0) << name;
    return s;
}

void expect_vec(Vec3 a, Vec3 b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

void check_camera(const scene::Scene& s, Vec3 eye, Vec3 target, float fov_deg) {
    ASSERT_TRUE(s.camera.has_value());
    const scene::Camera& c = *s.camera;
    EXPECT_EQ(c.projection, scene::Camera::Projection::Perspective);
    expect_vec(c.eye, eye);
    expect_vec(normalize(c.forward), normalize(target - eye));
    // up is orthogonal to forward and in the plane of forward and world +y
    EXPECT_NEAR(dot(normalize(c.up), normalize(c.forward)), 0.0f, 1e-5f);
    EXPECT_GT(normalize(c.up).y, 0.0f);
    EXPECT_NEAR(dot(cross(c.forward, Vec3(0, 1, 0)), c.up), 0.0f, 1e-5f);
    EXPECT_NEAR(c.fov, fov_deg * kPi / 180.0f, 1e-6f);
    // `Scale -1 1 1` makes image right = +x world = cross(forward, up): no mirroring
    EXPECT_FALSE(c.flip_x);
    EXPECT_GT(normalize(cross(c.forward, c.up)).x,
              0.9f * std::cos(std::atan2(target.z - eye.z, 1.0f)) - 1.0f);
    EXPECT_EQ(c.lens_radius, 0.0f);
}

void check_settings(const scene::Scene& s, int spp, const std::string& integrator) {
    EXPECT_EQ(s.settings.width, 256);
    EXPECT_EQ(s.settings.height, 256);
    EXPECT_EQ(s.settings.spp, spp);
    ASSERT_FALSE(s.settings.integrator_parameters.empty());
    const scene::IntegratorParameter& depth = s.settings.integrator_parameters[0];
    EXPECT_EQ(depth.name, "maxdepth");
    EXPECT_EQ(depth.values, std::vector<std::string>{"16"});
    EXPECT_EQ(s.settings.integrator, integrator);
}

using phos::testing::check_cornell_light;
using phos::testing::mesh_area;

// World-space centre and radius of sphere shapes.
std::vector<std::pair<Vec3, float>> spheres(const scene::Scene& s) {
    std::vector<std::pair<Vec3, float>> out;
    for (const Shape& sh : s.shapes)
        if (sh.kind == Shape::Kind::Sphere) out.push_back({sh.to_world.point(sh.center), sh.radius});
    return out;
}

TEST(PbrtBench, CornellDiffuse) {
    const scene::Scene s = load_bench("cornell-diffuse");
    check_camera(s, {0, 0.5f, 1.9f}, {0, 0.5f, 0}, 38.0f);
    check_settings(s, 1024, "path");
    check_cornell_light(s);
    EXPECT_TRUE(spheres(s).empty());
    size_t tris = 0;
    for (const Shape& sh : s.shapes) tris += sh.mesh.triangle_count();
    EXPECT_EQ(tris, 5u * 2u + 2u + 2u * 5u * 2u);  // 5 walls, light, 2 blocks x 5 quads
    // left wall red, right wall green
    bool red = false, green = false;
    for (const scene::Material& m : s.materials) {
        red |= m.diffuse == Rgb(0.63f, 0.065f, 0.05f);
        green |= m.diffuse == Rgb(0.14f, 0.45f, 0.091f);
    }
    EXPECT_TRUE(red && green);
}

TEST(PbrtBench, CornellGlassMirror) {
    const scene::Scene s = load_bench("cornell-glass-mirror");
    check_camera(s, {0, 0.5f, 1.9f}, {0, 0.5f, 0}, 38.0f);
    check_settings(s, 256, "bdpt");  // the file asks for bdpt
    check_cornell_light(s);
    const auto sp = spheres(s);
    ASSERT_EQ(sp.size(), 2u);
    expect_vec(sp[0].first, {-0.22f, 0.2f, -0.18f});
    EXPECT_FLOAT_EQ(sp[0].second, 0.2f);
    expect_vec(sp[1].first, {0.22f, 0.2f, 0.13f});
    EXPECT_FLOAT_EQ(sp[1].second, 0.2f);
    for (const Shape& sh : s.shapes) {
        if (sh.kind != Shape::Kind::Sphere) continue;
        const scene::Material& m = s.materials[size_t(sh.material)];
        if (sh.to_world.point(sh.center).x < 0) {  // mirror: reflectance form (eta 1, k from it)
            EXPECT_EQ(m.specular, Rgb(0.99f));
            EXPECT_FALSE(m.conductor);
            EXPECT_TRUE(m.conductor_from_reflectance);
            EXPECT_TRUE(m.microfacet);
            EXPECT_EQ(m.roughness_u, 0.0f);
            EXPECT_EQ(m.diffuse, Rgb(0.0f));
        } else {  // glass
            EXPECT_EQ(m.transmission, Rgb(1.0f));
            EXPECT_FLOAT_EQ(m.ior, 1.5f);
            EXPECT_TRUE(m.microfacet);
            EXPECT_EQ(m.roughness_u, 0.0f);
            EXPECT_FALSE(m.thin);
        }
    }
}

TEST(PbrtBench, CausticPoint) {
    const scene::Scene s = load_bench("caustic-point");
    check_camera(s, {0.6f, 3.0f, 3.2f}, {-0.45f, 0.25f, 0}, 36.0f);
    check_settings(s, 1024, "bdpt");  // the file asks for bdpt
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].kind, Light::Kind::Point);
    EXPECT_EQ(s.lights[0].color, Rgb(100.0f));
    expect_vec(s.lights[0].position, {3.830222f, 3.713938f, 0});
    const auto sp = spheres(s);
    ASSERT_EQ(sp.size(), 1u);
    expect_vec(sp[0].first, {0, 0.5f, 0});
    EXPECT_FLOAT_EQ(sp[0].second, 0.5f);
    // floor: 20 x 20, facing +y
    const Shape& floor = s.shapes[0];
    ASSERT_EQ(floor.kind, Shape::Kind::Mesh);
    EXPECT_NEAR(mesh_area(floor.mesh), 400.0f, 1e-3f);
    EXPECT_EQ(s.materials[size_t(floor.material)].diffuse, Rgb(0.8f));
}

}  // namespace
}  // namespace phos::io
