// Round-trip and malformed-input tests of the PLY and OBJ mesh readers and writers.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/log.h"
#include "io/mesh/mesh_io.h"
#include "support/gzip_writer.h"
#include "support/mesh_writers.h"
#include "test_util.h"

namespace phos::io {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
    // One directory per test process: ctest runs the parameterised cases in parallel.
    const fs::path d = fs::temp_directory_path() / ("phos_ply_obj_test_" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
}

std::string write_file(const std::string& name, const std::string& text) {
    const fs::path p = temp_dir() / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
}

// A small mesh with all attributes and non-trivial values.
scene::TriangleMesh sample_mesh(bool normals, bool uvs) {
    scene::TriangleMesh m;
    m.positions = {{0, 0, 0}, {1.5f, 0, 0.25f}, {1, 2, -3}, {0.1f, 1e-3f, 7}, {-2, -1, 1.0f / 3.0f}};
    if (normals) m.normals = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0.6f, 0.8f, 0}, {0, -1, 0}};
    if (uvs) m.uvs = {{0, 0}, {1, 0}, {0.5f, 1}, {0.25f, 0.75f}, {1.0f / 3.0f, 0.9f}};
    m.indices = {0, 1, 2, 0, 2, 3, 3, 2, 4};
    return m;
}

void expect_same(const scene::TriangleMesh& a, const scene::TriangleMesh& b) {
    ASSERT_EQ(a.positions.size(), b.positions.size());
    for (size_t i = 0; i < a.positions.size(); ++i) EXPECT_EQ(a.positions[i], b.positions[i]) << i;
    ASSERT_EQ(a.normals.size(), b.normals.size());
    for (size_t i = 0; i < a.normals.size(); ++i) EXPECT_EQ(a.normals[i], b.normals[i]) << i;
    ASSERT_EQ(a.uvs.size(), b.uvs.size());
    for (size_t i = 0; i < a.uvs.size(); ++i) EXPECT_EQ(a.uvs[i], b.uvs[i]) << i;
    EXPECT_EQ(a.indices, b.indices);
}

class PlyRoundTrip : public ::testing::TestWithParam<std::tuple<bool, bool, bool>> {};

TEST_P(PlyRoundTrip, WriteThenReadGivesTheSameMesh) {
    const auto [binary, normals, uvs] = GetParam();
    const scene::TriangleMesh m = sample_mesh(normals, uvs);
    const std::string path = (temp_dir() / "rt.ply").string();
    testing::write_ply(path, m, binary);
    expect_same(m, read_ply(path));
}

INSTANTIATE_TEST_SUITE_P(AllVariants, PlyRoundTrip,
                         ::testing::Combine(::testing::Bool(), ::testing::Bool(), ::testing::Bool()));

TEST(Ply, AsciiQuadIsFanTriangulatedAndExtraPropertiesSkipped) {
    const std::string path =
        write_file("quad.ply",
                   "ply\r\nformat ascii 1.0\ncomment hi\n"
                   "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                   "property uchar red\nproperty float s\nproperty float t\n"
                   "element edge 1\nproperty list uchar int stuff\n"
                   "element face 1\nproperty uchar flags\nproperty list int uint vertex_index\n"
                   "end_header\n"
                   "0 0 0 255 0 0\n1 0 0 3 1 0\n1 1 0 4 1 1\n0 1 0 9 0 1\n"
                   "2 7 8\n"
                   "7 4 0 1 2 3\n");
    const scene::TriangleMesh m = read_ply(path);
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_TRUE(m.normals.empty());
    ASSERT_EQ(m.uvs.size(), 4u);
    EXPECT_EQ(m.uvs[2], Vec2(1, 1));
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
}

// Big-endian binary with a short count type and double positions.
TEST(Ply, BinaryBigEndian) {
    std::string text =
        "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
        "property double z\nelement face 1\nproperty list ushort short vertex_indices\nend_header\n";
    auto put_be = [&](const void* p, int n) {
        const char* c = static_cast<const char*>(p);
        for (int i = n - 1; i >= 0; --i) text.push_back(c[i]);  // this test assumes a little-endian host
    };
    const double xyz[9] = {0, 0, 0, 2, 0, 0, 0, 3, -1};
    for (double d : xyz) put_be(&d, 8);
    const uint16_t count = 3;
    put_be(&count, 2);
    const int16_t idx[3] = {2, 1, 0};
    for (int16_t i : idx) put_be(&i, 2);
    const scene::TriangleMesh m = read_ply(write_file("be.ply", text));
    ASSERT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.positions[2], Vec3(0, 3, -1));
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{2, 1, 0}));
}

