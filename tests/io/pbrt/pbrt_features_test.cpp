// How each supported pbrt construct maps onto scene::Scene: cameras, transforms, instancing,
// shapes and their orientation, materials, textures, lights, spectra, media, and the warnings for
// anything unsupported or unused.
#include <gtest/gtest.h>
#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "io/pbrt/spectra.h"
#include "pbrt_test_util.h"
#include "spectrum/color.h"
#include "support/gzip_writer.h"
#include "support/mesh_writers.h"

namespace phos::io::test {
namespace {

using scene::Light;
using scene::Shape;

const std::string kView =
    "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\n";

struct Loaded {
    scene::Scene scene;
    int warnings = 0;
};

Loaded load_text(const std::string& text, const PbrtOptions& options = {}) {
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string path = dir.write("scene.pbrt", text);
    const int before = log::warning_count();
    Loaded l{load_pbrt(path, options), 0};
    l.warnings = log::warning_count() - before;
    return l;
}

void expect_vec(Vec3 a, Vec3 b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

Vec3 tri_normal(const scene::TriangleMesh& m, size_t t) {
    const Vec3 p0 = m.positions[m.indices[3 * t]], p1 = m.positions[m.indices[3 * t + 1]],
               p2 = m.positions[m.indices[3 * t + 2]];
    return cross(p1 - p0, p2 - p0);
}

// ---- camera ----

TEST(PbrtCamera, WithoutScaleTheImageIsMirroredAndFovDefaultsTo90) {
    const Loaded l = load_text("LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n");
    ASSERT_TRUE(l.scene.camera);
    EXPECT_TRUE(l.scene.camera->flip_x);  // pbrt's left-handed LookAt puts world -x on the image right
    EXPECT_NEAR(l.scene.camera->fov, kPi / 2, 1e-6f);
    expect_vec(l.scene.camera->eye, {0, 0, 5});
    EXPECT_FALSE(l.scene.settings.width.has_value());  // no Film: the CLI decides
    EXPECT_EQ(l.warnings, 0);
}

TEST(PbrtCamera, ScaleMinusOneGivesRightHandedImageAndFilmSettings) {
    const Loaded l = load_text(
        "Film \"rgb\" \"integer xresolution\" 400 \"integer yresolution\" 200 \"string filename\" "
        "\"out.exr\"\n" +
        kView + "WorldBegin\n");
    const scene::Camera& c = *l.scene.camera;
    EXPECT_FALSE(c.flip_x);
    expect_vec(normalize(c.forward), {0, 0, -1});
    expect_vec(normalize(c.up), {0, 1, 0});
    expect_vec(normalize(cross(c.forward, c.up)), {1, 0, 0});
    EXPECT_NEAR(c.fov, 45 * kPi / 180, 1e-6f);  // shorter axis (height here): unchanged
    EXPECT_EQ(l.scene.settings.width, 400);
    EXPECT_EQ(l.scene.settings.height, 200);
    EXPECT_EQ(l.scene.settings.output, "out.exr");
}

TEST(PbrtCamera, OrthographicScreenWindowAndLens) {
    const Loaded l = load_text(
        "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"orthographic\" \"float screenwindow\" [-2 2 -2 2] \"float "
        "lensradius\" "
        "0.1 \"float focaldistance\" 3\nWorldBegin\n");
    const scene::Camera& c = *l.scene.camera;
    EXPECT_EQ(c.projection, scene::Camera::Projection::Orthographic);
    EXPECT_FLOAT_EQ(c.ortho_half_size, 2.0f);
    EXPECT_FLOAT_EQ(c.lens_radius, 0.1f);
    EXPECT_FLOAT_EQ(c.focal_distance, 3.0f);
}

TEST(PbrtCamera, CoordSysTransformCameraPlacesALightAtTheEye) {
    const Loaded l =
        load_text(kView +
                  "WorldBegin\nAttributeBegin\nCoordSysTransform \"camera\"\nLightSource \"point\" "
                  "\"rgb I\" [1 2 3]\nAttributeEnd\n");
    ASSERT_EQ(l.scene.lights.size(), 1u);
    expect_vec(l.scene.lights[0].position, {0, 0, 5});
    EXPECT_EQ(l.scene.lights[0].color, Rgb(1, 2, 3));
}

// ---- settings ----

TEST(PbrtSettings, SppmIntegratorSamplerAndFilter) {
    const Loaded l = load_text(
        "Integrator \"sppm\" \"integer maxdepth\" 7 \"float radius\" 0.02 \"integer photonsperiteration\" "
        "65536\n"
        "Sampler \"halton\" \"integer pixelsamples\" 64\nPixelFilter \"box\"\nWorldBegin\n");
    EXPECT_EQ(l.scene.settings.integrator, "sppm");
    // Integrator parameters are kept as written, with their locations; `phos render` maps them
    // onto its option tables (tests/app/options_test.cpp).
    const auto& ps = l.scene.settings.integrator_parameters;
    ASSERT_EQ(ps.size(), 3u);
    EXPECT_EQ(ps[0].name, "maxdepth");
    EXPECT_EQ(ps[0].type, "integer");
    EXPECT_EQ(ps[0].values, std::vector<std::string>{"7"});
    EXPECT_EQ(ps[0].line, 1);
    EXPECT_EQ(ps[0].column, 19);
    EXPECT_EQ(ps[1].name, "radius");
    EXPECT_EQ(ps[1].values, std::vector<std::string>{"0.02"});
    EXPECT_EQ(ps[2].name, "photonsperiteration");
    EXPECT_EQ(ps[2].values, std::vector<std::string>{"65536"});
    EXPECT_EQ(l.scene.settings.spp, 64);
    EXPECT_EQ(l.warnings, 0);
}

TEST(PbrtSettings, UnsupportedThingsWarnExactlyOnceEach) {
    // an unsupported Option, mlt integrator, hyperboloid shape, an unknown light, TransformTimes: one
    // each, even though they carry parameters; pbrt-v3's WorldEnd is read silently.
    const Loaded l = load_text(
        "Option \"bool forcediffuse\" true\n"
        "Integrator \"mlt\" \"integer mutationsperpixel\" 10\nWorldBegin\n"
        "Shape \"hyperboloid\" \"point3 p1\" [0 0 0] \"point3 p2\" [1 1 1]\n"
        "LightSource \"sunsky\" \"string filename\" \"x.exr\"\nTransformTimes 0 1\n"
        "LightSource \"point\"\nWorldEnd\n");
    EXPECT_EQ(l.warnings, 4);  // the mlt integrator is reported by `phos render` (it may be overridden)
    EXPECT_EQ(l.scene.settings.integrator, "bdpt");  // mlt explores bdpt's paths: bdpt, with a warning
    EXPECT_EQ(l.scene.settings.unavailable_integrator, "mlt");
    EXPECT_EQ(l.scene.settings.integrator_location.substr(l.scene.settings.integrator_location.size() - 4),
              ":2:1");
    EXPECT_TRUE(l.scene.shapes.empty());
    EXPECT_EQ(l.scene.lights.size(), 1u);  // the point light; the unknown one is skipped
}

// A scene none of whose lights can be used is refused at the first of them (it would render black,
// exit 0, before): an unsupported light type, an unsupported area light.
TEST(PbrtSettings, ASceneWhoseLightsAllFailIsAnError) {
    PbrtTempDir dir;
    QuietLog quiet;
    expect_pbrt_error(dir.write("a.pbrt",
                                "WorldBegin\nShape \"sphere\"\nLightSource \"sunsky\" \"string "
                                "filename\" \"x.exr\"\nLightSource \"skylight\"\n"),
                      3, 1, "none of the scene's lights can be used");
    expect_pbrt_error(dir.write("b.pbrt", "WorldBegin\nAreaLightSource \"glow\"\nShape \"sphere\"\n"), 2, 1,
                      "none of the scene's lights can be used");
    // A scene with no light directive at all is not this error (the renderer says it has no light).
    EXPECT_NO_THROW(load_pbrt(dir.write("c.pbrt", "WorldBegin\nShape \"sphere\"\n")));
}

// ---- unused parameters ----

TEST(PbrtParams, UnusedParameterWarnsAndStrictMakesItAnError) {
    const std::string text = "WorldBegin\nShape \"sphere\" \"float radius\" 2 \"float radiuss\" 3\n";
    const Loaded l = load_text(text);
    EXPECT_EQ(l.warnings, 1);
    EXPECT_FLOAT_EQ(l.scene.shapes[0].radius, 2.0f);
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string path = dir.write("s.pbrt", text);
    expect_pbrt_error(path, 2, 33, "parameter \"float radiuss\" is not used", path, PbrtOptions{true});
}

TEST(PbrtParams, SyntaxVariants) {
    // un-bracketed values, bools bare or quoted, comments, escapes, legacy type names
    const Loaded l = load_text(
        "WorldBegin # comment \"not a string\"\nAreaLightSource \"diffuse\" \"color L\" [ 2 2 2 ] \"bool "
        "twosided\" "
        "\"true\"\nShape \"sphere\" \"float radius\" 1.5e-1\nAreaLightSource \"diffuse\" \"bool twosided\" "
        "false\n"
        "Shape \"disk\"\n");
    ASSERT_EQ(l.scene.lights.size(), 2u);
    EXPECT_TRUE(l.scene.lights[0].two_sided);
    EXPECT_FALSE(l.scene.lights[1].two_sided);
    EXPECT_EQ(l.scene.lights[0].color, Rgb(2.0f));
    EXPECT_EQ(l.scene.lights[1].color, Rgb(1.0f));  // default: D65 white of luminance 1
    EXPECT_FLOAT_EQ(l.scene.shapes[0].radius, 0.15f);
    EXPECT_EQ(l.warnings, 0);
}

// ---- transforms and structure ----

TEST(PbrtTransforms, TransformIsColumnMajorAndAttributesRestoreState) {
    const Loaded l = load_text(
        "WorldBegin\nAttributeBegin\nTransform [1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1]\nMaterial \"diffuse\" "
        "\"rgb "
        "reflectance\" [0.1 0.2 0.3]\nShape \"sphere\"\nAttributeEnd\nTranslate 1 0 0\nConcatTransform [2 0 "
        "0 0 0 2 0 0 "
        "0 0 2 0 0 0 0 1]\nRotate 90 0 0 1\nShape \"sphere\"\nIdentity\nCoordinateSystem \"id\"\nTranslate 0 "
        "0 1\n"
        "CoordSysTransform \"id\"\nShape \"sphere\"\n");
    ASSERT_EQ(l.scene.shapes.size(), 3u);
    expect_vec(l.scene.shapes[0].to_world.point({0, 0, 0}), {5, 6, 7});
    EXPECT_EQ(l.scene.materials[size_t(l.scene.shapes[0].material)].diffuse, Rgb(0.1f, 0.2f, 0.3f));
    // after AttributeEnd: default material (pbrt's diffuse 0.5), transform T(1,0,0) S(2) R(90 z)
    EXPECT_EQ(l.scene.materials[size_t(l.scene.shapes[1].material)].diffuse, Rgb(0.5f));
    expect_vec(l.scene.shapes[1].to_world.point({1, 0, 0}), {1, 2, 0});
    EXPECT_TRUE(l.scene.shapes[2].to_world.is_identity());
}

TEST(PbrtTransforms, LegacyTransformBeginWarnsOnceAndRestoresOnlyTheTransform) {
    const Loaded l = load_text(
        "WorldBegin\nTransformBegin\nTranslate 1 2 3\nMaterial \"diffuse\" \"rgb reflectance\" [1 0 "
        "0]\nTransformEnd\n"
        "TransformBegin\nTransformEnd\nShape \"sphere\"\n");
    EXPECT_LE(l.warnings, 1);  // warn_once: at most one per process
    expect_vec(l.scene.shapes[0].to_world.point({0, 0, 0}), {0, 0, 0});
    EXPECT_EQ(l.scene.materials[size_t(l.scene.shapes[0].material)].diffuse, Rgb(1, 0, 0));
}

TEST(PbrtTransforms, ObjectInstancing) {
    const Loaded l = load_text(
        "WorldBegin\nObjectBegin \"pair\"\nShape \"sphere\" \"float radius\" 0.5\nTranslate 2 0 0\nShape "
        "\"sphere\"\n"
        "ObjectEnd\nShape \"disk\"\nTranslate 0 10 0\nObjectInstance \"pair\"\nTranslate 0 10 "
        "0\nObjectInstance "
        "\"pair\"\n");
    ASSERT_EQ(l.scene.objects.size(), 1u);
    EXPECT_EQ(l.scene.objects[0].name, "pair");
    ASSERT_EQ(l.scene.objects[0].shapes.size(), 2u);
    expect_vec(l.scene.objects[0].shapes[1].to_world.point({0, 0, 0}), {2, 0, 0});
    ASSERT_EQ(l.scene.instances.size(), 2u);
    expect_vec(l.scene.instances[1].to_world.point({0, 0, 0}), {0, 20, 0});
    EXPECT_EQ(l.scene.instances[1].object, 0);
    ASSERT_EQ(l.scene.shapes.size(), 1u);  // the disk: ObjectEnd restored the transform
    expect_vec(l.scene.shapes[0].to_world.point({0, 0, 0}), {0, 0, 0});
}

TEST(PbrtTransforms, IncludeIsRelativeToTheIncludingFile) {
    QuietLog quiet;
    PbrtTempDir dir;
    dir.write("parts/sphere.pbrt", "Shape \"sphere\" \"float radius\" 3\nInclude \"more/disk.pbrt\"\n");
    dir.write("parts/more/disk.pbrt", "Shape \"disk\"\n");
    const std::string main =
        dir.write("main.pbrt", "WorldBegin\nInclude \"parts/sphere.pbrt\"\nShape \"cylinder\"\n");
    const scene::Scene s = load_pbrt(main);
    ASSERT_EQ(s.shapes.size(), 3u);
    EXPECT_EQ(s.shapes[0].kind, Shape::Kind::Sphere);
    EXPECT_EQ(s.shapes[1].kind, Shape::Kind::Disk);
    EXPECT_EQ(s.shapes[2].kind, Shape::Kind::Cylinder);
}

// ---- shapes ----

TEST(PbrtShapes, TriangleWindingFollowsNormalsOrReverseOrientation) {
    const std::string tri = "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]";  // CCW about +z
    const Loaded l = load_text("WorldBegin\n" + tri + "\n" + tri + " \"normal N\" [0 0 -1 0 0 -1 0 0 -1]\n" +
                               "ReverseOrientation\n" + tri + "\n" + tri +
                               " \"normal N\" [0 0 1 0 0 1 0 0 1]\n" + "Scale 1 1 -1\n" + tri + "\n");
    ASSERT_EQ(l.scene.shapes.size(), 5u);
    EXPECT_GT(tri_normal(l.scene.shapes[0].mesh, 0).z, 0);  // plain winding
    EXPECT_LT(tri_normal(l.scene.shapes[1].mesh, 0).z, 0);  // follows N
    EXPECT_LT(tri_normal(l.scene.shapes[2].mesh, 0).z, 0);  // reversed
    EXPECT_LT(tri_normal(l.scene.shapes[3].mesh, 0).z, 0);  // N flipped by ReverseOrientation
    EXPECT_EQ(l.scene.shapes[3].mesh.normals[0], Vec3(0, 0, -1));
    // Reverse XOR handedness swap: the mirrored triangle keeps its object-space orientation.
    EXPECT_GT(tri_normal(l.scene.shapes[4].mesh, 0).z, 0);
    for (const Shape& s : l.scene.shapes) {
        EXPECT_TRUE(s.to_world.is_identity());  // meshes are baked into world space
        EXPECT_FALSE(s.reverse_orientation);
    }
}

TEST(PbrtShapes, BilinearMeshBecomesTwoTrianglesPerPatch) {
    const Loaded l = load_text(
        "WorldBegin\nShape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 0] \"point2 uv\" [0 0 1 0 "
        "0 1 1 1]\n");
    const scene::TriangleMesh& m = l.scene.shapes[0].mesh;
    ASSERT_EQ(m.triangle_count(), 2u);
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 3, 0, 3, 2}));
    EXPECT_GT(tri_normal(m, 0).z, 0);
    EXPECT_GT(tri_normal(m, 1).z, 0);
    EXPECT_EQ(m.uvs[3], Vec2(1, 1));
}

