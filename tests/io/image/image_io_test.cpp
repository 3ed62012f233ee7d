// Tests of io/image reading and writing: lossless float round trips (EXR, PFM), 8-bit round trips
// (PNG, BMP), PFM orientation and byte order, the shared reference images, and error handling.
#include "io/image/image_io.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "io/image/formats.h"
#include "io/image/temp_dir.h"
#include "io/image/tonemap.h"

namespace phos::io {
namespace {

using test::TempDir;

// Non-square (so a transposition shows), with values a lossy or half-float writer would alter.
Image float_pattern() {
    Image img(7, 5);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            img.at(x, y) = Rgb(0.1234567f * float(x + 1) + 1e-7f * float(y), 1000.0f / float(3 + x * y),
                               float(y) - 2.5f + 3.3e-5f * float(x));
    img.at(0, 0) = Rgb(65504.5f, 1e-9f, 123456.789f);
    return img;
}

// Values inside [0, 1] with every channel different, for 8-bit formats.
Image ldr_pattern() {
    Image img(9, 4);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            img.at(x, y) =
                Rgb(float(x) / 8.0f, float(y) / 3.0f, float((x * 7 + y * 3) % 11) / 10.0f * 0.9f + 0.01f);
    return img;
}

void expect_identical(const Image& a, const Image& b) {
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) EXPECT_EQ(a.at(x, y), b.at(x, y)) << x << "," << y;
}

void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

std::string read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string float_bytes(float f, bool little) {
    const uint32_t u = std::bit_cast<uint32_t>(f);
    std::string s(4, '\0');
    for (int i = 0; i < 4; ++i) s[size_t(little ? i : 3 - i)] = char((u >> (8 * i)) & 0xff);
    return s;
}

TEST(ImageIo, ExrRoundTripIsExact) {
    TempDir dir;
    ASSERT_TRUE(dir.ok());
    const Image img = float_pattern();
    write_image(dir.file("a.exr"), img);
    expect_identical(read_image(dir.file("a.exr")), img);
}

TEST(ImageIo, PfmRoundTripIsExact) {
    TempDir dir;
    const Image img = float_pattern();
    write_image(dir.file("a.pfm"), img);
    expect_identical(read_image(dir.file("a.pfm")), img);
    // Upper-case extension is accepted too.
    write_image(dir.file("b.PFM"), img);
    expect_identical(read_image(dir.file("b.PFM")), img);
}

TEST(ImageIo, PfmGreyscaleRoundTrip) {
    TempDir dir;
    Image img(3, 2);
    for (int i = 0; i < 6; ++i) img.pixels[size_t(i)] = Rgb(float(i) * 0.75f);
    img.at(2, 1) = Rgb(0.0f, 3.0f, 6.0f);  // stored as its channel average, 3
    detail::write_pfm(dir.file("g.pfm"), img, /*greyscale=*/true);
    EXPECT_EQ(read_bytes(dir.file("g.pfm")).substr(0, 3), "Pf\n");
    const Image back = read_image(dir.file("g.pfm"));
    ASSERT_EQ(back.width, 3);
    ASSERT_EQ(back.height, 2);
    EXPECT_EQ(back.at(1, 0), Rgb(0.75f));
    EXPECT_EQ(back.at(0, 1), Rgb(2.25f));
    EXPECT_EQ(back.at(2, 1), Rgb(3.0f));
}

// A hand-made 2x2 file: the first stored row is the bottom of the picture.
TEST(ImageIo, PfmRowsAreBottomToTopInBothByteOrders) {
    TempDir dir;
    for (bool little : {true, false}) {
        std::string file = std::string("PF\n2 2\n") + (little ? "-1.0" : "1.0") + "\n";
        const float bottom[6] = {1, 2, 3, 4, 5, 6}, top[6] = {7, 8, 9, 10, 11, 12};
        for (float f : bottom) file += float_bytes(f, little);
        for (float f : top) file += float_bytes(f, little);
        write_bytes(dir.file("o.pfm"), file);
        const Image img = read_image(dir.file("o.pfm"));
        ASSERT_EQ(img.width, 2);
        EXPECT_EQ(img.at(0, 0), Rgb(7, 8, 9)) << "little=" << little;  // top-left
        EXPECT_EQ(img.at(1, 0), Rgb(10, 11, 12));
        EXPECT_EQ(img.at(0, 1), Rgb(1, 2, 3));  // bottom-left
        EXPECT_EQ(img.at(1, 1), Rgb(4, 5, 6));
    }
}

TEST(ImageIo, PfmWriterStoresBottomRowFirst) {
    TempDir dir;
    Image img(1, 2);
    img.at(0, 0) = Rgb(1, 1, 1);  // top
    img.at(0, 1) = Rgb(2, 2, 2);  // bottom
    write_image(dir.file("w.pfm"), img);
    const std::string bytes = read_bytes(dir.file("w.pfm"));
    const std::string header = "PF\n1 2\n-1.0\n";
    ASSERT_EQ(bytes.size(), header.size() + 24);
    EXPECT_EQ(bytes.substr(0, header.size()), header);
    EXPECT_EQ(bytes.substr(header.size(), 4), float_bytes(2.0f, true));
}

TEST(ImageIo, PngRoundTripWithinOneCode) {
    TempDir dir;
    const Image img = ldr_pattern();
    write_image(dir.file("a.png"), img);
    const Image back = read_image(dir.file("a.png"));
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            // Exactly the quantised value, which is within half a code of the original in sRGB space.
            EXPECT_EQ(back.pixels[i][c], srgb8_to_linear(linear_to_srgb8(img.pixels[i][c])));
            EXPECT_NEAR(linear_to_srgb(back.pixels[i][c]), linear_to_srgb(img.pixels[i][c]), 1.0f / 255.0f);
        }
    // srgb = false keeps the raw codes (data textures).
    const Image raw = read_image(dir.file("a.png"), /*srgb=*/false);
    EXPECT_FLOAT_EQ(raw.at(4, 0).r, float(linear_to_srgb8(0.5f)) / 255.0f);
}

