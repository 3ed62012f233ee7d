// Loads the three benchmark scenes in ../shared/bench/scn and checks their content against what
// the files (and ../shared/bench/scenes/README.md) describe.
#include <gtest/gtest.h>

#include <cmath>

#include "core/log.h"
#include "io/scn/scn_loader.h"

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

float mesh_area(const scene::TriangleMesh& m) {
    float a = 0;
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        const Vec3 p0 = m.positions[m.indices[3 * t]], p1 = m.positions[m.indices[3 * t + 1]],
                   p2 = m.positions[m.indices[3 * t + 2]];
        a += 0.5f * length(cross(p1 - p0, p2 - p0));
    }
    return a;
}

void check_cornell_light(const scene::Scene& s) {
    ASSERT_EQ(s.lights.size(), 1u);
    const Light& l = s.lights[0];
    EXPECT_EQ(l.kind, Light::Kind::Area);
    EXPECT_EQ(l.color, Rgb(15));
    const Shape& e = s.shapes[size_t(l.shape)];
    EXPECT_EQ(e.area_light, 0);
    EXPECT_NEAR(mesh_area(e.mesh), 0.05f, 1e-6f);
    const auto& m = e.mesh;
    const Vec3 n = cross(m.positions[m.indices[1]] - m.positions[m.indices[0]],
                         m.positions[m.indices[2]] - m.positions[m.indices[0]]);
    EXPECT_LT(n.y, 0);  // faces down into the box
    for (Vec3 p : m.positions) EXPECT_FLOAT_EQ(p.y, 0.998f);
    EXPECT_TRUE(s.materials[size_t(e.material)].diffuse.is_black());
}

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
