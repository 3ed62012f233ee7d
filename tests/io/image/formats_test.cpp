// Tests of io/image reading files other programs write: EXR in half precision, with alpha, with a
// data window away from the origin, or grey (Y only); hand-made Radiance HDR and TGA files.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfRgbaFile.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "io/image/image_io.h"
#include "io/image/temp_dir.h"
#include "io/image/tonemap.h"

namespace phos::io {
namespace {

using test::TempDir;

TEST(ImageFormats, ExrHalfRgbaWithOffsetDataWindow) {
    TempDir dir;
    const std::string path = dir.file("rgba.exr");
    // Data window x in [10, 12], y in [-1, 0]: 3x2 pixels, origin not at (0, 0).
    const Imath::Box2i dw(Imath::V2i(10, -1), Imath::V2i(12, 0));
    std::vector<Imf::Rgba> px(6);
    for (int i = 0; i < 6; ++i)
        px[size_t(i)] = Imf::Rgba(half(0.5f * float(i)), half(1.0f), half(-2.0f), half(0.25f));
    {
        Imf::RgbaOutputFile out(path.c_str(), Imf::Header(dw, dw), Imf::WRITE_RGBA);
        out.setFrameBuffer(px.data() - dw.min.x - dw.min.y * 3, 1, 3);
        out.writePixels(2);
    }
    const Image img = read_image(path);
    ASSERT_EQ(img.width, 3);
    ASSERT_EQ(img.height, 2);
    EXPECT_EQ(img.at(0, 0), Rgb(0.0f, 1.0f, -2.0f));
    EXPECT_EQ(img.at(2, 0), Rgb(1.0f, 1.0f, -2.0f));
    EXPECT_EQ(img.at(1, 1), Rgb(2.0f, 1.0f, -2.0f));  // alpha ignored
}

TEST(ImageFormats, ExrGreyOnly) {
    TempDir dir;
    const std::string path = dir.file("grey.exr");
    std::vector<float> y = {0.125f, 3.0f};
    {
        Imf::Header header(2, 1);
        header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
        Imf::OutputFile out(path.c_str(), header);
        Imf::FrameBuffer fb;
        fb.insert(
            "Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(y.data()), sizeof(float), 2 * sizeof(float)));
        out.setFrameBuffer(fb);
        out.writePixels(1);
    }
    const Image img = read_image(path);
    ASSERT_EQ(img.width, 2);
    EXPECT_EQ(img.at(0, 0), Rgb(0.125f));
    EXPECT_EQ(img.at(1, 0), Rgb(3.0f));
}

TEST(ImageFormats, RadianceHdrIsLinear) {
    TempDir dir;
    // Flat (not run-length encoded) RGBE pixels; mantissa * 2^(exponent - 136) per channel.
    std::string file = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n";
    file += std::string{char(128), char(64), char(32), char(129)};  // (1, 0.5, 0.25)
    file += std::string{char(192), char(0), char(128), char(132)};  // (12, 0, 8)
    std::ofstream(dir.file("a.hdr"), std::ios::binary) << file;
    for (bool srgb : {true, false}) {  // linear data: the srgb flag must not change it
        const Image img = read_image(dir.file("a.hdr"), srgb);
        ASSERT_EQ(img.width, 2);
        ASSERT_EQ(img.height, 1);
        EXPECT_EQ(img.at(0, 0), Rgb(1.0f, 0.5f, 0.25f));
        EXPECT_EQ(img.at(1, 0), Rgb(12.0f, 0.0f, 8.0f));
    }
}

TEST(ImageFormats, UncompressedTga) {
    TempDir dir;
    // 18-byte header: no id, no colour map, type 2 (true colour), 2x1, 24 bpp, descriptor 0x20
    // (top-left origin); then BGR pixels.
    std::string file(18, '\0');
    file[2] = 2;
    file[12] = 2;
    file[14] = 1;
    file[16] = 24;
    file[17] = 0x20;
    file += std::string{char(0), char(0), char(255)};   // red
    file += std::string{char(10), char(128), char(0)};  // (0, 128, 10)
    std::ofstream(dir.file("a.tga"), std::ios::binary) << file;
    const Image img = read_image(dir.file("a.tga"));
    ASSERT_EQ(img.width, 2);
    EXPECT_EQ(img.at(0, 0), Rgb(1, 0, 0));
    EXPECT_EQ(img.at(1, 0), Rgb(0, srgb8_to_linear(128), srgb8_to_linear(10)));
    const Image raw = read_image(dir.file("a.tga"), /*srgb=*/false);
    EXPECT_FLOAT_EQ(raw.at(1, 0).g, 128.0f / 255.0f);
}

}  // namespace
}  // namespace phos::io
