// Malformed pbrt input: each case must throw a ParseError at the exact file:line:col of the fault.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "pbrt_test_util.h"

namespace phos::io::test {
namespace {

struct Case {
    const char* name;
    std::string text;
    int line, col;
    const char* message;
};

class PbrtErrors : public ::testing::TestWithParam<Case> {};

TEST_P(PbrtErrors, ThrowsAtTheRightPlace) {
    QuietLog quiet;
    PbrtTempDir dir;
    const Case& c = GetParam();
    const std::string path = dir.write("bad.pbrt", c.text);
    expect_pbrt_error(path, c.line, c.col, c.message, path);
}

const std::string W = "WorldBegin\n";  // line 1

INSTANTIATE_TEST_SUITE_P(
    Malformed, PbrtErrors,
    ::testing::Values(
        Case{"UnterminatedString", W + "Shape \"sphere\" \"float radius\" [ 1 ]\nMaterial \"diffuse\n", 3, 10,
             "unterminated string"},
        Case{"MissingBracket", W + "Shape \"sphere\" \"float radius\" [ 1\nAttributeBegin\n", 2, 31,
             "missing ']'"},
        Case{"MissingBracketAtEof", W + "Shape \"sphere\" \"float radius\" [ 1", 2, 31, "missing ']'"},
        Case{"FilmTooLarge", "Film \"rgb\" \"integer xresolution\" [ 2000000000 ]\nWorldBegin\n", 1, 1,
             "resolution 2000000000 x 720 is not in [1, 65536]"},
        Case{"UnknownDirective", W + "  Shpe \"sphere\"\n", 2, 3, "unknown directive 'Shpe'"},
        Case{"WrongParamType", W + "Shape \"sphere\" \"string radius\" \"big\"\n", 2, 16, "should be float"},
        Case{"UnknownParamType", W + "Shape \"sphere\" \"flot radius\" 1\n", 2, 16, "unknown parameter type"},
        Case{"StringForNumber", W + "Shape \"sphere\" \"float radius\" [ \"one\" ]\n", 2, 16,
             "needs numbers"},
        Case{"BadIndex",
             W + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\n  \"integer indices\" [0 1 3]\n",
             2, 1, "vertex index 3 out of range"},
        Case{"NegativeIndex",
             W + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0] \"integer indices\" [0 1 "
                 "-1]\n",
             2, 1, "vertex index -1 out of range"},
        Case{"IndexCount",
             W + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0] \"integer indices\" [0 1 2 "
                 "3]\n",
             2, 1, "not a positive multiple of 3"},
        Case{"MissingIndices", W + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n", 2, 1,
             "\"integer indices\" is required"},
        Case{"NormalCount",
             W + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"normal N\" [0 0 1]\n", 2, 1,
             "\"N\" has 1 normals for 3 vertices"},
        Case{"PointCount", W + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1]\n", 2, 22,
             "multiple of 3"},
        Case{"MissingInclude", W + "\n Include \"nothere.pbrt\"\n", 3, 2, "cannot open included file"},
        Case{"NaN", W + "Translate 1 nan 0\n", 2, 13, "not a finite number"},
        Case{"NaNParam", W + "Shape \"sphere\" \"float radius\" [ inf ]\n", 2, 33, "not a finite number"},
        Case{"AttributeEndWithoutBegin", W + "AttributeBegin\nAttributeEnd\nAttributeEnd\n", 4, 1,
             "AttributeEnd without matching AttributeBegin"},
        Case{"WorldBeginTwice", W + "Shape \"sphere\"\n  WorldBegin\n", 3, 3, "WorldBegin given twice"},
        Case{"UnknownObject", W + "ObjectInstance \"ghost\"\n", 2, 1, "unknown object 'ghost'"},
        Case{"UnknownNamedMaterial", W + "NamedMaterial \"gold\"\n", 2, 1, "unknown material \"gold\""},
        Case{"NegativeRadius", W + "Shape \"sphere\" \"float radius\" -2\n", 2, 16,
             "radius must be positive"},
        Case{"ShapeBeforeWorld", "Shape \"sphere\"\n", 1, 1, "only allowed after WorldBegin"},
        Case{"CameraAfterWorld", W + "Camera \"perspective\"\n", 2, 1, "not allowed after WorldBegin"},
        Case{"RotateZeroAxis", W + "Rotate 30 0 0 0\n", 2, 1, "zero-length axis"},
        Case{"ScaleZero", W + "Scale 1 0 1\n", 2, 1, "Scale by zero"},
        Case{"MissingNumber", W + "Translate 1 2 Shape\n", 2, 15, "expected a number"},
        Case{"SingularTransform", W + "Transform [1 0 0 0 0 0 0 0 0 0 1 0 0 0 0 1]\n", 2, 1, "singular"},
        Case{"UnknownCoordSys", W + "CoordSysTransform \"lamp\"\n", 2, 1, "unknown coordinate system"},
        Case{"UnknownMedium", W + "MediumInterface \"fog\" \"\"\n", 2, 1, "unknown medium \"fog\""},
        Case{"UnknownTexture", W + "Material \"diffuse\" \"texture reflectance\" \"wood\"\n", 2, 20,
             "unknown texture \"wood\""},
        Case{"ObjectEndWithoutBegin", W + "ObjectEnd\n", 2, 1, "ObjectEnd without matching ObjectBegin"},
        Case{"UnclosedObject", W + "ObjectBegin \"a\"\nShape \"sphere\"\n", 2, 1,
             "ObjectBegin without ObjectEnd"},
        Case{"DuplicateParam", W + "Shape \"sphere\" \"float radius\" 1 \"float radius\" 2\n", 2, 33,
             "given twice"},
        Case{"BadParamDeclaration", W + "Shape \"sphere\" \"radius\" 1\n", 2, 16,
             "malformed parameter declaration"},
        Case{"StringWhereDirective", W + "\"sphere\"\n", 2, 1, "expected a directive"},
        Case{"UnknownNamedSpectrum", W + "Material \"conductor\" \"spectrum eta\" \"metal-Xx-eta\"\n", 2, 22,
             "neither a named spectrum"},
        Case{"BadBool", W + "AreaLightSource \"diffuse\" \"bool twosided\" \"yes\"\n", 2, 27,
             "true or false"},
        // spectra ("LightSource \"point\" " and "Material \"dielectric\" " are 20 and 22 columns)
        Case{"BlackbodyThreeValues", W + "LightSource \"point\" \"blackbody I\" [6500 1 2]\n", 2, 21,
             "needs a temperature (and, as in pbrt-v3, a scale), got 3 values"},
        Case{"BlackbodyNegativeScale", W + "LightSource \"point\" \"blackbody I\" [6500 -1]\n", 2, 21,
             "blackbody scale (the second value) must not be negative"},
        Case{"UnknownGlass", W + "Material \"dielectric\" \"spectrum eta\" \"glass-XX\"\n", 2, 23,
             "neither a named spectrum"},
        Case{"EtaSpectrumNotPositive", W + "Material \"dielectric\" \"spectrum eta\" [400 1.5 700 0]\n", 2,
             23, "eta must be positive at every wavelength"},
        Case{"EtaSpectrumWavelengthsDecrease",
             W + "Material \"dielectric\" \"spectrum eta\" [500 1.5 400 1.6]\n", 2, 23,
             "spectrum wavelengths must increase"},
        Case{"FilmIsoNotPositive", "Film \"rgb\" \"float iso\" -100\n" + W, 1, 12, "iso must be positive"},
        Case{"FilmWhiteBalanceNegative", "Film \"rgb\" \"float whitebalance\" -5\n" + W, 1, 12,
             "whitebalance must be 0 (none) or a temperature in [1000, 40000] kelvin"},
        Case{"ShutterNeverOpens",
             "Camera \"perspective\" \"float shutteropen\" 1 \"float shutterclose\" 0.5\n" + W, 1, 44,
             "shutterclose must be later than shutteropen"},
        Case{"IntegerNotInteger",
             W + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2.5]\n", 2,
             53, "non-integer"},
        Case{"MismatchedTransformEnd", W + "AttributeBegin\nTransformEnd\n", 3, 1,
             "closes the AttributeBegin"},
        Case{"BadEscape", W + "Shape \"sph\\qere\"\n", 2, 11, "unknown escape"},
        Case{"MaterialRedefined",
             W + "MakeNamedMaterial \"a\" \"string type\" \"diffuse\"\nMakeNamedMaterial \"a\" \"string "
                 "type\" \"diffuse\"\n",
             3, 1, "defined twice"},
        // media ("MakeNamedMedium \"m\" \"string type\" " is 34 columns)
        Case{"MediumNegativeSigma",
             W + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0.1 -1 0]\n", 2, 1,
             "coefficients must not be negative"},
        Case{"MediumNegativeScale",
             W + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"float scale\" -2\n", 2, 1,
             "coefficients must not be negative"},
        Case{"MediumGTooLarge", W + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"float g\" 1\n",
             2, 49, "g must be in (-1, 1)"},
        Case{"MediumGTooSmall",
             W + "MakeNamedMedium \"m\" \"string type\" \"uniformgrid\" \"float g\" -1.5 \"float density\" "
                 "[1]\n",
             2, 49, "g must be in (-1, 1)"},
        Case{"GridDensityCount",
             W + "MakeNamedMedium \"m\" \"string type\" \"uniformgrid\" \"integer nx\" 2 \"float density\" "
                 "[1]\n",
             2, 1, "\"density\" has 1 values, nx*ny*nz = 2"},
        Case{"GridP0NotBelowP1",
             W + "MakeNamedMedium \"m\" \"string type\" \"uniformgrid\" \"float density\" [1] \"point3 p0\" "
                 "[0 0 0] \"point3 p1\" [1 0 1]\n",
             2, 89, "p0 must be less than p1"},
        Case{"GridP0AboveDefaultP1",
             W + "MakeNamedMedium \"m\" \"string type\" \"uniformgrid\" \"float density\" [1] \"point3 p0\" "
                 "[0 2 0]\n",
             2, 69, "p0 must be less than p1"},
        Case{"GridLescaleCount",
             W + "MakeNamedMedium \"m\" \"string type\" \"uniformgrid\" \"integer nx\" 2 \"float density\" "
                 "[1 1] \"float Lescale\" [1 2 3]\n",
             2, 86, "\"Lescale\" has 3 values, nx*ny*nz = 2"},
        Case{"HomogeneousLescaleArray",
             W + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"float Lescale\" [1 2]\n", 2, 49,
             "\"Lescale\" takes one value here"},
        Case{"NanovdbMissingFile",
             W + "MakeNamedMedium \"m\" \"string type\" \"nanovdb\" \"string filename\" \"nothere.nvdb\"\n",
             2, 45, "cannot open"},
        Case{"NanovdbNoFilename", W + "MakeNamedMedium \"m\" \"string type\" \"nanovdb\"\n", 2, 1,
             "missing \"string filename\""},
        Case{"OpenvdbMissingFile",
             W + "MakeNamedMedium \"m\" \"string type\" \"openvdb\" \"string filename\" \"nothere.vdb\"\n", 2,
             45, "cannot open"}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

