// pbrt materials' "displacement" and "normalmap" (pbrt-v4's bump and normal maps) as the loader
// stores them on scene::Material: a float texture's index, a constant (nothing to store), an image
// read as linear RGB; errors located at the parameter.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "pbrt_test_util.h"
#include "scene/scene.h"

namespace phos::io::test {
namespace {

// A 2 x 1 PFM (linear RGB, bottom row first) of the given two pixels.
void write_pfm(const std::string& path, Rgb left, Rgb right) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fputs("PF\n2 1\n-1\n", f);
    const float px[6] = {left.r, left.g, left.b, right.r, right.g, right.b};
    std::fwrite(px, sizeof(float), 6, f);
    std::fclose(f);
}

scene::Scene load(PbrtTempDir& dir, const std::string& world, int* warnings = nullptr) {
    QuietLog quiet;
    const int before = log::warning_count();
    scene::Scene s = load_pbrt(dir.write("scene.pbrt", "WorldBegin\n" + world));
    if (warnings) *warnings = log::warning_count() - before;
    return s;
}

const scene::Material& material_of(const scene::Scene& s, size_t shape) {
    return s.materials.at(size_t(s.shapes.at(shape).material));
}

TEST(PbrtShadingDetail, DisplacementTexturesAndNormalMaps) {
    PbrtTempDir dir;
    write_pfm(dir.file("n.pfm"), Rgb(0.5f, 0.5f, 1), Rgb(0.75f, 0.5f, 0.9f));
    int warnings = -1;
    const scene::Scene s = load(dir,
                                "Texture \"bumps\" \"float\" \"checkerboard\"\n"
                                "Material \"diffuse\" \"texture displacement\" \"bumps\"\n"
                                "Shape \"sphere\"\n"
                                "Material \"conductor\" \"string normalmap\" \"n.pfm\"\n"
                                "Shape \"sphere\"\n"
                                "Material \"diffuse\" \"float displacement\" 0.2\n"
                                "Shape \"sphere\"\n"
                                "MakeNamedMaterial \"both\" \"string type\" \"diffuse\" \"texture "
                                "displacement\" "
                                "\"bumps\" \"string normalmap\" \"n.pfm\"\n"
                                "NamedMaterial \"both\"\nShape \"sphere\"\n",
                                &warnings);
    EXPECT_EQ(warnings, 1);  // both a displacement and a normal map
    const scene::Material& bumped = material_of(s, 0);
    ASSERT_GE(bumped.displacement_texture, 0);
    EXPECT_EQ(s.textures.at(size_t(bumped.displacement_texture)).kind, scene::Texture::Kind::Checkerboard);
    EXPECT_EQ(bumped.normal_map, nullptr);
    const scene::Material& mapped = material_of(s, 1);
    EXPECT_EQ(mapped.displacement_texture, -1);
    ASSERT_NE(mapped.normal_map, nullptr);
    ASSERT_EQ(mapped.normal_map->width, 2);
    ASSERT_EQ(mapped.normal_map->height, 1);
    // Read as stored (linear), not decoded from sRGB.
    EXPECT_FLOAT_EQ(mapped.normal_map->at(1, 0).r, 0.75f);
    EXPECT_FLOAT_EQ(mapped.normal_map->at(1, 0).b, 0.9f);
    const scene::Material& constant = material_of(s, 2);
    EXPECT_EQ(constant.displacement_texture, -1);
    EXPECT_EQ(constant.normal_map, nullptr);
    EXPECT_NE(material_of(s, 3).normal_map, nullptr);
}

TEST(PbrtShadingDetail, UnknownTexturesAndMissingImagesAreLocated) {
    PbrtTempDir dir;
    expect_pbrt_error(dir.write("a.pbrt",
                                "WorldBegin\nMaterial \"diffuse\" "
                                "\"texture displacement\" \"none\"\n"),
                      2, 20, "unknown float texture \"none\"");
    expect_pbrt_error(dir.write("b.pbrt",
                                "WorldBegin\nMaterial \"diffuse\" \"string "
                                "normalmap\" \"missing.png\"\n"),
                      2, 20, "normal map");
}

}  // namespace
}  // namespace phos::io::test