TEST(PbrtShapes, PlyMeshIsReadRelativeToTheFileAndTransformed) {
    QuietLog quiet;
    PbrtTempDir dir;
    const scene::TriangleMesh quad = phos::testing::unit_quad();
    const std::string ply = dir.write("geo/quad.ply", "");
    phos::testing::write_ply(ply, quad, true);
    dir.write("geo/part.pbrt", "Translate 0 0 2\nShape \"plymesh\" \"string filename\" \"quad.ply\"\n");
    const std::string main = dir.write("main.pbrt", "WorldBegin\nInclude \"geo/part.pbrt\"\n");
    const scene::Scene s = load_pbrt(main);
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(s.shapes[0].mesh.triangle_count(), 2u);
    expect_vec(s.shapes[0].mesh.positions[2], {1, 1, 2});
}

// Compressed files: an Include of a .pbrt.gz file and a .ply.gz mesh load as their uncompressed
// forms do; a damaged stream is an error at the compressed file, with the places that led to it.
TEST(PbrtShapes, GzippedIncludesAndPlyMeshesLoadAsTheirUncompressedForms) {
    QuietLog quiet;
    PbrtTempDir dir;
    const scene::TriangleMesh quad = phos::testing::unit_quad();
    const std::string ply = dir.write("geo/quad.ply", "");
    phos::testing::write_ply(ply, quad, true);
    std::ifstream in(ply, std::ios::binary);
    const std::string ply_bytes((std::istreambuf_iterator<char>(in)), {});
    dir.write("geo/quad.ply.gz", phos::testing::gzip_bytes(ply_bytes));
    const std::string part = "Translate 0 0 2\nShape \"plymesh\" \"string filename\" \"quad.ply.gz\"\n";
    dir.write("geo/part.pbrt.gz", phos::testing::gzip_bytes(part));
    const std::string main = dir.write("main.pbrt", "WorldBegin\nInclude \"geo/part.pbrt.gz\"\n");
    const scene::Scene s = load_pbrt(main);
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(s.shapes[0].mesh.triangle_count(), 2u);
    expect_vec(s.shapes[0].mesh.positions[2], {1, 1, 2});

    const std::string gz = phos::testing::gzip_bytes(part);
    dir.write("geo/cut.pbrt.gz", gz.substr(0, gz.size() / 2));
    const std::string cut = dir.write("cut.pbrt", "WorldBegin\n\nInclude \"geo/cut.pbrt.gz\"\n");
    expect_pbrt_error(cut, 0, 0, "corrupt gzip stream", dir.file("geo/cut.pbrt.gz"));
    try {
        load_pbrt(cut);
    } catch (const ParseError& e) {
        ASSERT_EQ(e.included_from.size(), 1u);
        EXPECT_NE(e.included_from[0].find("cut.pbrt:3:1"), std::string::npos) << e.included_from[0];
    }
    dir.write("geo/cut.ply.gz", gz.substr(0, 10));
    const std::string cut_mesh =
        dir.write("cut_mesh.pbrt", "WorldBegin\nShape \"plymesh\" \"string filename\" \"geo/cut.ply.gz\"\n");
    expect_pbrt_error(cut_mesh, 0, 0, "corrupt gzip stream", dir.file("geo/cut.ply.gz"));
}

