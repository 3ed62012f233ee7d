// What the `.scene` reader builds, against hand-computed values: transforms in the order written,
// shared materials, the camera's d, lights given by flux, the sky, emissive objects, and the media
// on either side of every boundary (invisible, refractive, nested, scene-filling).
#include <gtest/gtest.h>

#include <cmath>

#include "core/log.h"
#include "io/scene_format/scene_format_loader.h"
#include "spectrum/dispersion.h"
#include "support/mesh_writers.h"
#include "test_util.h"

namespace phos::io {
namespace {

using scene::Light;
using scene::Shape;

// A single triangle (1,0,0) (0,1,0) (0,0,1).
const std::string kTrianglePly =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n";

// The closed cube [-1, 1]^3, faces outwards.
const std::string kCubePly =
    "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 6\nproperty list uchar int vertex_indices\nend_header\n"
    "-1 -1 -1\n1 -1 -1\n1 1 -1\n-1 1 -1\n-1 -1 1\n1 -1 1\n1 1 1\n-1 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 3 7 6 2\n4 0 4 7 3\n4 1 2 6 5\n";

void expect_near(Vec3 a, Vec3 b, float tol = 1e-5f) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tol) << "component " << i;
}

scene::Scene load(const testing::TempDir& dir, const std::string& main) {
    log::set_quiet(true);
    scene::Scene s = load_scene_format(dir.write("main.scene", main));
    log::set_quiet(false);
    return s;
}

TEST(SceneFormat, TransformsApplyInTheOrderWritten) {
    testing::TempDir dir;
    dir.write("t.ply", kTrianglePly);
    dir.write("w.mat", "diffuse 0.5 0.5 0.5\n");
    // scale 2, then a quarter turn about +y (x -> -z), then up by 1: (1,0,0) -> (2,0,0) -> (0,0,-2) ->
    // (0,1,-2)
    dir.write("a.mesh", "ply t.ply\nmaterial w.mat\nscale 2\nrotate 90 0 1 0\ntranslate 0 1 0\n");
    // the same steps in the other order: (1,0,0) -> (1,1,0) -> (0,1,-1) -> (0,2,-2)
    dir.write("b.mesh", "ply t.ply\nmaterial w.mat\ntranslate 0 1 0\nrotate 90 0 1 0\nscale 2 2 2\n");
    // a non-uniform scale: (0,1,0) -> (0,3,0)
    dir.write("c.mesh", "translate 0 0 0\nply t.ply\nscale 1 3 1\nmaterial w.mat\n");
    const scene::Scene s = load(dir, "mesh a.mesh\nmesh b.mesh\nmesh c.mesh\n");
    ASSERT_EQ(s.shapes.size(), 3u);
    const auto world = [&](size_t shape, size_t v) {
        return s.shapes[shape].to_world.point(s.shapes[shape].mesh.positions[v]);
    };
    expect_near(world(0, 0), {0, 1, -2});
    expect_near(world(0, 1), {0, 3, 0});  // (0,1,0) -> (0,2,0) -> (0,2,0) -> (0,3,0)
    expect_near(world(0, 2), {2, 1, 0});  // (0,0,1) -> (0,0,2) -> (2,0,0) -> (2,1,0)
    expect_near(world(1, 0), {0, 2, -2});
    expect_near(world(1, 2), {2, 2, 0});  // (0,0,1) -> (0,1,1) -> (1,1,0) -> (2,2,0)
    expect_near(world(2, 1), {0, 3, 0});
    // one .mat file named by three meshes is one material
    EXPECT_EQ(s.materials.size(), 1u);
    for (const Shape& sh : s.shapes) EXPECT_EQ(sh.material, 0);
    EXPECT_EQ(s.materials[0].diffuse, Rgb(0.5f));
}

TEST(SceneFormat, CameraDIsTheDistanceToAnImagePlaneOfHeightTwo) {
    testing::TempDir dir;
    const scene::Scene s = load(dir, "camera 0 0 5  0 0 0  0 1 0  4\nresolution 300 200\n");
    ASSERT_TRUE(s.camera);
    expect_near(s.camera->eye, {0, 0, 5});
    expect_near(normalize(s.camera->forward), {0, 0, -1});
    EXPECT_NEAR(s.camera->fov, 2 * std::atan(0.25f), 1e-6f);
    EXPECT_TRUE(s.camera->fov_vertical);
    EXPECT_EQ(*s.settings.width, 300);
    EXPECT_EQ(*s.settings.height, 200);
    EXPECT_FALSE(s.settings.integrator);  // the renderer's default: the photon mapper
}

