// The pbrt loader's imagemap "filter" and "maxanisotropy" (pbrt-v4's names and defaults): the
// filter read into the texture, a MIP map built for the filtered ones only and shared by textures
// of the same image and wrap mode, pbrt-v3's "bool trilinear" upgraded as pbrt-v4 upgrades it,
// and bad values refused at file:line:col.
#include <gtest/gtest.h>

#include <cstdio>

#include "pbrt_test_util.h"
#include "scene/mip_map.h"

namespace phos::io::test {
namespace {

void write_pfm(const std::string& path, int n) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fprintf(f, "PF\n%d %d\n-1\n", n, n);
    for (int i = 0; i < n * n; ++i) {
        const float rgb[3] = {float(i % 3), 0.5f, 0.25f};
        std::fwrite(rgb, sizeof(float), 3, f);
    }
    std::fclose(f);
}

TEST(PbrtTextureFilter, FiltersAndSharedMipMaps) {
    QuietLog quiet;
    PbrtTempDir dir;
    write_pfm(dir.file("im.pfm"), 4);
    const std::string path = dir.write("scene.pbrt", R"(WorldBegin
Texture "a" "spectrum" "imagemap" "string filename" "im.pfm"
Texture "b" "spectrum" "imagemap" "string filename" "im.pfm" "string filter" "ewa" "float maxanisotropy" 4
Texture "c" "spectrum" "imagemap" "string filename" "im.pfm" "string filter" "trilinear"
Texture "d" "spectrum" "imagemap" "string filename" "im.pfm" "string filter" "point" "string wrap" "clamp"
Texture "e" "spectrum" "imagemap" "string filename" "im.pfm" "string filter" "EWA"
)");
    const scene::Scene s = load_pbrt(path);
    ASSERT_EQ(s.textures.size(), 5u);
    using F = scene::Texture::Filter;
    EXPECT_EQ(s.textures[0].filter, F::Bilinear);
    EXPECT_EQ(s.textures[0].mip_map, nullptr);  // the default needs none
    EXPECT_EQ(s.textures[0].max_anisotropy, 8.0f);
    EXPECT_EQ(s.textures[1].filter, F::Ewa);
    EXPECT_EQ(s.textures[1].max_anisotropy, 4.0f);
    EXPECT_EQ(s.textures[2].filter, F::Trilinear);
    EXPECT_EQ(s.textures[3].filter, F::Point);
    EXPECT_EQ(s.textures[4].filter, F::Ewa);
    ASSERT_NE(s.textures[1].mip_map, nullptr);
    EXPECT_EQ(s.textures[1].mip_map->levels(), 3);  // 4x4, 2x2, 1x1
    // One image for all; one MIP map per wrap mode.
    for (const scene::Texture& t : s.textures) EXPECT_EQ(t.image, s.textures[0].image);
    EXPECT_EQ(s.textures[2].mip_map, s.textures[1].mip_map);
    EXPECT_EQ(s.textures[4].mip_map, s.textures[1].mip_map);
    ASSERT_NE(s.textures[3].mip_map, nullptr);
    EXPECT_NE(s.textures[3].mip_map, s.textures[1].mip_map);
    EXPECT_EQ(s.textures[3].mip_map->wrap(), scene::Texture::Wrap::Clamp);
}

TEST(PbrtTextureFilter, PbrtV3TrilinearBecomesTheFilter) {
    QuietLog quiet;
    PbrtTempDir dir;
    write_pfm(dir.file("im.pfm"), 2);
    // pbrt-v4's upgrade: "bool trilinear" true -> "trilinear", false -> "bilinear".
    const std::string path = dir.write("v3.pbrt", R"(WorldBegin
Texture "a" "color" "imagemap" "string filename" "im.pfm" "bool trilinear" true
Texture "b" "color" "imagemap" "string filename" "im.pfm" "bool trilinear" false
)");
    const scene::Scene s = load_pbrt(path);
    ASSERT_EQ(s.textures.size(), 2u);
    EXPECT_EQ(s.textures[0].filter, scene::Texture::Filter::Trilinear);
    EXPECT_EQ(s.textures[1].filter, scene::Texture::Filter::Bilinear);
}

TEST(PbrtTextureFilter, BadFilterOrAnisotropyIsRefusedWhereItIs) {
    QuietLog quiet;
    PbrtTempDir dir;
    write_pfm(dir.file("im.pfm"), 2);
    const std::string head = "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"im.pfm\" ";
    const auto expect_error = [&](const std::string& param, const std::string& message) {
        const std::string path = dir.write("bad.pbrt", "WorldBegin\n" + head + param + "\n");
        expect_pbrt_error(path, 2, int(head.size()) + 1, message, path);
    };
    expect_error("\"string filter\" \"gaussian\"", "unknown filter");
    expect_error("\"float maxanisotropy\" 0", "maxanisotropy");
    expect_error("\"float maxanisotropy\" 1e39", "finite");
}

}  // namespace
}  // namespace phos::io::test