TEST(PbrtShapes, QuadricsKeepTheirTransform) {
    const Loaded l = load_text(
        "WorldBegin\nTranslate 1 2 3\nShape \"disk\" \"float height\" 0.5 \"float radius\" 2 \"float "
        "innerradius\" 1\n"
        "ReverseOrientation\nShape \"cylinder\" \"float radius\" 0.3 \"float zmin\" -1 \"float zmax\" 3\n"
        "Shape \"sphere\" \"float zmax\" 0.5\n");
    ASSERT_EQ(l.scene.shapes.size(), 3u);
    const Shape& d = l.scene.shapes[0];
    EXPECT_EQ(d.kind, Shape::Kind::Disk);
    expect_vec(d.to_world.point(d.center), {1, 2, 3.5f});
    EXPECT_EQ(d.normal, Vec3(0, 0, 1));
    EXPECT_FLOAT_EQ(d.inner_radius, 1.0f);
    const Shape& c = l.scene.shapes[1];
    EXPECT_EQ(c.kind, Shape::Kind::Cylinder);
    EXPECT_FALSE(c.capped);
    EXPECT_FLOAT_EQ(c.height, 4.0f);
    expect_vec(c.center, {0, 0, 1});
    EXPECT_TRUE(c.reverse_orientation);
    // A partial sphere: pbrt's +z pole, its z range clamped to the radius, phimax 360 degrees.
    const Shape& s = l.scene.shapes[2];
    EXPECT_TRUE(s.partial);
    EXPECT_EQ(s.axis, Vec3(0, 0, 1));
    EXPECT_FLOAT_EQ(s.z_min, -1.0f);
    EXPECT_FLOAT_EQ(s.z_max, 0.5f);
    EXPECT_FLOAT_EQ(s.phi_max, 2 * kPi);
    EXPECT_EQ(l.warnings, 0);
}

