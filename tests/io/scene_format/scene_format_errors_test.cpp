// Malformed `.scene` / `.mesh` / `.mat` / PLY inputs: each must throw a ParseError naming the file
// at fault (not only the .scene), the line and column, with a message that says what is wrong.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "core/log.h"
#include "io/scene_format/scene_format_loader.h"
#include "test_util.h"

namespace phos::io {
namespace {

using namespace std::string_literals;

const std::string kQuadPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
// A 1x1 PFM image (grey 0.5), a texture every decoder reads.
const std::string kPfm =
    "PF\n1 1\n-1\n"s + std::string("\x00\x00\x00\x3f\x00\x00\x00\x3f\x00\x00\x00\x3f", 12);

struct Case {
    std::string name;
    std::string main;                                        // main.scene
    std::vector<std::pair<std::string, std::string>> files;  // beside it (w.mat, q.ply, q.mesh always)
    std::string file;                                        // where the error is expected
    int line, col;
    std::string message;
};

const std::vector<Case> kCases = {
    {"UnknownCommand",
     "spere 1 0 0 0 w.mat\n",
     {},
     "main.scene",
     1,
     1,
     "unknown command 'spere'; did you mean 'sphere'?"},
    {"SphereShort",
     "sphere 1 0 0 w.mat\n",
     {},
     "main.scene",
     1,
     19,
     "expected 5 arguments: r cx cy cz file.mat, got 4"},
    {"SphereExtra", "sphere 1 0 0 0 w.mat extra\n", {}, "main.scene", 1, 22, "extra argument 'extra'"},
    {"NegativeRadius", "sphere -1 0 0 0 w.mat\n", {}, "main.scene", 1, 8, "radius must be positive"},
    {"NaN", "sphere 1 nan 0 0 w.mat\n", {}, "main.scene", 1, 10, "'nan' is not a finite number"},
    {"InfInLight", "light point 0 inf 0 1 1 1\n", {}, "main.scene", 1, 15, "'inf' is not a finite number"},
    {"WordForNumber",
     "camera 0 0 5 0 0 zero 0 1 0 4\n",
     {},
     "main.scene",
     1,
     18,
     "expected a number, got 'zero'"},
    {"MissingMeshFile",
     "# objects\nmesh nothere.mesh\n",
     {},
     "main.scene",
     2,
     6,
     "cannot open mesh file 'nothere.mesh': no such file"},
    {"MissingMatInMesh",
     "mesh m.mesh\n",
     {{"m.mesh", "ply q.ply\nmaterial none.mat\n"}},
     "m.mesh",
     2,
     10,
     "cannot open material file 'none.mat'"},
    {"MissingPly",
     "mesh m.mesh\n",
     {{"m.mesh", "ply none.ply\nmaterial w.mat\n"}},
     "m.mesh",
     1,
     5,
     "cannot open PLY file 'none.ply'"},
    {"CycleThroughMesh",
     "mesh c.mesh\n",
     {{"c.mesh", "ply q.ply\nmaterial main.scene\n"}},
     "c.mesh",
     2,
     10,
     "is already being read (a cycle"},
    {"SelfCycle", "mesh main.scene\n", {}, "main.scene", 1, 6, "is already being read (a cycle"},
    {"UnknownMatKey",
     "sphere 1 0 0 0 u.mat\n",
     {{"u.mat", "difuse 1 1 1\n"}},
     "u.mat",
     1,
     1,
     "unknown key 'difuse' in a .mat file; did you mean 'diffuse'?"},
    {"UnknownMeshKey",
     "mesh m.mesh\n",
     {{"m.mesh", "ply q.ply\nmaterial w.mat\ntranslat 0 1 0\n"}},
     "m.mesh",
     3,
     1,
     "unknown key 'translat' in a .mesh file; did you mean 'translate'?"},
    {"EnergyAboveOne",
     "sphere 1 0 0 0 e.mat\n",
     {{"e.mat", "diffuse 0.5 0.6 0.5\nspecular 0.5 0.5 0.5\n"}},
     "e.mat",
     2,
     1,
     "diffuse + specular + transmission is 1.1 in the green channel; it must not exceed 1"},
    {"NegativeDiffuse",
     "sphere 1 0 0 0 n.mat\n",
     {{"n.mat", "diffuse 0.5 -0.1 0.5\n"}},
     "n.mat",
     1,
     13,
     "must not be negative"},
    {"PhaseOutOfRange",
     "sphere 1 0 0 0 p.mat\n",
     {{"p.mat", "scattering 1 1 1\nphase 1\n"}},
     "p.mat",
     2,
     7,
     "g must be in (-1, 1)"},
    {"IorZero",
     "sphere 1 0 0 0 g.mat\n",
     {{"g.mat", "transmission 1 1 1\nior 0\n"}},
     "g.mat",
     2,
     5,
     "index of refraction must be positive"},
    {"AbbeWithoutIor",
     "sphere 1 0 0 0 a.mat\n",
     {{"a.mat", "transmission 1 1 1\nabbe 40\n"}},
     "a.mat",
     2,
     1,
     "abbe: needs 'ior', the index n_d at the d line (587.6 nm)"},
    {"AbbeNotPositive",
     "sphere 1 0 0 0 a.mat\n",
     {{"a.mat", "transmission 1 1 1\nior 1.5\nabbe -3\n"}},
     "a.mat",
     3,
     6,
     "abbe: the Abbe number V_d must be positive, got '-3'"},
    {"AbbeIorNotAboveOne",
     "sphere 1 0 0 0 a.mat\n",
     {{"a.mat", "transmission 1 1 1\nior 0.9\nabbe 40\n"}},
     "a.mat",
     2,
     5,
     "ior: with 'abbe' the index n_d must exceed 1, got '0.9'"},
    {"CauchyShort",
     "sphere 1 0 0 0 c.mat\n",
     {{"c.mat", "cauchy 1.5\n"}},
     "c.mat",
     1,
     11,
     "cauchy: expected 2 numbers: A B (B in um^2), got 1 argument"},
    {"CauchyBNotPositive",
     "sphere 1 0 0 0 c.mat\n",
     {{"c.mat", "transmission 1 1 1\ncauchy 1.5 0\n"}},
     "c.mat",
     2,
     12,
     "cauchy: B must be positive, got '0'"},
    {"CauchyNotFinite",
     "sphere 1 0 0 0 c.mat\n",
     {{"c.mat", "transmission 1 1 1\ncauchy inf 0.01\n"}},
     "c.mat",
     2,
     8,
     "'inf' is not a finite number"},
    {"CauchyAndIor",
     "sphere 1 0 0 0 c.mat\n",
     {{"c.mat", "transmission 1 1 1\ncauchy 1.5 0.01\nior 1.5\n"}},
     "c.mat",
     3,
     1,
     "ior: the index is given by 'cauchy' (line 2), 1.529 at the d line (587.6 nm); give one of them"},
    {"SellmeierNegative",
     "sphere 1 0 0 0 s.mat\n",
     {{"s.mat", "transmission 1 1 1\nsellmeier 1 0.2 1 -0.006 0.02 100\n"}},
     "s.mat",
     2,
     19,
     "sellmeier: must not be negative, got '-0.006'"},
    {"SellmeierVisibleResonance",
     "sphere 1 0 0 0 s.mat\n",
     {{"s.mat", "transmission 1 1 1\nsellmeier 1 0.2 1 0.006 0.25 100\n"}},
     "s.mat",
     2,
     25,
     "sellmeier: C2 = 0.25 um^2 puts a resonance at 500 nm, inside the visible range (360-830 nm)"},
    {"SellmeierNoB",
     "sphere 1 0 0 0 s.mat\n",
     {{"s.mat", "transmission 1 1 1\nsellmeier 0 0 0 0.006 0.02 100\n"}},
     "s.mat",
     2,
     11,
     "sellmeier: B1, B2 and B3 are all 0"},
    {"UnknownGlass",
     "sphere 1 0 0 0 g.mat\n",
     {{"g.mat", "transmission 1 1 1\nglass BK8\n"}},
     "g.mat",
     2,
     7,
     "glass: unknown glass 'BK8'; did you mean 'BK7'? (glasses: BK7, BAF10"},
    {"GlassWithoutName",
     "sphere 1 0 0 0 g.mat\n",
     {{"g.mat", "transmission 1 1 1\nglass\n"}},
     "g.mat",
     2,
     6,
     "glass: expected 1 argument: a glass name, got 0 arguments"},
    {"TwoDispersionKeys",
     "sphere 1 0 0 0 g.mat\n",
     {{"g.mat", "transmission 1 1 1\nglass BK7\ncauchy 1.5 0.01\n"}},
     "g.mat",
     3,
     1,
     "cauchy: the dispersion is already given by 'glass' (line 2); a material takes one of abbe, cauchy, "
     "sellmeier, glass"},
    {"DispersionKeyTwice",
     "sphere 1 0 0 0 g.mat\n",
     {{"g.mat", "transmission 1 1 1\nglass BK7\nglass SF10\n"}},
     "g.mat",
     3,
     1,
     "'glass' is given twice (first at line 2)"},
    {"DuplicateMatKey",
     "sphere 1 0 0 0 d.mat\n",
     {{"d.mat", "diffuse 0.1 0.1 0.1\ndiffuse 0.2 0.2 0.2\n"}},
     "d.mat",
     2,
     1,
     "'diffuse' is given twice (first at line 1)"},
    {"TextureWithoutUv",
     "mesh t.mesh\n",
     {{"t.mesh", "ply q.ply\nmaterial t.mat\n"},
      {"t.mat", "diffuse 1 1 1\ntexture tex.pfm\n"},
      {"tex.pfm", kPfm}},
     "t.mesh",
     1,
     5,
     "'q.ply' has no texture coordinates (vertex properties u v or s t), but its material 't.mat'"},
    {"UnreadableTexture",
     "sphere 1 0 0 0 b.mat\n",
     {{"b.mat", "diffuse 1 1 1\ntexture bad.png\n"}, {"bad.png", "no png"}},
     "b.mat",
     2,
     9,
     "texture: cannot read 'bad.png'"},
    {"MissingTexture",
     "sphere 1 0 0 0 b.mat\n",
     {{"b.mat", "diffuse 1 1 1\ntexture gone.png\n"}},
     "b.mat",
     2,
     9,
     "cannot open texture 'gone.png': no such file"},
    {"LightZeroNormal", "light area 0 1 0 0 0 0 1 1 1 1 1\n", {}, "main.scene", 1, 18, "the normal is zero"},
    {"LightNegativeWidth",
     "light area 0 1 0 0 -1 0 1 1 1 -2 1\n",
     {},
     "main.scene",
     1,
     31,
     "the width must be positive"},
    {"LightNegativeFlux", "light point 0 1 0 1 -1 1\n", {}, "main.scene", 1, 21, "must not be negative"},
    {"UnknownLightType",
     "light spot 0 1 0 1 1 1\n",
     {},
     "main.scene",
     1,
     7,
     "unknown type 'spot' (point or area)"},
    {"LightPointShort",
     "light point 0 1 0 1 1\n",
     {},
     "main.scene",
     1,
     22,
     "expected 6 numbers: px py pz  r g b, got 5"},
    {"LightWithoutType", "light\n", {}, "main.scene", 1, 6, "expected a type, 'point' or 'area'"},
    {"CameraZeroD",
     "camera 0 0 5 0 0 0 0 1 0 0\n",
     {},
     "main.scene",
     1,
     26,
     "d (the distance to an image plane"},
    {"CameraUpParallel",
     "camera 0 0 5 0 0 0 0 0 1 4\n",
     {},
     "main.scene",
     1,
     20,
     "parallel to the viewing direction"},
    {"CameraLookAtEye",
     "camera 1 2 3 1 2 3 0 1 0 4\n",
     {},
     "main.scene",
     1,
     14,
     "the look-at point is the eye"},
    {"ResolutionFraction", "resolution 100.5 100\n", {}, "main.scene", 1, 12, "whole number of pixels"},
    {"SkyNegative", "sky 0 -1 0\n", {}, "main.scene", 1, 7, "must not be negative"},
    {"MeshWithoutMaterial",
     "mesh m.mesh\n",
     {{"m.mesh", "ply q.ply\n"}},
     "m.mesh",
     2,
     1,
     "names no material"},
    {"MeshWithoutPly",
     "mesh m.mesh\n",
     {{"m.mesh", "material w.mat\n"}},
     "m.mesh",
     2,
     1,
     "names no geometry"},
    {"MeshDuplicatePly",
     "mesh m.mesh\n",
     {{"m.mesh", "ply q.ply\nply q.ply\nmaterial w.mat\n"}},
     "m.mesh",
     2,
     1,
     "'ply' is given twice"},
    {"ScaleZero",
     "mesh m.mesh\n",
     {{"m.mesh", "ply q.ply\nmaterial w.mat\nscale 1 0 1\n"}},
     "m.mesh",
     3,
     9,
     "a zero scale"},
    {"RotateZeroAxis",
     "mesh m.mesh\n",
     {{"m.mesh", "ply q.ply\nmaterial w.mat\nrotate 30 0 0 0\n"}},
     "m.mesh",
     3,
     11,
     "the axis is zero"},
    {"TranslateWord",
     "mesh m.mesh\n",
     {{"m.mesh", "ply q.ply\nmaterial w.mat\ntranslate 0 x 0\n"}},
     "m.mesh",
     3,
     13,
     "expected a number, got 'x'"},
    {"ScaleTwoNumbers",
     "mesh m.mesh\n",
     {{"m.mesh", "ply q.ply\nmaterial w.mat\nscale 1 2\n"}},
     "m.mesh",
     3,
     10,
     "expected 3 numbers: sx sy sz, got 2"},
    {"BrokenPly",
     "mesh m.mesh\n",
     {{"m.mesh", "ply bad.ply\nmaterial w.mat\n"},
      {"bad.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 "
       "2\n"}},
     "bad.ply",
     11,
     3,
     "zero"},
    {"BinaryMat",
     "sphere 1 0 0 0 x.mat\n",
     {{"x.mat", "diffuse 1 1 1\n\x01\x02"s}},
     "x.mat",
     2,
     1,
     "binary or control byte 0x01"},
    {"MediumTwice",
     "medium s.mat\nmedium s.mat\n",
     {{"s.mat", "scattering 1 1 1\n"}},
     "main.scene",
     2,
     1,
     "already has a medium"},
    {"MeshIsDirectory", "mesh sub\n", {{"sub/x", ""}}, "main.scene", 1, 6, "is a directory"},
};

class SceneFormatErrors : public ::testing::TestWithParam<Case> {};

TEST_P(SceneFormatErrors, LocatedInTheFileAtFault) {
    log::set_quiet(true);
    const Case& c = GetParam();
    testing::TempDir dir;
    dir.write("w.mat", "diffuse 0.5 0.5 0.5\n");
    dir.write("q.ply", kQuadPly);
    for (const auto& [name, text] : c.files) dir.write(name, text);
    const std::string main = dir.write("main.scene", c.main);
    testing::expect_parse_error_from([&] { load_scene_format(main); }, dir.file(c.file), c.line, c.col,
                                     c.message);
}

INSTANTIATE_TEST_SUITE_P(Cases, SceneFormatErrors, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& i) { return i.param.name; });

// An error in a .mesh, .mat or PLY file also names the lines that named it (a .scene's mesh or
// sphere, a .mesh's ply or material), innermost first, at the file name they give.
TEST(SceneFormatErrorsIncluded, NameTheIncludingLines) {
    log::set_quiet(true);
    testing::TempDir dir;
    dir.write("q.ply", kQuadPly);
    dir.write("sub/w.mat", "diffuse 0.5 0.5 0.5\n");
    dir.write("sub/u.mat", "\ndifuse 1 1 1\n");
    dir.write("sub/bad.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nend_header\n0 0 zero\n");
    dir.write("sub/ply.mesh", "ply bad.ply\nmaterial w.mat\n");
    dir.write("sub/mat.mesh", "ply ../q.ply\nmaterial u.mat\n");
    dir.write("sub/key.mesh", "ply ../q.ply\nmaterial w.mat\ntranslat 0 1 0\n");
    struct Case {
        std::string main, file;
        int line;
        std::vector<std::string> chain;  // relative names and positions, innermost first
    };
    const std::vector<Case> cases = {
        {"# a mesh\nmesh sub/ply.mesh\n", "sub/bad.ply", 8, {"sub/ply.mesh:1:5", "main.scene:2:6"}},
        {"mesh sub/mat.mesh\n", "sub/u.mat", 2, {"sub/mat.mesh:2:10", "main.scene:1:6"}},
        {"mesh   sub/key.mesh\n", "sub/key.mesh", 3, {"main.scene:1:8"}},
        {"sphere 1 0 0 0 sub/u.mat\n", "sub/u.mat", 2, {"main.scene:1:16"}},
    };
    for (const Case& c : cases) {
        const std::string main = dir.write("main.scene", c.main);
        try {
            load_scene_format(main);
            ADD_FAILURE() << "expected a ParseError: " << c.main;
        } catch (const ParseError& e) {
            EXPECT_EQ(e.file, dir.file(c.file)) << e.what();
            EXPECT_EQ(e.line, c.line) << e.what();
            std::vector<std::string> chain;
            for (const std::string& at : c.chain) chain.push_back(dir.file(at));
            EXPECT_EQ(e.included_from, chain) << e.what();
            std::string text = ParseError::format(e.file, e.line, e.column, e.message);
            for (const std::string& at : chain) text += "\n  included from " + at;
            EXPECT_EQ(std::string(e.what()), text);
        }
    }
    // An error in the .scene itself names no other file.
    const std::string main = dir.write("main.scene", "spere 1 0 0 0 sub/w.mat\n");
    try {
        load_scene_format(main);
        ADD_FAILURE() << "expected a ParseError";
    } catch (const ParseError& e) {
        EXPECT_TRUE(e.included_from.empty()) << e.what();
    }
}

}  // namespace
}  // namespace phos::io
