// Malformed .scn inputs: each must throw a ParseError naming the right file, line and column, with
// a message that says what is wrong. Line 1 of every main file defines material 0.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "core/log.h"
#include "scn_test_util.h"

namespace phos::io::test {
namespace {

using namespace std::string_literals;

const std::string kMat = "material 0 0 0  0.5 0.5 0.5  0 0 0  0 0 0  0 0 0  10 1 0\n";
const std::string kIdentityBegin = "begin -1 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n";

struct Case {
    std::string name;
    std::string main;  // written after kMat, so its first line is line 2
    std::vector<std::pair<std::string, std::string>> files;  // other files in the directory
    std::string file;  // where the error is expected (relative to the directory)
    int line, col;
    std::string message;
};

const std::vector<Case> kCases = {
    {"TruncatedBeforeKeyword",
     "sphere 0 1 2 3\nbox 0 0 0 0 1 1 1\n",
     {},
     "main.scn",
     3,
     1,
     "sphere: expected 5 numbers (material cx cy cz r), got 'box'"},
    {"WordForNumber", "sphere 0 1 two 3 1\n", {}, "main.scn", 2, 12, "got 'two'"},
    {"NaN", "sphere 0 nan 0 0 1\n", {}, "main.scn", 2, 10, "'nan' is not a finite number"},
    {"Inf", "sphere 0 0 0 0 -inf\n", {}, "main.scn", 2, 16, "'-inf' is not a finite number"},
    {"DoubleOverflow", "sphere 0 1e999 0 0 1\n", {}, "main.scn", 2, 10, "not a finite number"},
    {"FloatOverflow", "sphere 0 0 0 0 1e39\n", {}, "main.scn", 2, 16, "not a finite number"},
    {"HexFloat", "sphere 0 0x1p3 0 0 1\n", {}, "main.scn", 2, 10, "got '0x1p3'"},
    {"UnknownCommand", "teapot 0 1\n", {}, "main.scn", 2, 1, "unknown command 'teapot'"},
    {"ExtraNumber", "sphere 0 0 0 0 1 2\n", {}, "main.scn", 2, 18, "unexpected number '2'"},
    {"UndefinedMaterial", "sphere 3 0 0 0 1\n", {}, "main.scn", 2, 8, "material 3 is not defined"},
    {"NegativeMaterial", "sphere -2 0 0 0 1\n", {}, "main.scn", 2, 8, "material -2 is not defined"},
    {"FractionalMaterial", "sphere 0.5 0 0 0 1\n", {}, "main.scn", 2, 8, "must be an integer"},
    {"NegativeRadius", "sphere 0 0 0 0 -1\n", {}, "main.scn", 2, 16, "sphere: radius must be positive"},
    {"ZeroRadiusCircle",
     "circle 0 0 0 0 0 1 0 0\n",
     {},
     "main.scn",
     2,
     22,
     "circle: radius must be positive"},
    {"ZeroNormalCircle",
     "circle 0 0 0 0 0 0 0 1\n",
     {},
     "main.scn",
     2,
     16,
     "circle: normal must be a non-zero"},
    {"FlatBox", "box 0 0 0 0 1 0 1\n", {}, "main.scn", 2, 15, "box: zero size along y"},
    {"CollinearTri", "tri 0  0 0 0  1 1 1  2 2 2\n", {}, "main.scn", 2, 1, "degenerate triangle"},
    {"CoincidentTri", "tri 0 1 1 1 1 1 1 0 0 0\n", {}, "main.scn", 2, 1, "degenerate triangle"},
    {"ZeroDirLight", "dir_light 1 1 1 0 0 0\n", {}, "main.scn", 2, 17, "direction must be a non-zero vector"},
    {"MissingInclude", "include nothere.scn\n", {}, "main.scn", 2, 9, "'nothere.scn' not found"},
    {"MissingMesh", "mesh 0 nothere.off\n", {}, "main.scn", 2, 8, "'nothere.off' not found"},
    {"MissingTexture",
     "material 0 0 0 1 1 1 0 0 0 0 0 0 0 0 0 10 1 missing.png\n",
     {},
     "main.scn",
     2,
     45,
     "'missing.png' not found"},
    {"UnreadableTexture",
     "material 0 0 0 1 1 1 0 0 0 0 0 0 0 0 0 10 1 bad.png\n",
     {{"bad.png", "not a png"}},
     "main.scn",
     2,
     45,
     "cannot read texture"},
    {"IncludeCycle",
     "include a.scn\n",
     {{"a.scn", "include b.scn\n"}, {"b.scn", "# b\ninclude a.scn\n"}},
     "b.scn",
     2,
     9,
     "include cycle"},
    {"SelfInclude", "include main.scn\n", {}, "main.scn", 2, 9, "include cycle"},
    {"BinaryGarbage", "sphere 0 0 0 0 1\n\x01\x02\x03"s, {}, "main.scn", 3, 1, "binary or control byte 0x01"},
    {"NulByte", "sphere 0 0 0 \0 1\n"s, {}, "main.scn", 2, 14, "binary or control byte 0x00"},
    {"NonUtf8InComment", "sphere 0 0 0 0 1 # caf\xe9\n", {}, "main.scn", 2, 23, "invalid UTF-8 byte 0xE9"},
    {"OverlongUtf8", "sphere 0 0 0 0 1 \xc0\xaf\n", {}, "main.scn", 2, 18, "invalid UTF-8"},
    {"UnclosedBegin",
     kIdentityBegin + "sphere -1 0 0 0 1\n",
     {},
     "main.scn",
     2,
     1,
     "begin without a matching end"},
    {"StrayEnd", "end\n", {}, "main.scn", 2, 1, "end without a matching begin"},
    {"SingularMatrix", "begin -1 1 0 0 0 0 0 0 0 0 0 1 0 0 0 0 1\nend\n", {}, "main.scn", 2, 1, "singular"},
    {"NonAffineMatrix",
     "begin -1 1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1\nend\n",
     {},
     "main.scn",
     2,
     38,
     "last row must be 0 0 0 1"},
    {"FovTooWide", "camera 0 0 0 0 0 -1 0 1 0 1.6 0.1 10\n", {}, "main.scn", 2, 27, "(0, pi/2)"},
    {"FovZero", "camera 0 0 0 0 0 -1 0 1 0 0 0.1 10\n", {}, "main.scn", 2, 27, "(0, pi/2)"},
    {"UpParallelToView", "camera 0 0 0 0 0 -1 0 0 2 0.5 0.1 10\n", {}, "main.scn", 2, 21, "parallel"},
    {"FarBeforeNear", "camera 0 0 0 0 0 -1 0 1 0 0.5 10 1\n", {}, "main.scn", 2, 34, "far must be greater"},
    {"NegativeLightColour",
     "point_light 1 -1 1 0 0 0 0 0 1\n",
     {},
     "main.scn",
     2,
     15,
     "must not be negative"},
    {"TruncatedAtEndOfFile",
     "point_light 1 1 1 0 0",
     {},
     "main.scn",
     2,
     22,
     "point_light: expected 9 numbers (r g b  px py pz  ca la qa), got end of file"},
    {"MaterialMissingTexture",
     "material 0 0 0 1 1 1 0 0 0 0 0 0 0 0 0 10 1\nsphere 0 0 0 0 1\n",
     {},
     "main.scn",
     3,
     1,
     "expected a texture file name (or 0), got 'sphere'"},
    {"SpotCutoffNegative", "spot_light 1 1 1 0 0 0 0 -1 0 0 0 1 -0.5 1\n", {}, "main.scn", 2, 37, "cutoff"},
    {"RectSidesParallel",
     "rect_light 1 1 1 0 0 0 1 0 0 2 0 0 1 1 0 0 1\n",
     {},
     "main.scn",
     2,
     30,
     "a1 and a2 are parallel"},
    {"AreaLightZeroRadius",
     "area_light 1 1 1 0 0 0 0 -1 0 0 0 0 1\n",
     {},
     "main.scn",
     2,
     31,
     "area_light: radius must be positive"},
    {"IncludedFileHasItsOwnMaterials",
     "include inc.scn\n",
     {{"inc.scn", "# comment\nsphere 0 0 0 0 1\n"}},
     "inc.scn",
     2,
     8,
     "material 0 is not defined"},
    {"ZeroHeightCylinder",
     "cylinder 0 0 0 0 1 0\n",
     {},
     "main.scn",
     2,
     20,
     "cylinder: height must be positive"},
    {"ZeroLengthLine", "line 0 1 1 1 1 1 1\n", {}, "main.scn", 2, 14, "end points coincide"},
    {"AllZeroAttenuation", "point_light 1 1 1 0 0 0 0 0 0\n", {}, "main.scn", 2, 25, "all zero"},
    {"NegativeKd",
     "material 0 0 0 1 -1 1 0 0 0 0 0 0 0 0 0 10 1 0\n",
     {},
     "main.scn",
     2,
     18,
     "kd must not be negative"},
    {"ZeroIor",
     "material 0 0 0 1 1 1 0 0 0 0 0 0 0 0 0 10 0 0\n",
     {},
     "main.scn",
     2,
     43,
     "index of refraction"},
    {"BadOffIndex",
     "mesh 0 broken.off\n",
     {{"broken.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"}},
     "broken.off",
     6,
     7,
     "out of range"},
    {"UnknownMeshFormat",
     "mesh 0 model.stl\n",
     {{"model.stl", "solid x\n"}},
     "main.scn",
     2,
     8,
     "unknown mesh format '.stl'"},
    {"EndClosesParentGroup",
     kIdentityBegin + "include inc.scn\nend\n",
     {{"inc.scn", "end\n"}},
     "inc.scn",
     1,
     1,
     "end without a matching begin"},
    {"BeginUnclosedInInclude",
     "include inc.scn\n",
     {{"inc.scn", kIdentityBegin}},
     "inc.scn",
     1,
     1,
     "begin without a matching end"},
    {"NegativeBackground", "background 0 0 -0.1\n", {}, "main.scn", 2, 16, "must not be negative"},
};

// Names the case in gtest output instead of dumping its bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

class ScnError : public ::testing::TestWithParam<Case> {};

TEST_P(ScnError, IsReportedWithFileLineAndColumn) {
    log::set_quiet(true);
    const Case& c = GetParam();
    TempDir dir;
    for (const auto& [name, content] : c.files) dir.write(name, content);
    const std::string main = dir.write("main.scn", kMat + c.main);
    expect_parse_error(main, dir.file(c.file), c.line, c.col, c.message);
}

INSTANTIATE_TEST_SUITE_P(Malformed, ScnError, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& info) { return info.param.name; });

TEST(ScnErrorExtra, IncludeCycleMessageNamesTheChain) {
    log::set_quiet(true);
    TempDir dir;
    dir.write("a.scn", "include b.scn\n");
    dir.write("b.scn", "include a.scn\n");
    const std::string main = dir.write("main.scn", "include a.scn\n");
    try {
        load_scn(main);
        FAIL() << "expected a ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.message, "include cycle: " + dir.file("a.scn") + " -> " + dir.file("b.scn") + " -> " +
                                 dir.file("a.scn"));
    }
}

