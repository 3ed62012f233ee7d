// The pbrt loader's Texture directive for pbrt-v4's texture classes: each class read with its
// parameters (and float/spectrum variants), evaluated where its closed form is simple; the CTM at
// the directive as texture space; the 2D mappings; and bad input refused at file:line:col.
#include <gtest/gtest.h>

#include <cmath>

#include "core/log.h"
#include "pbrt_test_util.h"
#include "scene/texture_eval.h"

namespace phos::io::test {
namespace {

struct Loaded {
    scene::Scene scene;
    int warnings = 0;
};

Loaded load_text(const std::string& text) {
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string path = dir.write("scene.pbrt", text);
    const int before = log::warning_count();
    Loaded l{load_pbrt(path), 0};
    l.warnings = log::warning_count() - before;
    return l;
}

// The diffuse texture of the (only) shape's material.
int reflectance_texture(const scene::Scene& s) {
    const int t = s.materials.at(size_t(s.shapes.at(0).material)).diffuse_texture;
    EXPECT_GE(t, 0);
    return t;
}

scene::TextureContext at(Vec3 p, Vec2 uv = {0, 0}, Vec3 n = {0, 0, 1}) {
    scene::TextureContext c;
    c.p = p;
    c.uv = uv;
    c.n = n;
    return c;
}

void expect_rgb(Rgb got, Rgb want, float eps = 1e-5f) {
    EXPECT_NEAR(got.r, want.r, eps);
    EXPECT_NEAR(got.g, want.g, eps);
    EXPECT_NEAR(got.b, want.b, eps);
}

// A scene whose sphere's reflectance is texture "t", defined by `texture` (after `before`).
std::string with_texture(const std::string& texture, const std::string& before = "") {
    return "WorldBegin\n" + before + texture +
           "\nMaterial \"diffuse\" \"texture reflectance\" \"t\"\nShape \"sphere\"\n";
}

TEST(PbrtTextureClasses, MixWithATexturedAmount) {
    const Loaded l =
        load_text(with_texture("Texture \"t\" \"spectrum\" \"mix\" \"rgb tex1\" [1 0 0] \"rgb tex2\" [0 0 1] "
                               "\"texture amount\" \"a\"",
                               "Texture \"a\" \"float\" \"constant\" \"float value\" 0.25\n"));
    EXPECT_EQ(l.warnings, 0);
    const int t = reflectance_texture(l.scene);
    EXPECT_EQ(l.scene.textures[size_t(t)].kind, scene::Texture::Kind::Mix);
    expect_rgb(scene::eval_texture(l.scene, t, at({})), Rgb(0.75f, 0, 0.25f));
    // Float mix: defaults tex1 0, tex2 1, amount 0.5.
    const Loaded f = load_text(with_texture("Texture \"t\" \"float\" \"mix\""));
    expect_rgb(scene::eval_texture(f.scene, reflectance_texture(f.scene), at({})), Rgb(0.5f));
}

TEST(PbrtTextureClasses, DirectionMixTakesItsDirectionThroughTheCtm) {
    // "dir" (1 0 0) under a 90-degree rotation about z is world +y.
    const Loaded l =
        load_text(with_texture("AttributeBegin\nRotate 90 0 0 1\nTexture \"t\" \"spectrum\" \"directionmix\" "
                               "\"vector3 dir\" [1 0 0] "
                               "\"rgb tex1\" [1 0 0] \"rgb tex2\" [0 1 0]\nAttributeEnd"));
    EXPECT_EQ(l.warnings, 0);
    const int t = reflectance_texture(l.scene);
    expect_rgb(scene::eval_texture(l.scene, t, at({}, {}, {0, 1, 0})), Rgb(1, 0, 0));
    expect_rgb(scene::eval_texture(l.scene, t, at({}, {}, {1, 0, 0})), Rgb(0, 1, 0));
}

TEST(PbrtTextureClasses, BilerpFloatAndSpectrum) {
    const Loaded l = load_text(with_texture(
        "Texture \"t\" \"spectrum\" \"bilerp\" \"rgb v00\" [1 0 0] \"rgb v01\" [0 1 0] \"rgb v10\" [0 0 1] "
        "\"rgb v11\" [1 1 1] \"float uscale\" 2"));
    EXPECT_EQ(l.warnings, 0);
    const int t = reflectance_texture(l.scene);
    expect_rgb(scene::eval_texture(l.scene, t, at({}, {0.5f, 0})), Rgb(0, 0, 1));  // s = 2u = 1
    expect_rgb(scene::eval_texture(l.scene, t, at({}, {0.25f, 0.5f})), Rgb(0.5f));
    // Float defaults: v00 0, v01 1, v10 0, v11 1: the value is t.
    const Loaded f = load_text(with_texture("Texture \"t\" \"float\" \"bilerp\" \"float v10\" 0.5"));
    expect_rgb(scene::eval_texture(f.scene, reflectance_texture(f.scene), at({}, {1, 0.5f})), Rgb(0.75f));
}

TEST(PbrtTextureClasses, PbrtV3UvTextureIsTheFractionalMapping) {
    const Loaded l = load_text(with_texture("Texture \"t\" \"color\" \"uv\" \"float uscale\" 3"));
    EXPECT_EQ(l.warnings, 0);
    const int t = reflectance_texture(l.scene);
    expect_rgb(scene::eval_texture(l.scene, t, at({}, {0.1f, 0.25f})), Rgb(0.3f, 0.25f, 0));
    expect_rgb(scene::eval_texture(l.scene, t, at({}, {0.5f, 0.75f})), Rgb(0.5f, 0.75f, 0));  // s = 1.5
}

TEST(PbrtTextureClasses, Checkerboard3DInTheCtmSpace) {
    const Loaded l = load_text(with_texture(
        "AttributeBegin\nScale 2 2 2\nTexture \"t\" \"spectrum\" \"checkerboard\" \"integer dimension\" 3 "
        "\"rgb tex1\" [1 1 1] \"rgb tex2\" [0 0 0]\nAttributeEnd"));
    EXPECT_EQ(l.warnings, 0);
    const int t = reflectance_texture(l.scene);
    EXPECT_EQ(l.scene.textures[size_t(t)].dimension, 3);
    expect_rgb(scene::eval_texture(l.scene, t, at({1.5f, 1.5f, 1.5f})), Rgb(1.0f));  // cell (0, 0, 0)
    expect_rgb(scene::eval_texture(l.scene, t, at({2.5f, 1.5f, 1.5f})), Rgb(0.0f));  // cell (1, 0, 0)
    expect_rgb(scene::eval_texture(l.scene, t, at({2.5f, 2.5f, 1.5f})), Rgb(1.0f));
}

TEST(PbrtTextureClasses, DotsShowOutsideInsideTheDots) {
    // pbrt-v4 swaps the two: a dot shows "outside", the rest "inside".
    const Loaded l = load_text(
        with_texture("Texture \"t\" \"float\" \"dots\" \"float inside\" 0.25 \"float outside\" 0.75"));
    EXPECT_EQ(l.warnings, 0);
    const scene::Texture& d = l.scene.textures[size_t(reflectance_texture(l.scene))];
    EXPECT_EQ(d.kind, scene::Texture::Kind::Dots);
    EXPECT_EQ(l.scene.textures[size_t(d.tex1)].value, Rgb(0.75f));  // inside a dot
    EXPECT_EQ(l.scene.textures[size_t(d.tex2)].value, Rgb(0.25f));
}

TEST(PbrtTextureClasses, NoiseTexturesAndMarble) {
    const Loaded l = load_text(
        "WorldBegin\nTranslate 1 0 0\n"
        "Texture \"f\" \"float\" \"fbm\" \"integer octaves\" 3 \"float roughness\" 0.25\n"
        "Texture \"w\" \"float\" \"wrinkled\"\nTexture \"y\" \"float\" \"windy\"\n"
        "Texture \"m\" \"spectrum\" \"marble\" \"integer octaves\" 2 \"float roughness\" 0.4 \"float scale\" "
        "3 "
        "\"float variation\" 0.1\n"
        "Texture \"g\" \"spectrum\" \"fbm\"\n"  // pbrt-v3 allowed spectrum noise textures: grey
        "Material \"diffuse\" \"texture reflectance\" \"m\"\nShape \"sphere\"\n");
    EXPECT_EQ(l.warnings, 0);
    const auto& tex = l.scene.textures;
    ASSERT_EQ(tex.size(), 5u);
    EXPECT_EQ(tex[0].kind, scene::Texture::Kind::FBm);
    EXPECT_EQ(tex[0].octaves, 3);
    EXPECT_FLOAT_EQ(tex[0].roughness, 0.25f);
    EXPECT_EQ(tex[1].kind, scene::Texture::Kind::Wrinkled);
    EXPECT_EQ(tex[1].octaves, 8);  // pbrt's defaults
    EXPECT_FLOAT_EQ(tex[1].roughness, 0.5f);
    EXPECT_EQ(tex[2].kind, scene::Texture::Kind::Windy);
    EXPECT_EQ(tex[3].kind, scene::Texture::Kind::Marble);
    EXPECT_EQ(tex[3].octaves, 2);
    EXPECT_FLOAT_EQ(tex[3].marble_scale, 3.0f);
    EXPECT_FLOAT_EQ(tex[3].variation, 0.1f);
    EXPECT_EQ(tex[4].kind, scene::Texture::Kind::FBm);
    // Texture space is the CTM's: world (1, 0, 0) is its origin, where the noise is 0.
    expect_rgb(scene::eval_texture(l.scene, 0, at({1, 0, 0})), Rgb(0.0f));
    EXPECT_NE(scene::eval_texture(l.scene, 0, at({1.3f, 0.2f, 0.7f})).r, 0.0f);
}

TEST(PbrtTextureClasses, MappingsAndTheirParameters) {
    const Loaded l = load_text(
        "WorldBegin\nTranslate 0 0 1\n"
        "Texture \"s\" \"float\" \"bilerp\" \"string mapping\" \"spherical\"\n"
        "Texture \"c\" \"float\" \"bilerp\" \"string mapping\" \"cylindrical\"\n"
        "Texture \"p\" \"float\" \"bilerp\" \"string mapping\" \"planar\" \"vector3 v1\" [0 1 0] "
        "\"vector3 v2\" [0 0 1] \"float udelta\" 0.5 \"float vdelta\" 0.25\n"
        "Texture \"u\" \"float\" \"bilerp\" \"float uscale\" 2 \"float vscale\" 3 \"float udelta\" 1 "
        "\"float vdelta\" -1\n");
    EXPECT_EQ(l.warnings, 0);
    const auto& tex = l.scene.textures;
    ASSERT_EQ(tex.size(), 4u);
    EXPECT_EQ(tex[0].mapping, scene::Texture::Mapping::Spherical);
    EXPECT_EQ(tex[1].mapping, scene::Texture::Mapping::Cylindrical);
    EXPECT_EQ(tex[2].mapping, scene::Texture::Mapping::Planar);
    EXPECT_EQ(tex[3].mapping, scene::Texture::Mapping::UV);
    // Spherical about the texture-space origin, world (0, 0, 1): world (1, 0, 1) is (1/2, 0).
    const Vec2 sph = scene::map_2d(tex[0], at({1, 0, 1}));
    EXPECT_NEAR(sph.x, 0.5f, 1e-5f);
    EXPECT_NEAR(sph.y, 0.0f, 1e-5f);
    const Vec2 pl = scene::map_2d(tex[2], at({7, 2, 4}));  // texture space (7, 2, 3)
    EXPECT_NEAR(pl.x, 2.5f, 1e-5f);
    EXPECT_NEAR(pl.y, 3.25f, 1e-5f);
    const Vec2 uv = scene::map_2d(tex[3], at({}, {0.5f, 0.5f}));
    EXPECT_NEAR(uv.x, 2.0f, 1e-6f);
    EXPECT_NEAR(uv.y, 0.5f, 1e-6f);
    // A mapping reads only its own parameters: uscale on a spherical mapping is unused (a warning).
    EXPECT_EQ(load_text("WorldBegin\nTexture \"s\" \"float\" \"dots\" \"string mapping\" \"spherical\" "
                        "\"float uscale\" 2\n")
                  .warnings,
              1);
}

TEST(PbrtTextureClasses, PtexWarnsAndIsAConstant) {
    const Loaded l =
        load_text(with_texture("Texture \"t\" \"spectrum\" \"ptex\" \"string filename\" \"x.ptx\""));
    EXPECT_EQ(l.warnings, 1);
    expect_rgb(scene::eval_texture(l.scene, reflectance_texture(l.scene), at({})), Rgb(0.5f));
}

TEST(PbrtTextureClasses, BadInputIsRefusedWhereItIs) {
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string w = "WorldBegin\n";
    // Refused at line 2, at the column where `at` starts in `texture` (the directive when empty).
    const auto expect_error = [&](const std::string& texture, const std::string& at,
                                  const std::string& message) {
        const std::string path = dir.write("bad.pbrt", w + texture + "\n");
        const int col = at.empty() ? 1 : int(texture.find(at)) + 1;
        expect_pbrt_error(path, 2, col, message, path);
    };
    expect_error("Texture \"t\" \"float\" \"fbm\" \"integer octaves\" -1", "\"integer octaves\"", "octaves");
    expect_error("Texture \"t\" \"float\" \"dots\" \"string mapping\" \"sphere\"", "\"string mapping\"",
                 "unknown mapping");
    expect_error("Texture \"t\" \"float\" \"checkerboard\" \"integer dimension\" 4", "\"integer dimension\"",
                 "dimension");
    expect_error("Texture \"t\" \"float\" \"mix\" \"texture tex1\" \"nope\"", "\"texture tex1\"",
                 "unknown texture");
    expect_error("Texture \"t\" \"float\" \"mix\" \"texture amount\" \"nope\"", "\"texture amount\"",
                 "unknown texture");
    expect_error("Texture \"t\" \"float\" \"directionmix\" \"vector3 dir\" [0 0 0]", "\"vector3 dir\"",
                 "dir");
    expect_error("Texture \"t\" \"float\" \"bilerp\" \"float v00\" 1e39", "\"float v00\"", "finite");
    expect_error("Texture \"t\" \"float\" \"marble\"", "", "spectrum texture");
    expect_error("Texture \"t\" \"float\" \"wood\"", "", "unknown texture class");
}

}  // namespace
}  // namespace phos::io::test
