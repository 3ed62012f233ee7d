// Mesh refinement by longest-edge bisection and vertex displacement along normals, as pbrt-v4's
// TriQuadMesh::Refine / Displace / ComputeNormals (util/mesh.h) define them.
#include "scene/mesh_displacement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <unordered_map>

#include "core/error.h"

namespace phos::scene {

void refine_mesh(TriangleMesh& mesh, float max_edge, const EdgeLength& edge_length, size_t max_triangles) {
    const auto too_many = [&] {
        throw InputError("refining the mesh to edges shorter than " + std::to_string(max_edge) +
                         " makes too many triangles (more than " + std::to_string(max_triangles) + ")");
    };
    // Bisection leaves about 2 (L / max_edge)^2 triangles of a triangle whose longest edge is L:
    // refuse before allocating what could not be held.
    double estimate = 0;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        float longest = 0;
        for (int e = 0; e < 3; ++e)
            longest = std::max(longest, edge_length(mesh.positions[mesh.indices[i + size_t(e)]],
                                                    mesh.positions[mesh.indices[i + size_t((e + 1) % 3)]]));
        if (!std::isfinite(longest)) too_many();
        estimate += std::max(1.0, 2.0 * double(longest / max_edge) * double(longest / max_edge));
    }
    if (estimate > double(max_triangles)) too_many();
    const bool normals = !mesh.normals.empty(), uvs = !mesh.uvs.empty();
    // The vertex on the midpoint of each split edge, keyed by its sorted end vertices.
    std::unordered_map<uint64_t, uint32_t> midpoints;
    const auto midpoint = [&](uint32_t a, uint32_t b) {
        const uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
        if (const auto it = midpoints.find(key); it != midpoints.end()) return it->second;
        if (mesh.positions.size() >= 2 * max_triangles) too_many();
        const uint32_t m = uint32_t(mesh.positions.size());
        mesh.positions.push_back((mesh.positions[a] + mesh.positions[b]) * 0.5f);
        if (normals) {
            const Vec3 n = mesh.normals[a] + mesh.normals[b];
            const float l = length(n);
            mesh.normals.push_back(l > 0 ? n / l : mesh.normals[a]);
        }
        if (uvs) mesh.uvs.push_back((mesh.uvs[a] + mesh.uvs[b]) * 0.5f);
        midpoints.emplace(key, m);
        return m;
    };
    std::vector<uint32_t> out;
    out.reserve(mesh.indices.size());
    std::vector<std::array<uint32_t, 3>> stack;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        stack.push_back({mesh.indices[i], mesh.indices[i + 1], mesh.indices[i + 2]});
        while (!stack.empty()) {
            std::array<uint32_t, 3> v = stack.back();
            stack.pop_back();
            float d[3];
            for (int e = 0; e < 3; ++e)
                d[e] = edge_length(mesh.positions[v[size_t(e)]], mesh.positions[v[size_t((e + 1) % 3)]]);
            if (d[0] < max_edge && d[1] < max_edge && d[2] < max_edge) {
                if (out.size() >= 3 * max_triangles) too_many();
                out.insert(out.end(), v.begin(), v.end());
                continue;
            }
            // Rotate the longest edge to v0 v1 (keeping the winding), split it at m: (v0 m v2), (m v1 v2).
            const int longest = d[0] >= d[1] && d[0] >= d[2] ? 0 : (d[1] >= d[2] ? 1 : 2);
            std::rotate(v.begin(), v.begin() + longest, v.end());
            const uint32_t m = midpoint(v[0], v[1]);
            stack.push_back({m, v[1], v[2]});
            stack.push_back({v[0], m, v[2]});
        }
    }
    mesh.indices = std::move(out);
}

std::vector<Vec3> vertex_normals(const TriangleMesh& mesh) {
    std::vector<Vec3> n(mesh.positions.size(), Vec3(0.0f));
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
        const Vec3 w = cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
        n[a] += w, n[b] += w, n[c] += w;
    }
    for (Vec3& v : n) {
        const float l = length(v);
        if (l > 0) v = v / l;
    }
    return n;
}

void displace_mesh(TriangleMesh& mesh, float max_edge, const EdgeLength& edge_length,
                   const Displacement& displace, size_t max_triangles) {
    if (mesh.normals.size() != mesh.positions.size()) mesh.normals = vertex_normals(mesh);
    if (mesh.uvs.size() != mesh.positions.size()) mesh.uvs.clear();
    refine_mesh(mesh, max_edge, edge_length, max_triangles);
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const Vec2 uv = mesh.uvs.empty() ? Vec2(0, 0) : mesh.uvs[i];
        mesh.positions[i] += mesh.normals[i] * displace(mesh.positions[i], mesh.normals[i], uv);
    }
    mesh.normals = vertex_normals(mesh);
}

}  // namespace phos::scene