// ---- materials ----

const scene::Material& material_of(const Loaded& l, size_t shape) {
    return l.scene.materials[size_t(l.scene.shapes[shape].material)];
}

TEST(PbrtMaterials, ConductorsDielectricsAndRoughness) {
    const Loaded l = load_text(
        "WorldBegin\nMaterial \"conductor\" \"spectrum eta\" \"metal-Au-eta\" \"spectrum k\" \"metal-Au-k\" "
        "\"float roughness\" 0.01\nShape \"sphere\"\n"
        "Material \"conductor\"\nShape \"sphere\"\n"
        "Material \"conductor\" \"rgb eta\" [0.2 0.9 1.1] \"rgb k\" [3.9 2.4 2.1] \"float uroughness\" 0.04 "
        "\"float vroughness\" 0.04 \"bool remaproughness\" false\nShape \"sphere\"\n"
        "Material \"dielectric\" \"spectrum eta\" \"glass-BK7\" \"float roughness\" 0.25\nShape \"sphere\"\n"
        "Material \"thindielectric\" \"float eta\" 1.33\nShape \"sphere\"\n");
    const scene::Material& au = material_of(l, 0);
    EXPECT_TRUE(au.conductor);
    EXPECT_EQ(au.specular, Rgb(1.0f));
    EXPECT_EQ(au.conductor_eta, *pbrt::named_spectrum_rgb("metal-Au-eta", pbrt::SpectrumUse::Unbounded));
    EXPECT_GT(au.conductor_k.r, au.conductor_k.b);
    // Trowbridge-Reitz roughness as given, remapped (alpha = sqrt(0.01) = 0.1) when shading.
    EXPECT_TRUE(au.microfacet);
    EXPECT_TRUE(au.remap_roughness);
    EXPECT_FLOAT_EQ(au.roughness_u, 0.01f);
    EXPECT_FLOAT_EQ(au.roughness_v, 0.01f);
    const scene::Material& cu = material_of(l, 1);  // defaults: copper, smooth
    EXPECT_EQ(cu.conductor_eta, *pbrt::named_spectrum_rgb("metal-Cu-eta", pbrt::SpectrumUse::Unbounded));
    EXPECT_TRUE(cu.microfacet);
    EXPECT_EQ(cu.roughness_u, 0.0f);
    const scene::Material& rgb = material_of(l, 2);
    EXPECT_EQ(rgb.conductor_eta, Rgb(0.2f, 0.9f, 1.1f));
    EXPECT_FALSE(rgb.remap_roughness);
    EXPECT_FLOAT_EQ(rgb.roughness_u, 0.04f);
    const scene::Material& glass = material_of(l, 3);
    EXPECT_NEAR(glass.ior, 1.5168f, 1e-4f);
    EXPECT_EQ(glass.transmission, Rgb(1.0f));
    EXPECT_TRUE(glass.microfacet);
    EXPECT_FLOAT_EQ(glass.roughness_u, 0.25f);
    EXPECT_FLOAT_EQ(glass.roughness_v, 0.25f);
    EXPECT_FALSE(glass.thin);
    EXPECT_TRUE(material_of(l, 4).thin);
    EXPECT_FLOAT_EQ(material_of(l, 4).ior, 1.33f);
}