TEST(SceneFormat, LightsAreGivenByFlux) {
    testing::TempDir dir;
    const scene::Scene s = load(dir,
                                "light point 1 2 3  4 8 12\n"
                                "light area 0 1 0  0 -2 0  3 3 3  0.5 0.25\n"
                                "light area 0 0 0  1 0 0  1 1 1  2 1\n"
                                "sky 0.1 0.2 0.3\n");
    ASSERT_EQ(s.lights.size(), 4u);
    const Light& p = s.lights[0];
    EXPECT_EQ(p.kind, Light::Kind::Point);
    expect_near(p.position, {1, 2, 3});
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(p.color[c], (4.0f * float(c + 1)) / (4 * kPi), 1e-6f);  // I = flux / 4 pi

    const Light& a = s.lights[1];
    EXPECT_EQ(a.kind, Light::Kind::Area);
    EXPECT_FALSE(a.two_sided);
    EXPECT_NEAR(a.color.r, 3.0f / (kPi * 0.5f * 0.25f), 1e-4f);  // L = flux / (pi w h)
    const Shape& rect = s.shapes[size_t(a.shape)];
    // width along x (the projection of world x), height along n x width = (0,-1,0) x (1,0,0) = (0,0,1)
    expect_near(rect.mesh.positions[0], {-0.25f, 1, -0.125f});
    expect_near(rect.mesh.positions[2], {0.25f, 1, 0.125f});
    const Vec3 n = cross(rect.mesh.positions[1] - rect.mesh.positions[0],
                         rect.mesh.positions[2] - rect.mesh.positions[0]);
    expect_near(normalize(n), {0, -1, 0});  // faces n: counter-clockwise seen from below

    // n along x: the width runs along z, the height along n x z = -y
    const Shape& side = s.shapes[size_t(s.lights[2].shape)];
    expect_near(side.mesh.positions[1] - side.mesh.positions[0], {0, 0, 2});
    expect_near(side.mesh.positions[2] - side.mesh.positions[1], {0, -1, 0});

    EXPECT_EQ(s.lights[3].kind, Light::Kind::Infinite);
    EXPECT_EQ(s.lights[3].color, Rgb(0.1f, 0.2f, 0.3f));
}

TEST(SceneFormat, MaterialTermsAndEmissiveObjects) {
    testing::TempDir dir;
    dir.write("glass.mat", "transmission 0.9 0.95 1\nior 1.33\n");
    dir.write("mirror.mat", "# a mirror\nspecular 0.8 0.8 0.8\n");
    dir.write("lamp.mat", "diffuse 0.2 0.2 0.2\nemission 5 4 3\n");
    const scene::Scene s =
        load(dir, "sphere 1 0 0 0 glass.mat\nsphere 0.5 3 0 0 mirror.mat\nsphere 0.25 0 3 0 lamp.mat\n");
    ASSERT_EQ(s.shapes.size(), 3u);
    const scene::Material& glass = s.materials[size_t(s.shapes[0].material)];
    EXPECT_EQ(glass.transmission, Rgb(0.9f, 0.95f, 1.0f));
    EXPECT_FLOAT_EQ(glass.ior, 1.33f);
    EXPECT_GE(glass.transmission_shininess, scene::Material::kMirrorShininess);
    const scene::Material& mirror = s.materials[size_t(s.shapes[1].material)];
    EXPECT_EQ(mirror.specular, Rgb(0.8f));
    EXPECT_GE(mirror.shininess, scene::Material::kMirrorShininess);
    // an emissive object is an area light with the material's radiance, not a glow
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].kind, Light::Kind::Area);
    EXPECT_EQ(s.lights[0].color, Rgb(5, 4, 3));
    EXPECT_EQ(s.lights[0].shape, 2);
    EXPECT_EQ(s.shapes[2].area_light, 0);
    EXPECT_TRUE(s.materials[size_t(s.shapes[2].material)].emission.is_black());
    EXPECT_EQ(s.materials[size_t(s.shapes[2].material)].diffuse, Rgb(0.2f));
}

