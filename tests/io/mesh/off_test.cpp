// Tests of the OFF mesh reader (valid variants and malformed files, each located by line/column)
// and of read_mesh's dispatch by extension.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "io/mesh/mesh_io.h"

namespace phos::io {
namespace {

namespace fs = std::filesystem;

fs::path off_dir() {
    const fs::path d = fs::temp_directory_path() / ("phos_off_test_" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
}

std::string write_off(const std::string& name, const std::string& text) {
    const fs::path p = off_dir() / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
}

TEST(Off, TriangleAndQuadWithComments) {
    const auto m = read_off(write_off("a.off",
                                      "# a comment before the header\n"
                                      "OFF\n"
                                      "5 2 0   # counts\n"
                                      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                                      "\n"
                                      "0.5 0.5 -1e-1\n"
                                      "3 0 1 4\n"
                                      "4 0 1 2 3\n"));
    ASSERT_EQ(m.positions.size(), 5u);
    EXPECT_EQ(m.positions[4], Vec3(0.5f, 0.5f, -0.1f));
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 4, 0, 1, 2, 0, 2, 3}));
    EXPECT_TRUE(m.normals.empty());
    EXPECT_TRUE(m.uvs.empty());
}

TEST(Off, PentagonIsFanTriangulatedAndFaceColoursIgnored) {
    const auto m = read_off(write_off("b.off",
                                      "OFF 5 1 0\n"  // counts on the header line
                                      "0 0 0\n1 0 0\n2 1 0\n1 2 0\n0 1 0\n"
                                      "5 0 1 2 3 4  0.5 0.2 0.1 1\n"));
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
}

TEST(Off, CrlfLineEndingsAndTwoCounts) {
    const auto m = read_off(write_off("c.off", "OFF\r\n3 1\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 2 1 0\r\n"));
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{2, 1, 0}));
}

TEST(Off, NoffCoffAndStoffVariants) {
    const auto n =
        read_off(write_off("n.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 1 0\n3 0 1 2\n"));
    ASSERT_EQ(n.normals.size(), 3u);
    EXPECT_EQ(n.normals[2], Vec3(0, 1, 0));

    const auto c =
        read_off(write_off("c2.off", "COFF\n3 1 0\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n3 0 1 2\n"));
    EXPECT_EQ(c.positions[1], Vec3(1, 0, 0));  // colour columns skipped
    EXPECT_TRUE(c.normals.empty());

    const auto st = read_off(write_off("st.off", "STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n"));
    ASSERT_EQ(st.uvs.size(), 3u);
    EXPECT_EQ(st.uvs[1], Vec2(1, 0));
    EXPECT_EQ(st.uvs[2], Vec2(0, 1));
}

TEST(Off, ReadMeshDispatchesCaseInsensitively) {
    const std::string text = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const auto m = read_mesh(write_off("UPPER.OFF", text));
    EXPECT_EQ(m.mesh.triangle_count(), 1u);
    EXPECT_TRUE(m.triangle_materials.empty());
    EXPECT_THROW(read_mesh(write_off("x.stl", text)), ParseError);
}

struct BadOff {
    std::string name, text;
    int line, col;
    std::string message;
};

void PrintTo(const BadOff& b, std::ostream* os) { *os << b.name; }

const std::vector<BadOff> kBad = {
    {"Empty", "", 1, 1, "empty file"},
    {"NoHeader", "3 1 0\n0 0 0\n", 1, 1, "expected the OFF header"},
    {"FourDimensional", "4OFF\n", 1, 1, "unsupported OFF variant"},
    {"Binary", "OFF BINARY\n", 1, 5, "binary OFF is not supported"},
    {"ControlByte", "OFF\n3 1 0\n0 0 \x01\n", 3, 5, "binary or control byte 0x01"},
    {"OneCount", "OFF\n3\n", 2, 1, "expected the counts"},
    {"FractionalCount", "OFF\n3.5 1 0\n", 2, 1, "bad vertex count '3.5'"},
    {"NegativeFaceCount", "OFF\n3 -1 0\n", 2, 3, "bad face count '-1'"},
    {"TruncatedVertices", "OFF\n3 1 0\n0 0 0\n1 0 0\n", 4, 6, "declares 3 vertices but has only 2 lines"},
    {"TruncatedFaces", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 6, 8, "declares 2 faces"},
    {"ShortVertex", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", 4, 4, "vertex 1 has 2 numbers, expected 3"},
    {"WordInVertex", "OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n", 4, 3, "got 'zero'"},
    {"NanInVertex", "OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n", 4, 5, "got 'nan'"},
    {"IndexOutOfRange", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", 6, 7, "vertex index 3 out of range"},
    {"NegativeIndex", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", 6, 5, "vertex index -1 out of range"},
    {"FaceTooSmall", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", 6, 1, "at least 3 vertices"},
    {"FaceMissingIndices", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", 6, 8,
     "face 0 has 3 indices, expected 4"},
    {"FractionalIndex", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", 6, 5, "expected a vertex index"},
    {"TrailingContent", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", 7, 1, "after the last face"},
};

class OffMalformed : public ::testing::TestWithParam<BadOff> {};

TEST_P(OffMalformed, ThrowsLocatedParseError) {
    const BadOff& b = GetParam();
    const std::string path = write_off(b.name + ".off", b.text);
    try {
        read_off(path);
        FAIL() << "expected a ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.file, path);
        EXPECT_EQ(e.line, b.line) << e.what();
        EXPECT_EQ(e.column, b.col) << e.what();
        EXPECT_NE(e.message.find(b.message), std::string::npos) << e.what();
    }
}

INSTANTIATE_TEST_SUITE_P(Off, OffMalformed, ::testing::ValuesIn(kBad),
                         [](const ::testing::TestParamInfo<BadOff>& info) { return info.param.name; });

TEST(Off, MissingFile) { EXPECT_THROW(read_off((off_dir() / "absent.off").string()), ParseError); }

}  // namespace
}  // namespace phos::io