TEST(PbrtMaterials, NamedMaterialsAndApproximations) {
    const Loaded l = load_text(
        "WorldBegin\nMakeNamedMaterial \"red\" \"string type\" \"diffuse\" \"rgb reflectance\" [0.7 0.1 "
        "0.1]\n"
        "MakeNamedMaterial \"mix\" \"string type\" \"mix\" \"string materials\" [\"red\" \"red\"] \"float "
        "amount\" 0.3\n"
        "NamedMaterial \"mix\"\nShape \"sphere\"\n"
        "Material \"coateddiffuse\" \"rgb reflectance\" [0.5 0.5 0.5] \"float roughness\" 0\nShape "
        "\"sphere\"\n"
        "Material \"diffusetransmission\" \"rgb transmittance\" [0.1 0.2 0.3]\nShape \"sphere\"\n"
        "Material \"interface\"\nShape \"sphere\"\n"
        "NamedMaterial \"red\"\nShape \"sphere\"\n");
    const scene::Material& mix = material_of(l, 0);  // a mix of "red" with itself
    ASSERT_TRUE(mix.is_mix());
    EXPECT_EQ(l.scene.materials[size_t(mix.mix_a)].diffuse, Rgb(0.7f, 0.1f, 0.1f));
    EXPECT_EQ(mix.mix_b, mix.mix_a);
    EXPECT_FLOAT_EQ(mix.mix_amount, 0.3f);
    const scene::Material& coated = material_of(l, 1);
    EXPECT_TRUE(coated.layered);  // pbrt-v4's layered BSDF with its defaults
    EXPECT_FALSE(coated.layered_conductor_base);
    EXPECT_EQ(coated.diffuse, Rgb(0.5f));
    EXPECT_FLOAT_EQ(coated.coat_eta, 1.5f);
    EXPECT_EQ(coated.roughness_u, 0.0f);
    EXPECT_FLOAT_EQ(coated.layer_thickness, 0.01f);
    EXPECT_EQ(coated.layer_albedo, Rgb(0.0f));
    EXPECT_EQ(coated.layer_max_depth, 10);
    EXPECT_EQ(coated.layer_samples, 1);
    EXPECT_EQ(material_of(l, 2).diffuse_transmission, Rgb(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(material_of(l, 2).diffuse, Rgb(0.25f));
    EXPECT_TRUE(material_of(l, 3).interface_only);
    EXPECT_EQ(material_of(l, 4).name, "red");
    EXPECT_EQ(l.warnings, 0);  // mix and coateddiffuse are as pbrt
}

// ---- textures ----

// A 2x2 linear PFM: top row red, green; bottom row blue, white.
std::string pfm_2x2() {
    std::string s = "PF\n2 2\n-1.0\n";
    const float rows[2][6] = {{0, 0, 1, 1, 1, 1}, {1, 0, 0, 0, 1, 0}};  // bottom row first
    for (const auto& r : rows) s.append(reinterpret_cast<const char*>(r), sizeof(r));
    return s;
}

TEST(PbrtTextures, ImageCheckerboardScaleConstant) {
    QuietLog quiet;
    PbrtTempDir dir;
    dir.write("tex/img.pfm", pfm_2x2());
    const std::string path = dir.write(
        "t.pbrt",
        "WorldBegin\nTexture \"img\" \"spectrum\" \"imagemap\" \"string filename\" \"tex/img.pfm\" \"float "
        "uscale\" 2 "
        "\"string wrap\" \"clamp\"\nTexture \"half\" \"float\" \"constant\" \"float value\" 0.5\n"
        "Texture \"checks\" \"spectrum\" \"checkerboard\" \"texture tex1\" \"img\" \"rgb tex2\" [0 0 1] "
        "\"float vscale\" "
        "4\nTexture \"dim\" \"spectrum\" \"scale\" \"texture tex\" \"checks\" \"texture scale\" \"half\"\n"
        "Material \"diffuse\" \"texture reflectance\" \"dim\"\nShape \"sphere\"\n");
    const scene::Scene s = load_pbrt(path);
    ASSERT_EQ(s.shapes.size(), 1u);
    const scene::Material& m = s.materials[size_t(s.shapes[0].material)];
    ASSERT_GE(m.diffuse_texture, 0);
    EXPECT_EQ(m.diffuse, Rgb(1.0f));
    const scene::Texture& dim = s.textures[size_t(m.diffuse_texture)];
    EXPECT_EQ(dim.kind, scene::Texture::Kind::Scale);
    ASSERT_GE(dim.tex2, 0);
    EXPECT_EQ(s.textures[size_t(dim.tex2)].value, Rgb(0.5f));
    const scene::Texture& checks = s.textures[size_t(dim.tex1)];
    EXPECT_EQ(checks.kind, scene::Texture::Kind::Checkerboard);
    EXPECT_FLOAT_EQ(checks.v_scale, 4.0f);
    EXPECT_EQ(s.textures[size_t(checks.tex2)].value, Rgb(0, 0, 1));
    const scene::Texture& img = s.textures[size_t(checks.tex1)];
    EXPECT_EQ(img.kind, scene::Texture::Kind::Image);
    EXPECT_EQ(img.wrap, scene::Texture::Wrap::Clamp);
    EXPECT_FLOAT_EQ(img.u_scale, 2.0f);
    ASSERT_TRUE(img.image);
    EXPECT_EQ(img.image->width, 2);
    EXPECT_EQ(img.image->at(0, 0), Rgb(1, 0, 0));  // row 0 is the top
    EXPECT_EQ(img.image->at(1, 1), Rgb(1, 1, 1));
}

TEST(PbrtTextures, MissingImageIsAParseErrorAtTheFilename) {
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string path = dir.write(
        "t.pbrt", "WorldBegin\nTexture \"img\" \"spectrum\" \"imagemap\" \"string filename\" \"nope.png\"\n");
    expect_pbrt_error(path, 2, 37, "imagemap", path);
}

// ---- lights and spectra ----

TEST(PbrtLights, PointSpotDistantInfiniteAndPower) {
    const Loaded l = load_text(
        "WorldBegin\nLightSource \"point\" \"point3 from\" [1 2 3] \"float power\" 100\n"
        "Translate 0 1 0\nLightSource \"spot\" \"point3 from\" [0 0 0] \"point3 to\" [0 -1 0] \"float "
        "coneangle\" 30 "
        "\"float conedeltaangle\" 10 \"rgb I\" [2 2 2] \"float scale\" 3\n"
        "LightSource \"distant\" \"point3 from\" [0 0 0] \"point3 to\" [0 0 -1] \"rgb L\" [1 1 1] \"float "
        "illuminance\" 5\nLightSource \"infinite\" \"rgb L\" [0.1 0.2 0.3]\n");
    ASSERT_EQ(l.scene.lights.size(), 4u);
    const Light& p = l.scene.lights[0];
    EXPECT_EQ(p.kind, Light::Kind::Point);
    EXPECT_NEAR(p.color.g * 4 * kPi, 100.0f, 1e-3f);  // 4 pi I = power
    expect_vec(p.position, {1, 2, 3});
    const Light& s = l.scene.lights[1];
    EXPECT_EQ(s.kind, Light::Kind::Spot);
    EXPECT_EQ(s.color, Rgb(6.0f));
    expect_vec(s.position, {0, 1, 0});
    expect_vec(s.direction, {0, -1, 0});
    EXPECT_NEAR(s.cutoff, 30 * kPi / 180, 1e-6f);
    EXPECT_NEAR(s.falloff_start, 20 * kPi / 180, 1e-6f);
    const Light& d = l.scene.lights[2];
    EXPECT_EQ(d.kind, Light::Kind::Directional);
    expect_vec(d.direction, {0, 0, -1});
    EXPECT_EQ(d.color, Rgb(5.0f));
    EXPECT_EQ(l.scene.lights[3].kind, Light::Kind::Infinite);
    EXPECT_EQ(l.scene.lights[3].color, Rgb(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(l.scene.lights[3].texture, -1);
}

TEST(PbrtLights, AreaLightPowerScaleAndTwoSided) {
    const std::string quad =
        "Shape \"trianglemesh\" \"point3 P\" [0 0 0 0.5 0 0 0.5 0 0.1 0 0 0.1] \"integer "
        "indices\" [0 1 2 0 2 3]\n";  // area 0.05
    const Loaded l =
        load_text("WorldBegin\nAttributeBegin\nAreaLightSource \"diffuse\" \"float power\" 10\n" + quad +
                  "AreaLightSource \"diffuse\" \"rgb L\" [1 2 3] \"float scale\" 2 \"bool twosided\" true\n" +
                  quad + "AttributeEnd\n" + quad);
    ASSERT_EQ(l.scene.lights.size(), 2u);
    EXPECT_NEAR(l.scene.lights[0].color.r * kPi * 0.05f, 10.0f, 1e-3f);
    EXPECT_EQ(l.scene.lights[1].color, Rgb(2, 4, 6));
    EXPECT_TRUE(l.scene.lights[1].two_sided);
    EXPECT_EQ(l.scene.shapes.size(), 3u);
    EXPECT_EQ(l.scene.shapes[2].area_light, -1);  // AttributeEnd ended the emission
    EXPECT_EQ(l.scene.shapes[size_t(l.scene.lights[1].shape)].area_light, 1);
}

TEST(PbrtSpectra, BlackbodyAndSampledSpectra) {
    const Rgb d65 = pbrt::blackbody_rgb(6504.0f);
    EXPECT_NEAR(d65.luminance(), 1.0f, 0.02f);
    EXPECT_NEAR(d65.r, 1.0f, 0.1f);
    EXPECT_NEAR(d65.b, 1.0f, 0.1f);
    const Rgb warm = pbrt::blackbody_rgb(2700.0f);
    EXPECT_GT(warm.r, 1.5f * warm.b);
    const Rgb flat = pbrt::sampled_spectrum_rgb({400, 700}, {0.5f, 0.5f}, pbrt::SpectrumUse::Albedo);
    EXPECT_NEAR(flat.r, 0.5f, 1e-4f);
    EXPECT_NEAR(flat.g, 0.5f, 1e-4f);
    EXPECT_NEAR(flat.b, 0.5f, 1e-4f);
    const Rgb red = pbrt::sampled_spectrum_rgb({380, 590, 600, 780}, {0, 0, 1, 1}, pbrt::SpectrumUse::Albedo);
    EXPECT_GT(red.r, 0.5f);
    EXPECT_LT(red.b, 0.05f);
    // CIE y peaks near 555 nm
    EXPECT_GT(spectrum::cie_xyz(555).y, 0.95f);
    EXPECT_LT(spectrum::cie_xyz(450).y, 0.1f);

    const Loaded l = load_text(
        "WorldBegin\nLightSource \"point\" \"blackbody I\" 3000\nLightSource \"point\" \"spectrum I\" "
        "\"stdillum-D65\" "
        "\"float scale\" 4\nMaterial \"diffuse\" \"spectrum reflectance\" [400 0.25 500 0.25 700 "
        "0.25]\nShape "
        "\"sphere\"\n");
    EXPECT_NEAR(l.scene.lights[0].color.luminance(), 1.0f, 0.02f);  // pbrt: spectra normalised to 1 nit
    EXPECT_GT(l.scene.lights[0].color.r, l.scene.lights[0].color.b);
    EXPECT_EQ(l.scene.lights[1].color, Rgb(4.0f));
    EXPECT_NEAR(material_of(l, 0).diffuse.g, 0.25f, 1e-4f);
}

// ---- media ----

TEST(PbrtMedia, HomogeneousGridInterfaceAndCameraMedium) {
    const Loaded l = load_text(
        "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0.1 0.1 0.1] \"rgb "
        "sigma_s\" [1 2 3] "
        "\"float scale\" 2 \"float g\" 0.3\nMediumInterface \"\" \"fog\"\n" +
        kView +
        "WorldBegin\nMakeNamedMedium \"milk\" \"string type\" \"homogeneous\" \"string preset\" "
        "\"Skimmilk\"\n"
        "MakeNamedMedium \"grid\" \"string type\" \"uniformgrid\" \"integer nx\" 2 \"integer ny\" 1 "
        "\"integer nz\" 1 "
        "\"float density\" [0.5 1] \"point3 p1\" [2 1 1]\nMediumInterface \"milk\" \"grid\"\nShape "
        "\"sphere\"\n");
    ASSERT_EQ(l.scene.media.size(), 3u);
    const scene::Medium& fog = l.scene.media[0];
    EXPECT_EQ(fog.sigma_s, Rgb(1, 2, 3));
    EXPECT_FLOAT_EQ(fog.scale, 2.0f);
    EXPECT_FLOAT_EQ(fog.g, 0.3f);
    EXPECT_EQ(l.scene.camera_medium, 0);
    EXPECT_EQ(l.scene.media[1].sigma_s, Rgb(0.70f, 1.22f, 1.90f));
    const scene::Medium& grid = l.scene.media[2];
    EXPECT_EQ(grid.kind, scene::Medium::Kind::UniformGrid);
    EXPECT_EQ(grid.density, (std::vector<float>{0.5f, 1.0f}));
    EXPECT_EQ(grid.p1, Vec3(2, 1, 1));
    EXPECT_EQ(l.scene.shapes[0].media.inside, 1);
    EXPECT_EQ(l.scene.shapes[0].media.outside, 2);
}

// A light sits in a medium by declaration only under a MediumInterface statement (in effect in its
// attribute scope); elsewhere the renderer places it (shading/light_media.h). Each light records
// where it was defined.
TEST(PbrtMedia, LightsRecordWhetherTheirMediumIsDeclared) {
    const Loaded l = load_text(
        kView +
        "WorldBegin\nMakeNamedMedium \"smoke\" \"string type\" \"homogeneous\"\n"
        "LightSource \"point\" \"rgb I\" [1 1 1]\n"
        "AttributeBegin\nMediumInterface \"smoke\" \"smoke\"\nLightSource \"point\" \"rgb I\" [1 1 1]\n"
        "AreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\nShape \"sphere\"\nAttributeEnd\n"
        "AreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\nShape \"sphere\"\n");
    ASSERT_EQ(l.scene.lights.size(), 4u);
    const std::vector<bool> declared = {false, true, true, false};
    const std::vector<int> medium = {-1, 0, 0, -1};
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(l.scene.lights[i].medium_declared, declared[i]) << i;
        EXPECT_EQ(l.scene.lights[i].medium, medium[i]) << i;
    }
    EXPECT_NE(l.scene.lights[0].origin.find(":6:1"), std::string::npos) << l.scene.lights[0].origin;
    EXPECT_NE(l.scene.lights[2].origin.find(":11:1"), std::string::npos) << l.scene.lights[2].origin;
}

// Emission: "Le" with a scalar "Lescale" (any medium) or one factor per cell (uniformgrid).
TEST(PbrtMedia, EmissionAndLescale) {
    const Loaded l = load_text(
        kView +
        "WorldBegin\nMakeNamedMedium \"a\" \"string type\" \"homogeneous\" \"rgb Le\" [1 2 3]\n"
        "MakeNamedMedium \"b\" \"string type\" \"homogeneous\" \"rgb Le\" [1 2 3] \"float Lescale\" 2\n"
        "MakeNamedMedium \"c\" \"string type\" \"uniformgrid\" \"integer nx\" 2 \"float density\" [1 1] "
        "\"rgb Le\" [1 2 3] \"float Lescale\" [0.5 4]\n");
    ASSERT_EQ(l.scene.media.size(), 3u);
    const Rgb le = l.scene.media[0].emission;
    EXPECT_GT(le.g, 0.0f);
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(l.scene.media[1].emission[c], 2 * le[c]);
    EXPECT_EQ(l.scene.media[2].emission, le);
    EXPECT_EQ(l.scene.media[2].emission_scale, (std::vector<float>{0.5f, 4.0f}));
    EXPECT_TRUE(l.scene.media[0].emission_scale.empty());
}

TEST(PbrtMedia, NanovdbMediumReadsVdbAndNvdbFiles) {
    QuietLog quiet;
    PbrtTempDir dir;
    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.5));
    grid->tree().setValue(openvdb::Coord(1, 2, 3), 3.0f);
    grid->tree().setValue(openvdb::Coord(2, 2, 3), 1.5f);
    std::filesystem::create_directories(dir.path() / "vol");
    openvdb::io::File(dir.file("vol/smoke.vdb")).write({grid});
    auto handle = nanovdb::openToNanoVDB(*grid);
    nanovdb::io::writeGrid(dir.file("vol/smoke.nvdb"), handle);
    const std::string path = dir.write(
        "scene.pbrt",
        "WorldBegin\nAttributeBegin\nTranslate 1 2 3\n"
        "MakeNamedMedium \"smoke\" \"string type\" \"nanovdb\" \"string filename\" \"vol/smoke.vdb\"\n"
        "  \"float scale\" 4 \"rgb sigma_a\" [1 1 1] \"rgb sigma_s\" [2 2 2] \"float g\" 0.5 "
        "\"rgb Le\" [1 0 0] \"float Lescale\" 2\nAttributeEnd\n"
        "MakeNamedMedium \"nano\" \"string type\" \"nanovdb\" \"string filename\" \"vol/smoke.nvdb\"\n"
        "MakeNamedMedium \"syn\" \"string type\" \"openvdb\" \"string filename\" \"vol/smoke.vdb\"\n"
        "MediumInterface \"smoke\" \"\"\nShape \"sphere\"\n");
    const scene::Scene sc = load_pbrt(path);
    ASSERT_EQ(sc.media.size(), 3u);
    for (const scene::Medium& m : sc.media) {
        EXPECT_EQ(m.kind, scene::Medium::Kind::Sparse) << m.name;
        ASSERT_NE(m.sparse.buffer, nullptr) << m.name;
        EXPECT_GT(m.sparse.bytes, 0u);
        const auto* g = static_cast<const nanovdb::FloatGrid*>(m.sparse.buffer.get());
        EXPECT_EQ(g->gridType(), nanovdb::GridType::Float);
        EXPECT_EQ(g->activeVoxelCount(), 2u);
        EXPECT_FLOAT_EQ(g->tree().getValue(nanovdb::Coord(1, 2, 3)), 3.0f);
        EXPECT_DOUBLE_EQ(g->voxelSize()[0], 0.5);
    }
    const scene::Medium& smoke = sc.media[0];
    EXPECT_NE(smoke.sparse.file.find("smoke.vdb"), std::string::npos);
    EXPECT_NE(sc.media[1].sparse.file.find("smoke.nvdb"), std::string::npos);
    EXPECT_FLOAT_EQ(smoke.scale, 4.0f);
    EXPECT_EQ(smoke.sigma_s, Rgb(2.0f));
    EXPECT_FLOAT_EQ(smoke.g, 0.5f);
    // pbrt-v4's nanovdb media take their emission from a temperature grid only: "Le" warns and is
    // not rendered (phos has no temperature grids).
    EXPECT_EQ(smoke.emission, Rgb(0.0f));
    expect_vec(smoke.to_world.point(Vec3(0)), Vec3(1, 2, 3));
    EXPECT_EQ(sc.shapes[0].media.inside, 0);
}

}  // namespace
}  // namespace phos::io::test
