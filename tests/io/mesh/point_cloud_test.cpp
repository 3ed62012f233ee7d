// The point-cloud writers: exact ASCII and binary little-endian PLY, the plain text table, and the
// refusals (columns of different lengths, names that would break the header, unknown columns).
#include "io/mesh/point_cloud.h"

#include <gtest/gtest.h>

#include <sstream>

#include "core/error.h"

namespace phos::io {
namespace {

PointCloud two_points() {
    PointCloud c;
    c.comments = {"two points"};
    c.add_floats("x").floats = {0.1f, -2.5f};
    c.add_bytes("red").bytes = {255, 7};
    c.add_floats("power_r").floats = {1e-7f, 3.0f};
    return c;
}

TEST(PointCloud, AsciiPlyIsExact) {
    std::ostringstream out;
    write_ply_points(out, two_points(), false);
    EXPECT_EQ(out.str(),
              "ply\nformat ascii 1.0\ncomment two points\nelement vertex 2\nproperty float x\n"
              "property uchar red\nproperty float power_r\nend_header\n0.1 255 1e-07\n-2.5 7 3\n");
}

TEST(PointCloud, BinaryPlyIsLittleEndian) {
    std::ostringstream out;
    write_ply_points(out, two_points(), true);
    const std::string s = out.str();
    const std::string header =
        "ply\nformat binary_little_endian 1.0\ncomment two points\nelement vertex 2\nproperty float x\n"
        "property uchar red\nproperty float power_r\nend_header\n";
    ASSERT_EQ(s.size(), header.size() + 2 * 9);
    EXPECT_EQ(s.substr(0, header.size()), header);
    // -2.5f is 0xc0200000: bytes 00 00 20 c0, after the first row's 9 bytes.
    const std::string row2 = s.substr(header.size() + 9);
    EXPECT_EQ(row2.substr(0, 4), std::string("\x00\x00\x20\xc0", 4));
    EXPECT_EQ(uint8_t(row2[4]), 7);
    EXPECT_EQ(row2.substr(5), std::string("\x00\x00\x40\x40", 4));  // 3.0f
}

TEST(PointCloud, EmptyCloudHasAHeaderOnly) {
    PointCloud c;
    c.add_floats("x");
    std::ostringstream out;
    write_ply_points(out, c, true);
    EXPECT_NE(out.str().find("element vertex 0\nproperty float x\nend_header\n"), std::string::npos);
    std::ostringstream text;
    write_point_text(text, c, {"x"});
    EXPECT_EQ(text.str(), "0\n");
}

TEST(PointCloud, TextTableHasTheCountThenTheNamedColumns) {
    std::ostringstream out;
    write_point_text(out, two_points(), {"power_r", "x"});
    EXPECT_EQ(out.str(), "2\n1e-07 0.1\n3 -2.5\n");
    EXPECT_THROW(write_point_text(out, two_points(), {"y"}), InputError);
}

TEST(PointCloud, RefusesWhatWouldBreakTheFile) {
    std::ostringstream out;
    PointCloud uneven = two_points();
    uneven.columns[1].bytes.pop_back();
    EXPECT_THROW(write_ply_points(out, uneven, true), InputError);
    PointCloud spaced = two_points();
    spaced.columns[0].name = "x y";
    EXPECT_THROW(write_ply_points(out, spaced, false), InputError);
    PointCloud comment = two_points();
    comment.comments.push_back("two\nlines");
    EXPECT_THROW(write_ply_points(out, comment, false), InputError);
}

}  // namespace
}  // namespace phos::io