TEST(PbrtErrorsFiles, ErrorInsideAnIncludedFileNamesThatFile) {
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string inc = dir.write("sub/inc.pbrt", "# comment\nShape \"sphere\" \"float radius\" \"x\"\n");
    const std::string main = dir.write("main.pbrt", "WorldBegin\nInclude \"sub/inc.pbrt\"\n");
    expect_pbrt_error(main, 2, 16, "needs numbers", inc);
}

TEST(PbrtErrorsFiles, IncludeCycle) {
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string a = dir.write("a.pbrt", "WorldBegin\nInclude \"b.pbrt\"\n");
    const std::string b = dir.write("b.pbrt", "\n\n  Import \"a.pbrt\"\n");
    expect_pbrt_error(a, 3, 3, "Include cycle", b);
}

TEST(PbrtErrorsFiles, MissingSceneFile) {
    EXPECT_THROW(load_pbrt("/nonexistent/dir/scene.pbrt"), ParseError);
}

TEST(PbrtErrorsFiles, MissingPlyFileIsReportedAtTheParameter) {
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string p =
        dir.write("m.pbrt", "WorldBegin\nShape \"plymesh\" \"string filename\" \"none.ply\"\n");
    expect_pbrt_error(p, 2, 17, "cannot open", p);
}

TEST(PbrtErrorsFiles, UnreadableVolumeFileIsReportedAtTheFilename) {
    QuietLog quiet;
    PbrtTempDir dir;
    dir.write("vol/garbage.nvdb", std::string(1000, 'x'));
    dir.write("vol/garbage.vdb", std::string(1000, 'x'));
    const std::string a =
        dir.write("a.pbrt",
                  "WorldBegin\n\nMakeNamedMedium \"m\" \"string type\" \"nanovdb\"\n   \"string filename\" "
                  "\"vol/garbage.nvdb\"\n");
    expect_pbrt_error(a, 4, 4, "garbage.nvdb", a);
    expect_pbrt_error(a, 4, 4, "not a NanoVDB file", a);
    const std::string b =
        dir.write("b.pbrt",
                  "WorldBegin\nMakeNamedMedium \"m\" \"string type\" \"nanovdb\" \"string filename\" "
                  "\"vol/garbage.vdb\"\n");
    expect_pbrt_error(b, 2, 45, "cannot read it as an OpenVDB file", b);
    const std::string c =
        dir.write("c.pbrt",
                  "WorldBegin\nMakeNamedMedium \"m\" \"string type\" \"nanovdb\" \"string filename\" "
                  "\"vol/cloud.txt\"\n");
    dir.write("vol/cloud.txt", "not a volume");
    expect_pbrt_error(c, 2, 45, "unknown extension", c);
}

