// pbrt shapes' "alpha" (cut-outs, as pbrt-v4 defines them): a float value in [0, 1] or a float
// texture, stored on scene::Shape (alpha, alpha_texture) for every shape type, shapes inside
// objects included; values outside [0, 1], unknown or spectrum-only textures are located errors.
#include <gtest/gtest.h>

#include <string>

#include "pbrt_test_util.h"
#include "scene/scene.h"

namespace phos::io::test {
namespace {

const std::string kQuad =
    "\"point3 P\" [0 0 0 1 0 0 1 1 0 0 1 0] \"integer indices\" [0 1 2 0 2 3] \"point2 uv\" [0 0 1 0 1 1 0 "
    "1]";

scene::Scene load(PbrtTempDir& dir, const std::string& world, int* warnings = nullptr) {
    QuietLog quiet;
    const int before = log::warning_count();
    scene::Scene s = load_pbrt(dir.write("scene.pbrt", "WorldBegin\n" + world));
    if (warnings) *warnings = log::warning_count() - before;
    return s;
}

TEST(PbrtAlpha, ValueAndTextureOnEveryShapeType) {
    PbrtTempDir dir;
    int warnings = -1;
    const scene::Scene s =
        load(dir,
             "Texture \"checks\" \"float\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 4\n"
             "Shape \"trianglemesh\" " +
                 kQuad +
                 " \"texture alpha\" \"checks\"\n"
                 "Shape \"sphere\" \"float alpha\" 0.3\n"
                 "Shape \"disk\" \"float alpha\" 0\n"
                 "Shape \"cylinder\" \"float alpha\" 1\n"
                 "Shape \"bilinearmesh\" \"point3 P\" [0 0 0 1 0 1 0 1 1 1 1 0] \"float alpha\" 0.5\n"
                 "Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0] \"texture alpha\" \"checks\"\n"
                 "Shape \"sphere\"\n"
                 "ObjectBegin \"leaf\"\nShape \"trianglemesh\" " +
                 kQuad + " \"float alpha\" 0.25\nObjectEnd\n",
             &warnings);
    EXPECT_EQ(warnings, 0);
    ASSERT_EQ(s.shapes.size(), 7u);
    const int checks = s.shapes[0].alpha_texture;
    ASSERT_GE(checks, 0);
    ASSERT_LT(size_t(checks), s.textures.size());
    EXPECT_EQ(s.textures[size_t(checks)].kind, scene::Texture::Kind::Checkerboard);
    EXPECT_EQ(s.shapes[0].alpha, 1.0f);
    EXPECT_EQ(s.shapes[1].alpha, 0.3f);
    EXPECT_EQ(s.shapes[1].alpha_texture, -1);
    EXPECT_EQ(s.shapes[2].alpha, 0.0f);
    EXPECT_EQ(s.shapes[3].alpha, 1.0f);
    EXPECT_EQ(s.shapes[4].alpha, 0.5f);
    EXPECT_EQ(s.shapes[5].alpha_texture, checks);
    EXPECT_EQ(s.shapes[6].alpha, 1.0f);  // the default: opaque
    EXPECT_EQ(s.shapes[6].alpha_texture, -1);
    ASSERT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(s.objects[0].shapes.at(0).alpha, 0.25f);
}

TEST(PbrtAlpha, BadValuesAndTexturesAreLocatedErrors) {
    PbrtTempDir dir;
    expect_pbrt_error(dir.write("a.pbrt", "WorldBegin\nShape \"sphere\" \"float alpha\" 1.5\n"), 2, 16,
                      "\"alpha\" must be in [0, 1]");
    expect_pbrt_error(dir.write("b.pbrt", "WorldBegin\nShape \"sphere\" \"float alpha\" -0.1\n"), 2, 16,
                      "\"alpha\" must be in [0, 1]");
    expect_pbrt_error(dir.write("c.pbrt", "WorldBegin\nShape \"sphere\" \"texture alpha\" \"nothing\"\n"), 2,
                      16, "unknown float texture \"nothing\"");
    // A spectrum texture is not a float texture.
    expect_pbrt_error(dir.write("d.pbrt",
                                "WorldBegin\nTexture \"c\" \"spectrum\" \"checkerboard\"\n"
                                "Shape \"sphere\" \"texture alpha\" \"c\"\n"),
                      3, 16, "unknown float texture \"c\"");
}

}  // namespace
}  // namespace phos::io::test