// The dispersion keys: the index over wavelength, `ior` its value at the d line (587.6 nm).
TEST(SceneFormat, DispersionKeysGiveTheIndexOverWavelength) {
    testing::TempDir dir;
    dir.write("abbe.mat", "transmission 1 1 1\nabbe 30\nior 1.7\n");
    dir.write("cauchy.mat", "transmission 1 1 1\ncauchy 1.5 0.0042\n");
    dir.write("sellmeier.mat",
              "transmission 1 1 1\nsellmeier 1.03961212 0.231792344 1.01046945 0.00600069867 0.0200179144 "
              "103.560653\n");
    dir.write("glass.mat", "transmission 1 1 1\nglass SF10\n");
    dir.write("prefixed.mat", "transmission 1 1 1\nglass glass-LASF9\n");
    dir.write("plain.mat", "transmission 1 1 1\nior 1.5\n");
    const scene::Scene s = load(dir,
                                "sphere 1 0 0 0 abbe.mat\nsphere 1 3 0 0 cauchy.mat\nsphere 1 6 0 0 "
                                "sellmeier.mat\nsphere 1 9 0 0 glass.mat\nsphere 1 12 0 0 prefixed.mat\n"
                                "sphere 1 15 0 0 plain.mat\n");
    const auto mat = [&](size_t i) -> const scene::Material& {
        return s.materials[size_t(s.shapes[i].material)];
    };
    const auto n = [&](size_t i, double lambda) { return double((*mat(i).ior_spectrum)(float(lambda))); };
    for (size_t i = 0; i < 5; ++i) {
        ASSERT_TRUE(mat(i).ior_spectrum.has_value()) << i;
        EXPECT_NEAR(mat(i).ior, n(i, spectrum::kLineD), 1e-6) << i;  // ior: the d line's index
        EXPECT_GT(n(i, 450), n(i, 650)) << i;                        // normal dispersion
    }
    // abbe: n_d = ior, and (n_d - 1) / (n_F - n_C) = V_d.
    EXPECT_NEAR(n(0, spectrum::kLineD), 1.7, 1e-5);
    EXPECT_NEAR((n(0, spectrum::kLineD) - 1) / (n(0, spectrum::kLineF) - n(0, spectrum::kLineC)), 30, 1e-2);
    // cauchy: A + B / lambda^2, lambda in um.
    EXPECT_NEAR(n(1, 500), 1.5 + 0.0042 / 0.25, 1e-6);
    EXPECT_NEAR(mat(1).ior, 1.5 + 0.0042 / (0.5875618 * 0.5875618), 1e-6);
    // sellmeier: BK7's coefficients give BK7's catalogue index.
    EXPECT_NEAR(mat(2).ior, 1.51680, 1e-4);
    // glass: the named glasses, with or without pbrt-v4's "glass-" prefix.
    EXPECT_NEAR(mat(3).ior, 1.72828, 1e-4);
    EXPECT_NEAR(mat(4).ior, 1.85025, 1e-4);
    EXPECT_NEAR(n(3, 450), spectrum::named_glass("glass-SF10")->ior(450), 1e-6);
    // A plain ior has no dispersion.
    EXPECT_FALSE(mat(5).ior_spectrum.has_value());
    EXPECT_FLOAT_EQ(mat(5).ior, 1.5f);
}

