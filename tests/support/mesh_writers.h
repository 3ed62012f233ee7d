// Mesh writers for the tests of the mesh readers and of the scene formats that reference mesh
// files: a TriangleMesh as PLY (ASCII or binary little-endian) or OBJ, floats written so they read
// back exactly.
#pragma once

#include <bit>
#include <cstdint>
#include <fstream>
#include <string>

#include "core/error.h"
#include "scene/shape.h"

namespace phos::testing {

// The unit square in the plane z = 0 as two triangles (counter-clockwise about +z).
inline scene::TriangleMesh unit_quad() {
    scene::TriangleMesh quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    return quad;
}

inline void write_ply(const std::string& path, const scene::TriangleMesh& mesh, bool binary) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw InputError("cannot write PLY file '" + path + "'");
    const bool normals = mesh.normals.size() == mesh.positions.size() && !mesh.normals.empty();
    const bool uvs = mesh.uvs.size() == mesh.positions.size() && !mesh.uvs.empty();
    out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\n";
    out << "comment written by phos\n";
    out << "element vertex " << mesh.positions.size() << "\n";
    out << "property float x\nproperty float y\nproperty float z\n";
    if (normals) out << "property float nx\nproperty float ny\nproperty float nz\n";
    if (uvs) out << "property float u\nproperty float v\n";
    out << "element face " << mesh.triangle_count() << "\n";
    out << "property list uchar int vertex_indices\nend_header\n";
    auto put_f = [&](float f) {
        if constexpr (std::endian::native == std::endian::big) {
            uint32_t b = std::bit_cast<uint32_t>(f);
            b = (b >> 24) | ((b >> 8) & 0xff00u) | ((b << 8) & 0xff0000u) | (b << 24);
            f = std::bit_cast<float>(b);
        }
        out.write(reinterpret_cast<const char*>(&f), 4);
    };
    auto put_i = [&](uint32_t i) {
        if constexpr (std::endian::native == std::endian::big)
            i = (i >> 24) | ((i >> 8) & 0xff00u) | ((i << 8) & 0xff0000u) | (i << 24);
        out.write(reinterpret_cast<const char*>(&i), 4);
    };
    if (binary) {
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            const Vec3 p = mesh.positions[i];
            put_f(p.x), put_f(p.y), put_f(p.z);
            if (normals) put_f(mesh.normals[i].x), put_f(mesh.normals[i].y), put_f(mesh.normals[i].z);
            if (uvs) put_f(mesh.uvs[i].x), put_f(mesh.uvs[i].y);
        }
        for (size_t t = 0; t < mesh.triangle_count(); ++t) {
            out.put(char(3));
            for (int k = 0; k < 3; ++k) put_i(mesh.indices[3 * t + size_t(k)]);
        }
    } else {
        out.precision(9);  // round-trips float exactly
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            const Vec3 p = mesh.positions[i];
            out << p.x << ' ' << p.y << ' ' << p.z;
            if (normals)
                out << ' ' << mesh.normals[i].x << ' ' << mesh.normals[i].y << ' ' << mesh.normals[i].z;
            if (uvs) out << ' ' << mesh.uvs[i].x << ' ' << mesh.uvs[i].y;
            out << '\n';
        }
        for (size_t t = 0; t < mesh.triangle_count(); ++t)
            out << "3 " << mesh.indices[3 * t] << ' ' << mesh.indices[3 * t + 1] << ' '
                << mesh.indices[3 * t + 2] << '\n';
    }
    if (!out) throw InputError("error writing PLY file '" + path + "'");
}

inline void write_obj(const std::string& path, const scene::TriangleMesh& mesh) {
    std::ofstream out(path);
    if (!out) throw InputError("cannot write OBJ file '" + path + "'");
    const bool normals = !mesh.normals.empty() && mesh.normals.size() == mesh.positions.size();
    const bool uvs = !mesh.uvs.empty() && mesh.uvs.size() == mesh.positions.size();
    out.precision(9);  // round-trips float exactly
    out << "# written by phos\n";
    for (const Vec3& p : mesh.positions) out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    if (normals)
        for (const Vec3& n : mesh.normals) out << "vn " << n.x << ' ' << n.y << ' ' << n.z << '\n';
    if (uvs)
        for (const Vec2& t : mesh.uvs) out << "vt " << t.x << ' ' << t.y << '\n';
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        out << 'f';
        for (int k = 0; k < 3; ++k) {
            const uint32_t i = mesh.indices[3 * t + size_t(k)] + 1;
            out << ' ' << i;
            if (uvs || normals) out << '/';
            if (uvs) out << i;
            if (normals) out << '/' << i;
        }
        out << '\n';
    }
    if (!out) throw InputError("error writing OBJ file '" + path + "'");
}

}  // namespace phos::testing
