// Inputs found by fuzzing the pbrt reader (fuzz/pbrt_fuzzer.cpp, scripts/fuzz.sh), kept as
// regression tests: each must be a ParseError at the offending place, not undefined behaviour.
#include <gtest/gtest.h>

#include "pbrt_test_util.h"

namespace phos::io::test {
namespace {

// "integer xresolution" 1e38 must not be converted to int unchecked (undefined behaviour, reported
// by UBSan); integer parameters must fit an int.
TEST(PbrtFuzz, IntegerParameterBeyondIntIsAnError) {
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string path = dir.write(
        "big.pbrt", "Film \"rgb\" \"integer xresolution\" 1e38 \"integer yresolution\" [ 256 ]\n" + kWorld);
    expect_pbrt_error(path, 1, 12, "integer parameter \"integer xresolution\" has a value out of range",
                      path);
    const std::string negative =
        dir.write("neg.pbrt", kWorld +
                                  "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\n"
                                  "  \"integer indices\" [0 1 -3000000000]\n");
    expect_pbrt_error(negative, 3, 3, "value out of range", negative);
}

// A file name longer than the file system allows makes std::filesystem::exists throw
// filesystem_error ("File name too long"), which must not escape the loader: it is a file not found.
TEST(PbrtFuzz, OverlongFileNameIsNotFound) {
    QuietLog quiet;
    PbrtTempDir dir;
    const std::string name(300, 'x');
    const std::string light = dir.write(
        "light.pbrt", kWorld + "LightSource \"infinite\" \"string filename\" \"" + name + ".pfm\"\n");
    expect_pbrt_error(light, 2, 24, "cannot read", light);
    const std::string ply =
        dir.write("ply.pbrt", kWorld + "Shape \"plymesh\" \"string filename\" \"" + name + ".ply\"\n");
    expect_pbrt_error(ply, 2, 17, "cannot open", ply);
}

}  // namespace
}  // namespace phos::io::test
