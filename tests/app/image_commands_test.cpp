// `phos info`, `phos montage` and bench/seed_scenes.sh, which surveys a folder of scenes with them.
#include "app/lib/image_commands.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "io/image/image_io.h"
#include "test_util.h"

namespace phos::testing {
namespace {

TEST(ImageCommands, InfoCountsMeanBlackAndNonFinite) {
    Image img(2, 2);
    img.at(0, 0) = Rgb(1, 2, 3);
    img.at(1, 0) = Rgb(0, 0, 0);
    img.at(0, 1) = Rgb(std::numeric_limits<float>::quiet_NaN(), 1, 1);
    img.at(1, 1) = Rgb(2, 2, 2);
    const app::ImageInfo i = app::image_info(img);
    EXPECT_EQ(i.width, 2);
    EXPECT_EQ(i.non_finite, 1u);
    EXPECT_DOUBLE_EQ(i.mean, (6.0 + 0 + 2 + 6) / 11.0);
    EXPECT_DOUBLE_EQ(i.black_fraction, 0.25);

    TempDir dir;
    io::write_image(dir.file("a.pfm"), img);
    const auto r = run_phos("info " + dir.file("a.pfm"));
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.output.find("a.pfm 2x2 mean 1.27273 black 0.2500 nonfinite 1 speckle"), std::string::npos)
        << r.output;
    EXPECT_EQ(run_phos("info " + dir.file("missing.pfm")).exit_code, 2);
}

TEST(ImageCommands, MontagePlacesScaledImagesInAGrid) {
    Image red(4, 2), blue(2, 2);
    for (Rgb& p : red.pixels) p = Rgb(1, 0, 0);
    for (Rgb& p : blue.pixels) p = Rgb(0, 0, 1);
    const Image m = app::montage({red, blue, blue}, 8);
    ASSERT_EQ(m.width, 16);  // ceil(sqrt(3)) = 2 columns, 2 rows
    ASSERT_EQ(m.height, 16);
    EXPECT_EQ(m.at(0, 4), Rgb(1, 0, 0));    // red, 8x4, centred vertically in its cell
    EXPECT_EQ(m.at(0, 0), Rgb(0, 0, 0));    // letterbox
    EXPECT_EQ(m.at(12, 4), Rgb(0, 0, 1));   // second cell
    EXPECT_EQ(m.at(4, 12), Rgb(0, 0, 1));   // third cell, next row
    EXPECT_EQ(m.at(12, 12), Rgb(0, 0, 0));  // empty cell
}

TEST(ImageCommands, SeedScenesScriptReportsEveryScene) {
    TempDir dir;
    dir.write("scenes/lit.scn",
              "camera 0 0 3  0 0 -1  0 1 0  0.5  0.01 100\n"
              "material 0 0 0  .5 .5 .5  0 0 0  0 0 0  0 0 0  1 1 0\n"
              "sphere 0  0 0 0  1\npoint_light 3 3 3  0 2 2  0 0 1\n");
    dir.write("scenes/broken.scn", "sphere\n");
    const std::string cmd = "PHOS=" + std::string(PHOS_BINARY) + " bash " +
                            source_path("bench/seed_scenes.sh") + " " + dir.file("scenes") + " " +
                            dir.file("out") + " --width 16 --spp 1 --quality draft 2>&1";
    CommandResult r;
    FILE* pipe = popen(cmd.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, pipe)) r.output.append(buf, n);
    EXPECT_EQ(pclose(pipe), 0) << r.output;
    EXPECT_NE(r.output.find("broken                          2"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("lit                             0"), std::string::npos) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/lit.exr")));
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/contact.png")));
}

}  // namespace
}  // namespace phos::testing
