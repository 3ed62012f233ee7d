// Loads the three benchmark scenes in ../shared/bench/scn and checks their content against what
// the files (and ../shared/bench/scenes/README.md) describe.
#include <gtest/gtest.h>

#include <cmath>

#include "core/log.h"
#include "io/scn/scn_loader.h"
#include "support/bench_checks.h"

namespace phos::io {
namespace {

using scene::Light;
using scene::Shape;

std::string bench(const std::string& name) { return std::string(PHOS_SHARED_DIR) + "/bench/scn/" + name; }

size_t triangles(const scene::Scene& s) {
    size_t n = 0;
    for (const auto& sh : s.shapes)
        if (sh.kind == Shape::Kind::Mesh && sh.area_light < 0) n += sh.mesh.triangle_count();
    return n;
}

using phos::testing::check_cornell_light;

void check_cornell_camera(const scene::Scene& s) {
    ASSERT_TRUE(s.camera);
    EXPECT_EQ(s.camera->eye, Vec3(0, 0.5f, 1.9f));
    EXPECT_NEAR(s.camera->fov, 2 * 0.331613f, 1e-6f);
}

TEST(ScnBench, CornellDiffuse) {
    log::set_quiet(true);
    const auto s = load_scn(bench("cornell-diffuse.scn"));
    check_cornell_camera(s);
    EXPECT_EQ(triangles(s), 30u);
    EXPECT_EQ(s.shapes.size(), 1u + 1u + 1u + 1u + 1u);  // runs by material: 0, 1, 2, 0 + the light
    ASSERT_GE(s.materials.size(), 3u);
    EXPECT_EQ(s.materials[1].diffuse, Rgb(0.63f, 0.065f, 0.05f));
    check_cornell_light(s);
}

TEST(ScnBench, CornellGlassMirror) {
    log::set_quiet(true);
    const auto s = load_scn(bench("cornell-glass-mirror.scn"));
    check_cornell_camera(s);
    EXPECT_EQ(triangles(s), 10u);
    int spheres = 0;
    for (const auto& sh : s.shapes)
        if (sh.kind == Shape::Kind::Sphere) {
            ++spheres;
            EXPECT_FLOAT_EQ(sh.radius, 0.2f);
        }
    EXPECT_EQ(spheres, 2);
    EXPECT_EQ(s.materials[3].specular, Rgb(0.99f));
    EXPECT_GE(s.materials[3].shininess, scene::Material::kMirrorShininess);
    EXPECT_EQ(s.materials[4].transmission, Rgb(1));
    EXPECT_FLOAT_EQ(s.materials[4].ior, 1.5f);
    check_cornell_light(s);
}

TEST(ScnBench, CausticPoint) {
    log::set_quiet(true);
    const auto s = load_scn(bench("caustic-point.scn"));
    ASSERT_TRUE(s.camera);
    EXPECT_NEAR(s.camera->fov, 2 * 0.314159f, 1e-6f);
    EXPECT_EQ(triangles(s), 2u);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].kind, Light::Kind::Point);
    EXPECT_EQ(s.lights[0].color, Rgb(100));
    EXPECT_NEAR(s.lights[0].position.x, 3.830222f, 1e-6f);
    EXPECT_NEAR(s.lights[0].position.y, 3.713938f, 1e-6f);
    EXPECT_EQ(s.lights[0].attenuation, Vec3(0, 0, 1));
    ASSERT_EQ(s.shapes.size(), 2u);
    EXPECT_EQ(s.shapes[1].kind, Shape::Kind::Sphere);
    EXPECT_EQ(s.shapes[1].center, Vec3(0, 0.5f, 0));
    EXPECT_EQ(s.materials[size_t(s.shapes[1].material)].transmission, Rgb(1));
}

}  // namespace
}  // namespace phos::io