void expect_ply_error(const std::string& text, int line, int col, const std::string& fragment) {
    const std::string path = write_file("bad.ply", text);
    try {
        read_ply(path);
        FAIL() << "no error for: " << fragment;
    } catch (const ParseError& e) {
        EXPECT_EQ(e.line, line) << e.what();
        if (col > 0) {
            EXPECT_EQ(e.column, col) << e.what();
        }
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
}

const std::string kHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

TEST(Ply, MalformedInputs) {
    expect_ply_error("plx\n", 1, 1, "magic");
    expect_ply_error("ply\nformat weird 1.0\nend_header\n", 2, 8, "unknown PLY format");
    expect_ply_error("ply\nformat ascii 1.0\nelement vertex\nend_header\n", 3, 1, "malformed element");
    expect_ply_error("ply\nformat ascii 1.0\nproperty float x\n", 3, 1, "before any element");
    expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty quux x\n", 4, 1,
                     "malformed property");
    expect_ply_error("ply\nformat ascii 1.0\nelement vertex 0\n", 3, 1, "end of file in the PLY header");
    expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n", 3, 1,
                     "lacks x, y or z");
    expect_ply_error(kHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", 13, 7, "out of range");
    expect_ply_error(kHeader + "0 0 0\n1 zz 0\n0 1 0\n3 0 1 2\n", 11, 3, "malformed number");
    expect_ply_error(kHeader + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n", 11, 4, "too few values");
    expect_ply_error(kHeader + "0 0 0\n1 0 0\n0 1 0\n", 13, 0, "unexpected end of file");
    expect_ply_error(kHeader + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", 13, 0, "fewer than 3");
    expect_ply_error(kHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", 13, 5, "expected an integer");
    expect_ply_error(kHeader + "0 0 0 9\n1 0 0\n0 1 0\n3 0 1 2\n", 10, 0, "extra values");
}

TEST(Ply, BinaryErrorsGiveTheByteOffset) {
    std::string text =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const size_t header = text.size();
    for (int i = 0; i < 9; ++i) {
        const float f = float(i);
        text.append(reinterpret_cast<const char*>(&f), 4);
    }
    text.push_back(char(3));
    const int32_t idx[3] = {0, 1, 7};
    text.append(reinterpret_cast<const char*>(idx), 12);
    try {
        read_ply(write_file("badbin.ply", text));
        FAIL();
    } catch (const ParseError& e) {
        EXPECT_EQ(e.line, 0);
        const std::string want = "byte offset " + std::to_string(header + 36 + 1 + 8);
        EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
    }
    // Truncated body.
    try {
        read_ply(write_file("trunc.ply", text.substr(0, header + 20)));
        FAIL();
    } catch (const ParseError& e) {
        EXPECT_NE(std::string(e.what()).find("unexpected end of file"), std::string::npos) << e.what();
    }
}

TEST(Ply, MissingFile) { EXPECT_THROW(read_ply((temp_dir() / "nope.ply").string()), ParseError); }

class ObjRoundTrip : public ::testing::TestWithParam<std::tuple<bool, bool>> {};

TEST_P(ObjRoundTrip, WriteThenReadGivesTheSameMesh) {
    const auto [normals, uvs] = GetParam();
    const scene::TriangleMesh m = sample_mesh(normals, uvs);
    const std::string path = (temp_dir() / "rt.obj").string();
    testing::write_obj(path, m);
    const LoadedMesh l = read_obj(path);
    expect_same(m, l.mesh);
    EXPECT_TRUE(l.triangle_materials.empty());
}

INSTANTIATE_TEST_SUITE_P(AllVariants, ObjRoundTrip, ::testing::Combine(::testing::Bool(), ::testing::Bool()));

TEST(Obj, SplitsVerticesWithDifferentNormalsAndReadsMaterials) {
    write_file("m.mtl", "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n");
    const std::string path = write_file("cube.obj",
                                        "mtllib m.mtl\n"
                                        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                        "vn 0 0 1\nvn 0 0 -1\n"
                                        "usemtl blue\nf 1//1 2//1 3//1 4//1\n"
                                        "usemtl red\nf 1//2 3//2 2//2\n");
    const LoadedMesh l = read_obj(path);
    // Quad -> 2 triangles, + 1 triangle; the shared positions with another normal are duplicated.
    EXPECT_EQ(l.mesh.triangle_count(), 3u);
    EXPECT_EQ(l.mesh.positions.size(), 7u);
    ASSERT_EQ(l.mesh.normals.size(), 7u);
    ASSERT_EQ(l.material_names, (std::vector<std::string>{"red", "blue"}));
    EXPECT_EQ(l.triangle_materials, (std::vector<int>{1, 1, 0}));
    EXPECT_EQ(l.mesh.normals[l.mesh.indices[6]], Vec3(0, 0, -1));
    EXPECT_EQ(l.mesh.positions[l.mesh.indices[7]], Vec3(1, 1, 0));
}

TEST(Obj, MalformedInputsThrowParseError) {
    try {
        read_obj(write_file("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"));
        FAIL();
    } catch (const ParseError& e) {
        EXPECT_EQ(e.line, 4) << e.what();
    }
    try {
        read_obj(write_file("bad0.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 0 1 2\n"));
        FAIL();
    } catch (const ParseError& e) {
        EXPECT_EQ(e.line, 5) << e.what();
    }
    EXPECT_THROW(read_obj(write_file("empty.obj", "v 0 0 0\n")), ParseError);
    // an overflowing coordinate (the .scn and .scene loaders rely on the reader for this)
    try {
        read_obj(write_file("inf.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n"));
        FAIL();
    } catch (const ParseError& e) {
        EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
    }
    EXPECT_THROW(read_obj((temp_dir() / "nope.obj").string()), ParseError);
}

TEST(Obj, MissingMaterialLibraryWarns) {
    log::set_quiet(true);
    const int before = log::warning_count();
    const LoadedMesh l =
        read_obj(write_file("nomtl.obj", "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    EXPECT_EQ(l.mesh.triangle_count(), 1u);
    EXPECT_GT(log::warning_count(), before);
    log::set_quiet(false);
}

// A gzip-compressed mesh (name.ply.gz, name.obj.gz, and a compressed file under its plain name) reads
// as the uncompressed file does: same positions, normals, uvs and indices.
TEST(MeshIo, GzippedMeshesReadAsTheUncompressedOnes) {
    const scene::TriangleMesh m = sample_mesh(true, true);
    for (const bool binary : {false, true}) {
        const std::string ply = temp_dir() / (binary ? "gz_bin.ply" : "gz_ascii.ply");
        phos::testing::write_ply(ply, m, binary);
        const std::string packed = phos::testing::gzip_bytes(phos::testing::read_bytes(ply));
        for (const std::string& name : {std::string(binary ? "gz_bin" : "gz_ascii") + ".ply.gz",
                                        std::string(binary ? "gz_bin_named" : "gz_ascii_named") + ".ply"}) {
            const scene::TriangleMesh back = read_mesh(write_file(name, packed)).mesh;
            EXPECT_EQ(back.positions, m.positions) << name;
            EXPECT_EQ(back.normals, m.normals) << name;
            EXPECT_EQ(back.uvs, m.uvs) << name;
            EXPECT_EQ(back.indices, m.indices) << name;
        }
    }
    const std::string obj = temp_dir() / "gz.obj";
    phos::testing::write_obj(obj, m);
    const LoadedMesh plain = read_mesh(obj);
    const LoadedMesh packed =
        read_mesh(write_file("gz.obj.gz", phos::testing::gzip_bytes(phos::testing::read_bytes(obj))));
    EXPECT_EQ(packed.mesh.positions, plain.mesh.positions);
    EXPECT_EQ(packed.mesh.indices, plain.mesh.indices);
    EXPECT_THROW(read_mesh(write_file("cut.ply.gz", phos::testing::gzip_bytes("ply\n").substr(0, 8))),
                 ParseError);
}

}  // namespace
}  // namespace phos::io