TEST(SceneFormat, SmokeIsAnInvisibleBoundaryAroundItsMedium) {
    testing::TempDir dir;
    dir.write("cube.ply", kCubePly);
    dir.write("smoke.mat", "absorption 0.1 0.2 0.3\nscattering 1 2 3\nphase 0.4\n");
    dir.write("smoke.mesh", "ply cube.ply\nmaterial smoke.mat\n");
    // the light is inside the smoke, the camera outside
    const scene::Scene s =
        load(dir, "mesh smoke.mesh\nlight point 0 0.5 0 1 1 1\ncamera 0 0 5 0 0 0 0 1 0 2\n");
    ASSERT_EQ(s.media.size(), 1u);
    const scene::Medium& m = s.media[0];
    EXPECT_EQ(m.kind, scene::Medium::Kind::Homogeneous);
    EXPECT_EQ(m.sigma_a, Rgb(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(m.sigma_s, Rgb(1, 2, 3));
    EXPECT_FLOAT_EQ(m.g, 0.4f);
    EXPECT_TRUE(s.materials[size_t(s.shapes[0].material)].interface_only);
    EXPECT_EQ(s.shapes[0].media.inside, 0);
    EXPECT_EQ(s.shapes[0].media.outside, -1);
    EXPECT_EQ(s.lights[0].medium, 0);
    EXPECT_EQ(s.camera_medium, -1);
}

TEST(SceneFormat, MurkyWaterAroundAGlassSphereInAFoggyScene) {
    testing::TempDir dir;
    dir.write("cube.ply", kCubePly);
    dir.write("water.mat", "transmission 1 1 1\nior 1.33\nabsorption 0.3 0.1 0.05\nscattering 0.5 0.5 0.5\n");
    dir.write("glass.mat", "transmission 1 1 1\nior 1.5\n");
    dir.write("fog.mat", "scattering 0.05 0.05 0.05\n");
    dir.write("wall.mat", "diffuse 0.5 0.5 0.5\n");
    dir.write("tank.mesh", "ply cube.ply\nmaterial water.mat\nscale 2\n");
    const scene::Scene s = load(dir,
                                "mesh tank.mesh\n"
                                "sphere 0.5 0 -1 0 glass.mat\n"  // inside the tank
                                "sphere 0.5 5 0 0 glass.mat\n"   // in the fog
                                "sphere 0.5 -5 0 0 wall.mat\n"   // opaque: no transition
                                "medium fog.mat\n"
                                "light point 0 10 0 1 1 1\n"
                                "camera 0 0 9 0 0 0 0 1 0 2\n");
    ASSERT_EQ(s.media.size(), 2u);
    const int water = s.shapes[0].media.inside, fog = s.camera_medium;
    EXPECT_NE(water, -1);
    EXPECT_NE(fog, -1);
    EXPECT_NE(water, fog);
    EXPECT_EQ(s.media[size_t(water)].sigma_a, Rgb(0.3f, 0.1f, 0.05f));
    EXPECT_FALSE(s.materials[size_t(s.shapes[0].material)].interface_only);  // it refracts
    EXPECT_EQ(s.shapes[0].media.outside, fog);
    EXPECT_EQ(s.shapes[1].media.inside, -1);  // clear glass
    EXPECT_EQ(s.shapes[1].media.outside, water);
    EXPECT_EQ(s.shapes[2].media.outside, fog);
    EXPECT_FALSE(s.shapes[3].media.is_transition());
    EXPECT_EQ(s.lights[0].medium, fog);
    EXPECT_EQ(s.media[size_t(fog)].sigma_s, Rgb(0.05f));
}

TEST(SceneFormat, TexturedMeshKeepsItsUv) {
    testing::TempDir dir;
    dir.write(
        "uv.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "property float s\nproperty float t\nelement face 1\nproperty list uchar int vertex_indices\n"
        "end_header\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n");
    dir.write("tex.pfm", std::string("PF\n1 1\n-1\n") +
                             std::string("\x00\x00\x00\x3f\x00\x00\x80\x3e\x00\x00\x80\x3f", 12));
    dir.write("t.mat", "diffuse 0.5 0.5 0.5\ntexture tex.pfm\n");
    dir.write("t.mesh", "ply uv.ply\nmaterial t.mat\n");
    const scene::Scene s = load(dir, "mesh t.mesh\nsphere 1 5 0 0 t.mat\n");
    ASSERT_EQ(s.textures.size(), 1u);  // one file, read once
    ASSERT_EQ(s.shapes[0].mesh.uvs.size(), 3u);
    EXPECT_EQ(s.shapes[0].mesh.uvs[1], Vec2(1, 0));
    const scene::Material& m = s.materials[size_t(s.shapes[0].material)];
    EXPECT_EQ(m.diffuse_texture, 0);
    ASSERT_TRUE(s.textures[0].image);
    EXPECT_EQ(s.textures[0].image->at(0, 0), Rgb(0.5f, 0.25f, 1.0f));  // PFM floats are linear
}

// A binary PLY with normals and uv, written by phos's own writer, is read through a .mesh.
TEST(SceneFormat, BinaryPlyWithNormalsAndUv) {
    testing::TempDir dir;
    scene::TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    m.uvs = {{0, 0}, {1, 0}, {0, 1}};
    m.indices = {0, 1, 2};
    testing::write_ply(dir.file("b.ply"), m, /*binary=*/true);
    dir.write("t.mat", "diffuse 1 1 1\ntexture tex.pfm\n");
    dir.write("tex.pfm", std::string("PF\n1 1\n-1\n") + std::string(12, '\0'));
    dir.write("b.mesh", "ply b.ply\nmaterial t.mat\n");
    const scene::Scene s = load(dir, "mesh b.mesh\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(s.shapes[0].mesh.positions, m.positions);
    EXPECT_EQ(s.shapes[0].mesh.normals, m.normals);
    EXPECT_EQ(s.shapes[0].mesh.uvs, m.uvs);
}

}  // namespace
}  // namespace phos::io