TEST(ImageIo, BmpRoundTripWithinOneCode) {
    TempDir dir;
    const Image img = ldr_pattern();  // width 9: rows need padding to 4 bytes
    write_image(dir.file("a.bmp"), img);
    EXPECT_EQ(read_bytes(dir.file("a.bmp")).size(), 54u + 28u * 4u);
    const Image back = read_image(dir.file("a.bmp"));
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(back.pixels[i][c], srgb8_to_linear(linear_to_srgb8(img.pixels[i][c]))) << i << " " << c;
}

TEST(ImageIo, EightBitWritersApplyExposure) {
    TempDir dir;
    Image img(1, 1);
    img.at(0, 0) = Rgb(0.125f, 0.25f, 1.0f);
    write_image(dir.file("e.png"), img, {.exposure = 2.0f});
    write_image(dir.file("e.bmp"), img, {.exposure = 2.0f});
    for (const char* name : {"e.png", "e.bmp"}) {
        const Image back = read_image(dir.file(name));
        EXPECT_EQ(back.at(0, 0), Rgb(srgb8_to_linear(linear_to_srgb8(0.5f)), 1.0f, 1.0f)) << name;
    }
    // Linear formats ignore exposure: they store radiance.
    write_image(dir.file("e.pfm"), img, {.exposure = 2.0f});
    EXPECT_EQ(read_image(dir.file("e.pfm")).at(0, 0), img.at(0, 0));
}