TEST(ScnErrorExtra, MissingTopLevelFile) {
    TempDir dir;
    const std::string path = dir.file("absent.scn");
    try {
        load_scn(path);
        FAIL() << "expected a ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.file, path);
        EXPECT_NE(e.message.find("not found"), std::string::npos);
    }
}

TEST(ScnErrorExtra, WhatStringIsFileLineColMessage) {
    log::set_quiet(true);
    TempDir dir;
    const std::string main = dir.write("main.scn", kMat + "sphere 0 1 2 3\nbox 0 0 0 0 1 1 1\n");
    try {
        load_scn(main);
        FAIL() << "expected a ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(std::string(e.what()),
                  main + ":3:1: sphere: expected 5 numbers (material cx cy cz r), got 'box'");
    }
}

// An error inside a mesh or an included scene names its own file, line and column, then every
// `mesh` / `include` that led there, innermost first, at the file name that command gives.
TEST(ScnErrorExtra, ErrorsInIncludedFilesNameTheIncludingLines) {
    log::set_quiet(true);
    TempDir dir;
    dir.write("sub/bad.off", "OFF\n3 1 0\n0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n");
    dir.write("sub/inc.scn", "# the mesh, in the group's material\n  mesh -1 bad.off\n");
    const std::string main = dir.write("main.scn", kMat + "\ninclude sub/inc.scn\n");
    try {
        load_scn(main);
        FAIL() << "expected a ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.file, dir.file("sub/bad.off"));
        EXPECT_EQ(e.line, 4) << e.what();
        const std::vector<std::string> chain{dir.file("sub/inc.scn") + ":2:11", main + ":3:9"};
        EXPECT_EQ(e.included_from, chain);
        EXPECT_EQ(std::string(e.what()), dir.file("sub/bad.off") + ":4:" + std::to_string(e.column) + ": " +
                                             e.message + "\n  included from " + chain[0] +
                                             "\n  included from " + chain[1]);
    }
    // A mesh named by the top-level file: one "included from".
    const std::string direct = dir.write("direct.scn", kMat + "mesh 0 sub/bad.off\n");
    try {
        load_scn(direct);
        FAIL() << "expected a ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.included_from, std::vector<std::string>{direct + ":2:8"});
    }
    // A problem in the included scene itself, and a byte its lexer refuses.
    dir.write("sub/typo.scn", "\nspher -1 0 0 0 1\n");
    dir.write("sub/binary.scn", "sphere -1 0 0 0 1\n\x01\n");
    for (const char* name : {"typo", "binary"}) {
        const std::string top = dir.write("top.scn", "include sub/" + std::string(name) + ".scn\n");
        try {
            load_scn(top);
            FAIL() << "expected a ParseError";
        } catch (const ParseError& e) {
            EXPECT_EQ(e.file, dir.file("sub/" + std::string(name) + ".scn")) << e.what();
            EXPECT_EQ(e.included_from, std::vector<std::string>{top + ":1:9"}) << e.what();
        }
    }
}

// An error in the top-level file, or at the include command itself (a cycle, a missing file), is
// where the include is written: nothing "included" it.
TEST(ScnErrorExtra, ErrorsAtTheIncludeCommandAreNotIncludedFromThemselves) {
    log::set_quiet(true);
    TempDir dir;
    dir.write("a.scn", "include b.scn\n");
    dir.write("b.scn", "\ninclude a.scn\n");
    const std::string main = dir.write("main.scn", "include a.scn\n");
    try {
        load_scn(main);
        FAIL() << "expected a ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.file, dir.file("b.scn"));
        EXPECT_EQ(e.line, 2);
        const std::vector<std::string> chain{dir.file("a.scn") + ":1:9", main + ":1:9"};
        EXPECT_EQ(e.included_from, chain);
    }
    const std::string missing = dir.write("missing.scn", "include nothere.scn\n");
    try {
        load_scn(missing);
        FAIL() << "expected a ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.file, missing);
        EXPECT_TRUE(e.included_from.empty()) << e.what();
    }
}

}  // namespace
}  // namespace phos::io::test
