// One test per .scn command: each loads a tiny scene written to a temp dir and checks the exact
// scene data it produces (camera, materials, shapes and transforms, lights, groups, includes).
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstdio>

#include "core/log.h"
#include "io/scn/scn_loader.h"
#include "scn_test_util.h"

namespace phos::io::test {
namespace {

using scene::Light;
using scene::Shape;

// Material 0 of most test files: a plain diffuse grey.
const std::string kMat = "material 0 0 0  0.5 0.5 0.5  0 0 0  0 0 0  0 0 0  10 1 0\n";

void expect_vec(Vec3 a, Vec3 b, float tol = 1e-6f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

class ScnCommand : public ::testing::Test {
protected:
    void SetUp() override { log::set_quiet(true); }
    scene::Scene load(const std::string& text, const ScnOptions& o = {}) {
        return load_scn(dir.write("main.scn", text), o);
    }
    TempDir dir;
};

TEST_F(ScnCommand, CameraStoresFullFovAndVectors) {
    const auto s = load("camera 1 2 3   0 0 -2   0 1 0   0.5   0.1 100\n");
    ASSERT_TRUE(s.camera.has_value());
    expect_vec(s.camera->eye, {1, 2, 3});
    expect_vec(s.camera->forward, {0, 0, -2});
    expect_vec(s.camera->up, {0, 1, 0});
    EXPECT_FLOAT_EQ(s.camera->fov, 1.0f);  // the file's half angle, doubled
    EXPECT_FLOAT_EQ(s.camera->near_clip, 0.1f);
    EXPECT_FLOAT_EQ(s.camera->far_clip, 100.0f);
}

TEST_F(ScnCommand, NoCameraLeavesItUnset) { EXPECT_FALSE(load(kMat + "sphere 0 0 0 0 1\n").camera); }

TEST_F(ScnCommand, MaterialFields) {
    const auto s = load("material 0.1 0.2 0.3  0.4 0.5 0.6  0.1 0.15 0.2  0.3 0.2 0.1  1 2 3  50 1.33 0\n");
    ASSERT_EQ(s.materials.size(), 1u);
    const auto& m = s.materials[0];
    EXPECT_EQ(m.ambient, Rgb(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(m.diffuse, Rgb(0.4f, 0.5f, 0.6f));
    EXPECT_EQ(m.specular, Rgb(0.1f, 0.15f, 0.2f));
    EXPECT_EQ(m.transmission, Rgb(0.3f, 0.2f, 0.1f));
    EXPECT_EQ(m.emission, Rgb(1, 2, 3));
    EXPECT_FLOAT_EQ(m.shininess, 50);
    EXPECT_FLOAT_EQ(m.transmission_shininess, 50);
    EXPECT_FLOAT_EQ(m.ior, 1.33f);
    EXPECT_EQ(m.diffuse_texture, -1);
}

TEST_F(ScnCommand, OverbrightMaterialIsScaledByDefaultOrKeptRaw) {
    const std::string text = "material 0 0 0  0.8 0.2 0.2  0.5 0.2 0.2  0 0 0  0 0 0  10 1 0\n";
    // By default (what the seed's -real did): scaled, one warning naming the factors (plus one for
    // the default lights this light-less scene gets).
    const int before = log::warning_count();
    auto s = load(text);
    EXPECT_EQ(log::warning_count() - before, 2);
    const auto& m = s.materials[0];
    EXPECT_NEAR(m.diffuse.r, 0.8f / 1.3f, 1e-6f);
    EXPECT_NEAR(m.specular.r, 0.5f / 1.3f, 1e-6f);
    EXPECT_NEAR(m.diffuse.r + m.specular.r + m.transmission.r, 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(m.diffuse.g, 0.2f);  // channels with sum <= 1 are untouched
    EXPECT_FLOAT_EQ(m.specular.g, 0.2f);

    // --raw-materials: kept as written, still one warning.
    ScnOptions raw;
    raw.raw_materials = true;
    const int before_raw = log::warning_count();
    s = load(text, raw);
    EXPECT_EQ(log::warning_count() - before_raw, 2);
    EXPECT_EQ(s.materials[0].diffuse, Rgb(0.8f, 0.2f, 0.2f));
}

TEST_F(ScnCommand, TriBecomesAOneTriangleMesh) {
    const auto s = load(kMat + "tri 0   0 0 0   1 0 0   0 1 0\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    const Shape& sh = s.shapes[0];
    EXPECT_EQ(sh.kind, Shape::Kind::Mesh);
    EXPECT_EQ(sh.material, 0);
    ASSERT_EQ(sh.mesh.triangle_count(), 1u);
    expect_vec(sh.mesh.positions[sh.mesh.indices[0]], {0, 0, 0});
    expect_vec(sh.mesh.positions[sh.mesh.indices[1]], {1, 0, 0});
    expect_vec(sh.mesh.positions[sh.mesh.indices[2]], {0, 1, 0});
    EXPECT_EQ(sh.origin, dir.file("main.scn") + ":2");
    EXPECT_TRUE(sh.to_world.is_identity());
}

TEST_F(ScnCommand, ConsecutiveTrisWithTheSameMaterialMerge) {
    const auto s = load(kMat + kMat +
                        "tri 0  0 0 0  1 0 0  0 1 0\n"
                        "tri 0  0 0 1  1 0 1  0 1 1\n"
                        "tri 0  0 0 2  1 0 2  0 1 2\n"
                        "tri 1  0 0 3  1 0 3  0 1 3\n"
                        "sphere 0  0 0 0  1\n"
                        "tri 1  0 0 4  1 0 4  0 1 4\n");
    ASSERT_EQ(s.shapes.size(), 4u);
    EXPECT_EQ(s.shapes[0].mesh.triangle_count(), 3u);
    EXPECT_EQ(s.shapes[0].origin, dir.file("main.scn") + ":3-5");
    expect_vec(s.shapes[0].mesh.positions[s.shapes[0].mesh.indices[6]], {0, 0, 2});
    EXPECT_EQ(s.shapes[1].mesh.triangle_count(), 1u);
    EXPECT_EQ(s.shapes[1].material, 1);
    EXPECT_EQ(s.shapes[2].kind, Shape::Kind::Sphere);
    EXPECT_EQ(s.shapes[3].mesh.triangle_count(), 1u);  // a sphere in between breaks the run
}

TEST_F(ScnCommand, BoxAcceptsCornersInAnyOrder) {
    const auto s = load(kMat + "box 0   1 -2 3   -1 2 0.5\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(s.shapes[0].kind, Shape::Kind::Box);
    expect_vec(s.shapes[0].box_min, {-1, -2, 0.5f});
    expect_vec(s.shapes[0].box_max, {1, 2, 3});
}

TEST_F(ScnCommand, Sphere) {
    const auto s = load(kMat + "sphere 0   1 2 3   0.25\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(s.shapes[0].kind, Shape::Kind::Sphere);
    expect_vec(s.shapes[0].center, {1, 2, 3});
    EXPECT_FLOAT_EQ(s.shapes[0].radius, 0.25f);
    EXPECT_EQ(s.shapes[0].material, 0);
}

TEST_F(ScnCommand, CircleIsADiskWithUnitNormal) {
    const auto s = load(kMat + "circle 0   1 2 3   0 0 -4   0.5\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(s.shapes[0].kind, Shape::Kind::Disk);
    expect_vec(s.shapes[0].center, {1, 2, 3});
    expect_vec(s.shapes[0].normal, {0, 0, -1});
    EXPECT_FLOAT_EQ(s.shapes[0].radius, 0.5f);
}

TEST_F(ScnCommand, CylinderAndConeAlongY) {
    const auto s = load(kMat + "cylinder 0   1 2 3   0.5 2\ncone 0   -1 0 0   0.25 1.5\n");
    ASSERT_EQ(s.shapes.size(), 2u);
    EXPECT_EQ(s.shapes[0].kind, Shape::Kind::Cylinder);
    expect_vec(s.shapes[0].center, {1, 2, 3});
    expect_vec(s.shapes[0].axis, {0, 1, 0});
    EXPECT_FLOAT_EQ(s.shapes[0].radius, 0.5f);
    EXPECT_FLOAT_EQ(s.shapes[0].height, 2.0f);
    EXPECT_TRUE(s.shapes[0].capped);
    EXPECT_EQ(s.shapes[1].kind, Shape::Kind::Cone);
    expect_vec(s.shapes[1].center, {-1, 0, 0});
    expect_vec(s.shapes[1].axis, {0, 1, 0});
    EXPECT_FLOAT_EQ(s.shapes[1].radius, 0.25f);
    EXPECT_FLOAT_EQ(s.shapes[1].height, 1.5f);
    EXPECT_TRUE(s.shapes[1].capped);
}

TEST_F(ScnCommand, LineIsAThinCylinderBetweenItsEnds) {
    const auto s = load(kMat + "line 0   1 1 1   1 1 5\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    const Shape& c = s.shapes[0];
    EXPECT_EQ(c.kind, Shape::Kind::Cylinder);
    expect_vec(c.center, {1, 1, 3});
    expect_vec(c.axis, {0, 0, 1});
    EXPECT_FLOAT_EQ(c.height, 4.0f);
    EXPECT_FLOAT_EQ(c.radius, 0.02f);  // 0.5 % of the length
}

TEST_F(ScnCommand, MeshLoadsAnOffFileRelativeToTheScene) {
    dir.write("meshes/quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
    const auto s = load(kMat + "mesh 0 meshes/quad.off\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(s.shapes[0].kind, Shape::Kind::Mesh);
    EXPECT_EQ(s.shapes[0].mesh.positions.size(), 4u);
    EXPECT_EQ(s.shapes[0].mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(s.shapes[0].material, 0);
}

TEST_F(ScnCommand, MeshAlsoReadsObjAndPly) {
    dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n");
    dir.write(
        "tri.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    const auto s = load(kMat + "mesh 0 tri.obj\nmesh -1 tri.ply\n");
    ASSERT_EQ(s.shapes.size(), 2u);
    EXPECT_EQ(s.shapes[0].mesh.triangle_count(), 2u);
    EXPECT_EQ(s.shapes[1].mesh.triangle_count(), 1u);
    EXPECT_EQ(s.materials[size_t(s.shapes[1].material)].diffuse, Rgb(0.8f));  // default material
}

TEST_F(ScnCommand, GroupsComposeTransformsAndInheritMaterials) {
    const auto s = load(kMat + kMat +
                        "begin 1   1 0 0 10   0 1 0 0   0 0 1 0   0 0 0 1\n"  // translate x+10, material 1
                        "  sphere -1   0 0 0  1\n"
                        "  begin -1   2 0 0 0   0 2 0 0   0 0 2 0   0 0 0 1\n"  // scale 2, inherits 1
                        "    sphere -1   1 0 0  1\n"
                        "    sphere 0   1 0 0  1\n"
                        "  end\n"
                        "end\n"
                        "sphere -1   0 0 0  1\n");
    ASSERT_EQ(s.shapes.size(), 4u);
    EXPECT_EQ(s.shapes[0].material, 1);
    expect_vec(s.shapes[0].to_world.point({0, 0, 0}), {10, 0, 0});
    EXPECT_EQ(s.shapes[1].material, 1);
    // outer * inner: scale first, then translate
    expect_vec(s.shapes[1].to_world.point({1, 0, 0}), {12, 0, 0});
    EXPECT_FLOAT_EQ(s.shapes[1].to_world.matrix()(0, 0), 2.0f);
    EXPECT_FLOAT_EQ(s.shapes[1].to_world.matrix()(0, 3), 10.0f);
    EXPECT_EQ(s.shapes[2].material, 0);
    // after both ends: identity and the default white material (albedo 0.8)
    EXPECT_TRUE(s.shapes[3].to_world.is_identity());
    const int d = s.shapes[3].material;
    ASSERT_EQ(d, 2);
    EXPECT_EQ(s.materials[size_t(d)].diffuse, Rgb(0.8f));
}

TEST_F(ScnCommand, LightsInsideGroupsAreTransformed) {
    const auto s = load(
        "begin -1   0 -1 0 1   1 0 0 2   0 0 1 3   0 0 0 1\n"  // rotate +90 about z, translate
        "  point_light 1 1 1   1 0 0   0 0 1\n"
        "  dir_light 1 1 1   1 0 0\n"
        "end\n");
    ASSERT_EQ(s.lights.size(), 2u);
    expect_vec(s.lights[0].position, {1, 3, 3});
    expect_vec(s.lights[1].direction, {0, 1, 0});  // a vector: no translation
}

TEST_F(ScnCommand, IncludeNumbersMaterialsPerFileAndResolvesRelativePaths) {
    dir.write("sub/tri.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    dir.write("sub/inc.scn",
              "material 0 0 0  0.1 0.2 0.3  0 0 0  0 0 0  0 0 0  10 1 0\n"  // its own material 0
              "sphere 0   0 0 0  1\n"
              "mesh 0 tri.off\n");
    const auto s = load(kMat +
                        "material 0 0 0  0.9 0.9 0.9  0 0 0  0 0 0  0 0 0  10 1 0\n"
                        "include sub/inc.scn\n"
                        "sphere 1   0 0 0  2\n");
    ASSERT_EQ(s.materials.size(), 3u);
    ASSERT_EQ(s.shapes.size(), 3u);
    EXPECT_EQ(s.shapes[0].material, 2);  // the included file's material 0
    EXPECT_EQ(s.materials[2].diffuse, Rgb(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(s.shapes[0].origin, dir.file("sub/inc.scn") + ":2");
    EXPECT_EQ(s.shapes[1].mesh.triangle_count(), 1u);
    EXPECT_EQ(s.shapes[2].material, 1);  // back in main.scn, its own numbering
}

TEST_F(ScnCommand, IncludeInsideAGroupInheritsTransformAndMaterial) {
    dir.write("inc.scn", "sphere -1   0 0 0  1\n");
    const auto s = load(kMat + "begin 0   1 0 0 0   0 1 0 5   0 0 1 0   0 0 0 1\ninclude inc.scn\nend\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(s.shapes[0].material, 0);
    expect_vec(s.shapes[0].to_world.point({0, 0, 0}), {0, 5, 0});
}

TEST_F(ScnCommand, BackgroundAndAmbient) {
    const auto s = load("background 0.1 0.2 0.3\nambient 0.4 0.5 0.6\n");
    EXPECT_EQ(s.background, Rgb(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(s.ambient, Rgb(0.4f, 0.5f, 0.6f));
}

TEST_F(ScnCommand, PointLight) {
    const auto s = load("point_light 10 20 30   1 2 3   0 0 1\n");
    ASSERT_EQ(s.lights.size(), 1u);
    const Light& l = s.lights[0];
    EXPECT_EQ(l.kind, Light::Kind::Point);
    EXPECT_EQ(l.color, Rgb(10, 20, 30));
    expect_vec(l.position, {1, 2, 3});
    expect_vec(l.attenuation, {0, 0, 1});
}

TEST_F(ScnCommand, SpotLight) {
    const auto s = load("spot_light 5 5 5   0 4 0   0 -2 0   0 0 1   0.3 8\n");
    ASSERT_EQ(s.lights.size(), 1u);
    const Light& l = s.lights[0];
    EXPECT_EQ(l.kind, Light::Kind::Spot);
    EXPECT_EQ(l.color, Rgb(5));
    expect_vec(l.position, {0, 4, 0});
    expect_vec(l.direction, {0, -1, 0});
    EXPECT_FLOAT_EQ(l.cutoff, 0.3f);
    EXPECT_FLOAT_EQ(l.dropoff, 8.0f);
}

TEST_F(ScnCommand, DirLight) {
    const auto s = load("dir_light 2 3 4   0 0 -5\n");
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].kind, Light::Kind::Directional);
    EXPECT_EQ(s.lights[0].color, Rgb(2, 3, 4));
    expect_vec(s.lights[0].direction, {0, 0, -1});
}

TEST_F(ScnCommand, AreaLightIsABlackDiskEmitter) {
    const auto s = load("area_light 7 8 9   1 2 3   0 -3 0   0.5   0 0 1\n");
    ASSERT_EQ(s.lights.size(), 1u);
    ASSERT_EQ(s.shapes.size(), 1u);
    const Light& l = s.lights[0];
    EXPECT_EQ(l.kind, Light::Kind::Area);
    EXPECT_EQ(l.color, Rgb(7, 8, 9));
    EXPECT_EQ(l.shape, 0);
    EXPECT_FALSE(l.two_sided);
    const Shape& d = s.shapes[0];
    EXPECT_EQ(d.kind, Shape::Kind::Disk);
    EXPECT_EQ(d.area_light, 0);
    expect_vec(d.center, {1, 2, 3});
    expect_vec(d.normal, {0, -1, 0});
    EXPECT_FLOAT_EQ(d.radius, 0.5f);
    const auto& m = s.materials[size_t(d.material)];
    EXPECT_TRUE(m.diffuse.is_black() && m.specular.is_black() && m.transmission.is_black());
}

TEST_F(ScnCommand, RectLightWindingFacesA1CrossA2) {
    const auto s = load("rect_light 15 15 15   0 1 0   1 0 0   0 0 1   0.5 0.2   0 0 1\n");
    ASSERT_EQ(s.lights.size(), 1u);
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(s.lights[0].color, Rgb(15));
    const auto& mesh = s.shapes[0].mesh;
    ASSERT_EQ(mesh.triangle_count(), 2u);
    float area = 0;
    for (size_t t = 0; t < 2; ++t) {
        const Vec3 p0 = mesh.positions[mesh.indices[3 * t]], p1 = mesh.positions[mesh.indices[3 * t + 1]],
                   p2 = mesh.positions[mesh.indices[3 * t + 2]];
        const Vec3 n = cross(p1 - p0, p2 - p0);
        area += 0.5f * length(n);
        expect_vec(normalize(n), {0, -1, 0});  // (1,0,0) x (0,0,1)
        for (Vec3 p : {p0, p1, p2}) {
            EXPECT_FLOAT_EQ(p.y, 1.0f);
            EXPECT_NEAR(std::fabs(p.x), 0.25f, 1e-6f);
            EXPECT_NEAR(std::fabs(p.z), 0.1f, 1e-6f);
        }
    }
    EXPECT_NEAR(area, 0.1f, 1e-6f);
}

TEST_F(ScnCommand, NonPhysicalAttenuationWarnsOncePerLightUnlessLegacy) {
    const std::string text =
        "point_light 1 1 1  0 0 0  1 0 0\npoint_light 1 1 1  0 0 0  0 0 1\n"
        "spot_light 1 1 1  0 0 0  0 -1 0  1 0.5 0  0.5 1\n";
    int before = log::warning_count();
    auto s = load(text);
    EXPECT_EQ(log::warning_count() - before, 2);
    expect_vec(s.lights[0].attenuation, {1, 0, 0});
    expect_vec(s.lights[2].attenuation, {1, 0.5f, 0});
    ScnOptions legacy;
    legacy.legacy_attenuation = true;
    before = log::warning_count();
    s = load(text, legacy);
    EXPECT_EQ(log::warning_count() - before, 0);
    expect_vec(s.lights[0].attenuation, {1, 0, 0});
}

// A scene without lights gets the seed renderer's two default directional lights, with one
// warning; --no-default-lights leaves it dark (and `phos render` then warns once, for every
// format: tests/app/options_test.cpp, NoLightsWarnsOnceNamingTheCause).
TEST_F(ScnCommand, NoLightsGetsTheSeedsDefaultLights) {
    const int before = log::warning_count();
    auto s = load(kMat + "sphere 0 0 0 0 1\n");
    EXPECT_EQ(log::warning_count() - before, 1);
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].kind, scene::Light::Kind::Directional);
    expect_vec(s.lights[0].direction, normalize(Vec3(-3, -4, -5)));
    EXPECT_EQ(s.lights[0].color, Rgb(1.0f));
    expect_vec(s.lights[1].direction, normalize(Vec3(3, 2, 3)));
    EXPECT_EQ(s.lights[1].color, Rgb(0.5f));

    ScnOptions none;
    none.no_default_lights = true;
    const int before_none = log::warning_count();
    s = load(kMat + "sphere 0 0 0 0 1\n", none);
    EXPECT_EQ(log::warning_count() - before_none, 0);
    EXPECT_TRUE(s.lights.empty());

    // Any light, even a black one (the seed's way to suppress them), means no default lights.
    const int before2 = log::warning_count();
    s = load(kMat + "sphere 0 0 0 0 1\npoint_light 0 0 0  0 2 0  0 0 1\n");
    EXPECT_EQ(log::warning_count() - before2, 0);
    EXPECT_EQ(s.lights.size(), 1u);
}

// A glow `e` is a light: each glowing shape becomes a two-sided area light of radiance e (its glow
// moves into the light, so it is not counted twice). Only light commands keep the seed's default
// lights away; with emission_lights off the glow is only seen, as in the seed.
TEST_F(ScnCommand, GlowingSurfacesAreTwoSidedAreaLights) {
    const std::string glow = "material 0 0 0  0.2 0.2 0.2  0 0 0  0 0 0  4 3 2  10 1 0\n";
    const std::string black_light = "point_light 0 0 0  0 2 0  0 0 1\n";
    auto s = load(kMat + glow + "sphere 0 0 0 0 1\ntri 1  0 1 0  1 1 0  0 1 1\ncircle 1  0 3 0  0 -1 0  1\n" +
                  black_light);
    ASSERT_EQ(s.lights.size(), 3u);  // the black point light and the two glowing shapes
    EXPECT_EQ(s.shapes[0].area_light, -1);
    for (size_t i : {size_t(1), size_t(2)}) {
        ASSERT_GE(s.shapes[i].area_light, 0) << i;
        const Light& l = s.lights[size_t(s.shapes[i].area_light)];
        EXPECT_EQ(l.kind, Light::Kind::Area);
        EXPECT_TRUE(l.two_sided);
        EXPECT_EQ(l.shape, int(i));
        EXPECT_EQ(l.color, Rgb(4, 3, 2));
        EXPECT_TRUE(s.materials[size_t(s.shapes[i].material)].emission.is_black());
        EXPECT_EQ(s.materials[size_t(s.shapes[i].material)].diffuse, Rgb(0.2f));
    }

    // Without a light command the seed's default lights come too.
    s = load(kMat + glow + "sphere 1 0 0 0 1\n");
    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_EQ(s.lights[0].kind, Light::Kind::Directional);
    EXPECT_EQ(s.lights[2].kind, Light::Kind::Area);

    ScnOptions seen_only;
    seen_only.emission_lights = false;
    s = load(kMat + glow + "sphere 1 0 0 0 1\n" + black_light, seen_only);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.shapes[0].area_light, -1);
    EXPECT_EQ(s.materials[size_t(s.shapes[0].material)].emission, Rgb(4, 3, 2));
}

// Writes a width x 1 RGB PNG with the given 8-bit pixels.
void write_png(const std::string& path, const std::vector<unsigned char>& rgb) {
    FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, f);
    png_set_IHDR(png, info, png_uint_32(rgb.size() / 3), 1, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    png_write_row(png, rgb.data());
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
}

TEST_F(ScnCommand, TextureIsLoadedAsSrgbAndShared) {
    dir.write("tex/readme.txt", "");  // creates the directory
    write_png(dir.file("tex/wood.png"), {255, 0, 0, 0, 128, 255});
    const auto s = load(
        "material 0 0 0  1 1 1  0 0 0  0 0 0  0 0 0  10 1 tex/wood.png\n"
        "material 0 0 0  0.5 0.5 0.5  0 0 0  0 0 0  0 0 0  10 1 ./tex/wood.png\n");
    ASSERT_EQ(s.materials.size(), 2u);
    ASSERT_EQ(s.textures.size(), 1u);  // the same file is loaded once
    EXPECT_EQ(s.materials[0].diffuse_texture, 0);
    EXPECT_EQ(s.materials[1].diffuse_texture, 0);
    const auto& t = s.textures[0];
    EXPECT_EQ(t.kind, scene::Texture::Kind::Image);
    ASSERT_TRUE(t.image);
    ASSERT_EQ(t.image->width, 2);
    ASSERT_EQ(t.image->height, 1);
    EXPECT_NEAR(t.image->at(0, 0).r, 1.0f, 1e-4f);
    EXPECT_NEAR(t.image->at(0, 0).g, 0.0f, 1e-4f);
    // sRGB 128/255 decodes to about 0.2159 linear
    EXPECT_NEAR(t.image->at(1, 0).g, 0.2158605f, 1e-3f);
    EXPECT_NEAR(t.image->at(1, 0).b, 1.0f, 1e-4f);
}

TEST_F(ScnCommand, CommentsAndLineBreaksInsideCommands) {
    const auto s = load("# a comment line\n" + kMat +
                        "sphere 0   # material\n"
                        "  1 2 3    # centre\n"
                        "  0.5      # radius\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    expect_vec(s.shapes[0].center, {1, 2, 3});
    EXPECT_FLOAT_EQ(s.shapes[0].radius, 0.5f);
    EXPECT_EQ(s.shapes[0].origin, dir.file("main.scn") + ":3");
}

TEST_F(ScnCommand, NumberForms) {
    const auto s = load(kMat + "sphere 0   .5 -1e-3 +2.   1E1\n");
    expect_vec(s.shapes[0].center, {0.5f, -0.001f, 2.0f});
    EXPECT_FLOAT_EQ(s.shapes[0].radius, 10.0f);
}

}  // namespace
}  // namespace phos::io::test
