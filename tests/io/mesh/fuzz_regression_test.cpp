// Inputs found by fuzzing the mesh readers (fuzz/ply_fuzzer.cpp, fuzz/obj_fuzzer.cpp,
// scripts/fuzz.sh), kept as regression tests: each must be read or rejected with a located
// ParseError, not crash, hang, hit undefined behaviour or allocate by a count the file cannot back.
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

std::string write_mesh(const std::string& name, const std::string& bytes) {
    const fs::path d = fs::temp_directory_path() / ("phos_mesh_fuzz_test_" + std::to_string(getpid()));
    fs::create_directories(d);
    const fs::path p = d / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p.string();
}

// Reads `bytes` as a PLY file and expects a ParseError at `line` whose message contains `what`.
void expect_ply_error(const std::string& bytes, int line, const std::string& what) {
    try {
        read_ply(write_mesh("fuzz.ply", bytes));
        ADD_FAILURE() << "accepted; expected an error containing '" << what << "'";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.line, line) << e.what();
        EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
}

const std::string kAsciiHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

// A face index of 1e300 in an ASCII file must not be converted to long long for the message
// (undefined behaviour); integer values must fit their declared type.
TEST(PlyFuzz, HugeAsciiIndexIsOutOfRangeForItsType) {
    expect_ply_error(kAsciiHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 1e300\n", 13,
                     "out of range for its property type");
    expect_ply_error(kAsciiHeader + "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n", 13,
                     "out of range for its property type");
    expect_ply_error(kAsciiHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n", 13, "out of range");
}

// Element counts the rest of the file cannot hold must not reserve memory for them (gigabytes, or
// std::bad_alloc) or, for an element without properties, loop that many times.
TEST(PlyFuzz, ElementCountsAreBoundedByTheFileSize) {
    expect_ply_error(
        "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\n"
        "property float y\nproperty float z\nend_header\n\x01\x02\x03",
        3, "declares 1000000000000 instances");
    expect_ply_error(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element nothing 9223372036854775807\nelement face 1\nproperty list uchar int vertex_indices\n"
        "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
        7, "element 'nothing' declares");
    // Enough bytes: the same file without the empty element still reads.
    const auto m = read_ply(write_mesh("ok.ply", kAsciiHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
    EXPECT_EQ(m.indices.size(), 3u);
}

// tinyobjloader's `vw` (skin weight) lines convert their joint ids to int unchecked; "1e38" was
// undefined behaviour (the fuzzer's input: "vw v 11e38l4" after a binary first line). phos uses no
// skin weights and blanks those lines, keeping line numbers for later errors.
TEST(ObjFuzz, SkinWeightLinesAreIgnored) {
    const std::string found(
        "m\xd0\xc6\x7f\0"
        "1\nvw v 11e38l4",
        19);
    EXPECT_THROW(read_obj(write_mesh("found.obj", found)), ParseError);
    const LoadedMesh m =
        read_obj(write_mesh("vw.obj", "v 0 0 0\nv 1 0 0\n\tvw 0 1e38 1\rv 0 1 0\nvw 1 0 0.5\r\nf 1 2 3\n"));
    EXPECT_EQ(m.mesh.positions.size(), 3u);
    EXPECT_EQ(m.mesh.indices.size(), 3u);
    // An error after a blanked line still names its own line (6).
    try {
        read_obj(write_mesh("line.obj", "v 0 0 0\nvw 0 1e38 1\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n"));
        ADD_FAILURE() << "accepted an out-of-range face index";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.line, 6) << e.what();
    }
}

}  // namespace
}  // namespace phos::io