TEST(PbrtErrorsFiles, MalformedPlyIsReportedInThePlyFile) {
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string ply = dir.write("bad.ply",
                                      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                      "property float y\nproperty float z\nend_header\n0 0 zero\n");
    const std::string p =
        dir.write("m.pbrt", "WorldBegin\nShape \"plymesh\" \"string filename\" \"bad.ply\"\n");
    expect_pbrt_error(p, 8, 5, "malformed number", ply);
}

// Errors inside included files (and PLY meshes they name) also name every Include / Import
// directive, and the plymesh's filename parameter, that led there, innermost first.
TEST(PbrtErrorsFiles, ErrorsInIncludedFilesNameTheIncludingLines) {
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string inc = dir.write("sub/inc.pbrt", "# comment\nShape \"sphere\" \"float radius\" \"x\"\n");
    const std::string main = dir.write("main.pbrt", "WorldBegin\n  Include \"sub/inc.pbrt\"\n");
    try {
        load_pbrt(main);
        FAIL() << "expected a ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.file, inc);
        EXPECT_EQ(e.included_from, std::vector<std::string>{main + ":2:3"});
        EXPECT_EQ(std::string(e.what()), inc + ":2:16: " + e.message + "\n  included from " + main + ":2:3");
    }
    dir.write("sub/bad.ply",
              "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
              "property float y\nproperty float z\nend_header\n0 0 zero\n");
    dir.write("sub/mesh.pbrt", "\nShape \"plymesh\" \"string filename\" \"bad.ply\"\n");
    const std::string top = dir.write("top.pbrt", "WorldBegin\nImport \"sub/mesh.pbrt\"\n");
    try {
        load_pbrt(top);
        FAIL() << "expected a ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.file, dir.file("sub/bad.ply"));
        EXPECT_EQ(e.line, 8);
        const std::vector<std::string> chain{dir.file("sub/mesh.pbrt") + ":2:17", top + ":2:1"};
        EXPECT_EQ(e.included_from, chain);
    }
    // An error at the Include itself (a cycle) is in the including file: one line less.
    const std::string a = dir.write("a.pbrt", "WorldBegin\nInclude \"b.pbrt\"\n");
    const std::string b = dir.write("b.pbrt", "\n\n  Import \"a.pbrt\"\n");
    try {
        load_pbrt(a);
        FAIL() << "expected a ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.file, b);
        EXPECT_EQ(e.included_from, std::vector<std::string>{a + ":2:1"});
    }
}

}  // namespace
}  // namespace phos::io::test