TEST(ImageIo, SharedReferencesAgreeBetweenPfmAndExr) {
    const std::string ref = std::string(PHOS_SHARED_DIR) + "/bench/ref/cornell-diffuse";
    const Image pfm = read_image(ref + ".pfm");
    const Image exr = read_image(ref + ".exr");
    ASSERT_EQ(pfm.width, 256);
    ASSERT_EQ(pfm.height, 256);
    ASSERT_EQ(exr.width, 256);
    ASSERT_EQ(exr.height, 256);
    double max_rel = 0, sum = 0;
    for (size_t i = 0; i < pfm.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double a = pfm.pixels[i][c], b = exr.pixels[i][c];
            max_rel = std::max(max_rel, std::fabs(a - b) / std::max(std::fabs(a), 1e-6));
            sum += a;
        }
    EXPECT_LT(max_rel, 1e-6);
    EXPECT_GT(sum, 0.0);
    // Orientation: red wall on the image left, green wall on the right (scenes/README.md), and the
    // ceiling light in the top half. A flipped reader would fail one of these.
    const Rgb left = pfm.at(10, 128), right = pfm.at(245, 128);
    EXPECT_GT(left.r, 2 * left.g);
    EXPECT_GT(right.g, 2 * right.r);
    int bx = 0, by = 0;
    for (int y = 0; y < pfm.height; ++y)
        for (int x = 0; x < pfm.width; ++x)
            if (pfm.at(x, y).average() > pfm.at(bx, by).average()) bx = x, by = y;
    EXPECT_LT(by, 128);
}

TEST(ImageIo, UnknownExtensionThrows) {
    TempDir dir;
    EXPECT_THROW(write_image(dir.file("a.gif"), float_pattern()), InputError);
    EXPECT_THROW(write_image(dir.file("noext"), float_pattern()), InputError);
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
    write_bytes(dir.file("a.xyz"), "hello");
    EXPECT_THROW(read_image(dir.file("a.xyz")), InputError);
    EXPECT_TRUE(is_writable_image_path("x/y.EXR"));
    EXPECT_FALSE(is_writable_image_path("x/y.jpg"));
}

TEST(ImageIo, MissingFileThrowsWithName) {
    TempDir dir;
    for (const char* name : {"nope.exr", "nope.pfm", "nope.png", "nope.jpg", "nope.hdr"}) {
        try {
            read_image(dir.file(name));
            ADD_FAILURE() << name;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
    }
}

TEST(ImageIo, CorruptFilesThrowInputError) {
    TempDir dir;
    const std::string garbage = "this is not an image at all, just some text\n";
    for (const char* name : {"c.exr", "c.pfm", "c.png", "c.jpg", "c.tga", "c.bmp", "c.hdr"}) {
        write_bytes(dir.file(name), garbage);
        EXPECT_THROW(read_image(dir.file(name)), InputError) << name;
        write_bytes(dir.file(name), "");
        EXPECT_THROW(read_image(dir.file(name)), InputError) << name << " (empty)";
    }
    // Truncated versions of valid files.
    const Image img = float_pattern();
    for (const char* name : {"t.exr", "t.pfm", "t.png", "t.bmp"}) {
        write_image(dir.file(name), img);
        const std::string full = read_bytes(dir.file(name));
        write_bytes(dir.file(name), full.substr(0, full.size() / 2));
        EXPECT_THROW(read_image(dir.file(name)), InputError) << name;
    }
    // Malformed PFM headers.
    for (const char* header :
         {"PF\n-2 2\n-1.0\n", "PF\n2 x\n-1.0\n", "PF\n2 2\n0\n", "PF\n2 2\nabc\n", "PF\n2"}) {
        write_bytes(dir.file("h.pfm"), std::string(header) + std::string(48, '\0'));
        EXPECT_THROW(read_image(dir.file("h.pfm")), InputError) << header;
    }
}

TEST(ImageIo, EmptyImageIsRejected) {
    TempDir dir;
    EXPECT_THROW(write_image(dir.file("e.exr"), Image()), InputError);
    Image bad(2, 2);
    bad.pixels.pop_back();
    EXPECT_THROW(write_image(dir.file("e.pfm"), bad), InputError);
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace phos::io
