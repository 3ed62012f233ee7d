// Mesh refinement and displacement (scene/mesh_displacement.h): every edge ends shorter than the
// edge length, the refined mesh stays watertight and keeps its area, a constant displacement moves
// a plane along its normal, a checkerboard one makes two heights, and normals are recomputed.
#include "scene/mesh_displacement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

#include "core/error.h"

namespace phos::scene {
namespace {

TriangleMesh unit_quad() {
    TriangleMesh quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    return quad;
}

float distance(Vec3 a, Vec3 b) { return length(a - b); }

float area(const TriangleMesh& m) {
    float a = 0;
    for (size_t i = 0; i < m.indices.size(); i += 3)
        a += 0.5f * length(cross(m.positions[m.indices[i + 1]] - m.positions[m.indices[i]],
                                 m.positions[m.indices[i + 2]] - m.positions[m.indices[i]]));
    return a;
}

TEST(MeshDisplacement, RefinementMakesEveryEdgeShorterThanTheLength) {
    for (float edge : {0.6f, 0.25f, 0.1f}) {
        TriangleMesh m = unit_quad();
        refine_mesh(m, edge, distance, 1u << 20);
        EXPECT_GT(m.triangle_count(), 2u);
        std::map<std::pair<uint32_t, uint32_t>, int> uses;
        for (size_t i = 0; i < m.indices.size(); i += 3)
            for (int e = 0; e < 3; ++e) {
                const uint32_t a = m.indices[i + size_t(e)], b = m.indices[i + size_t((e + 1) % 3)];
                EXPECT_LT(distance(m.positions[a], m.positions[b]), edge);
                ++uses[{std::min(a, b), std::max(a, b)}];
                // Winding kept: every triangle still faces +z.
                if (e == 0) {
                    const Vec3 n = cross(m.positions[m.indices[i + 1]] - m.positions[a],
                                         m.positions[m.indices[i + 2]] - m.positions[a]);
                    EXPECT_GT(n.z, 0);
                }
            }
        // Watertight: inner edges are shared by two triangles, the square's border by one, and the
        // border edges sum to the perimeter (no T-junctions leave gaps).
        float border = 0;
        for (const auto& [e, n] : uses) {
            EXPECT_LE(n, 2);
            if (n == 1) border += distance(m.positions[e.first], m.positions[e.second]);
        }
        EXPECT_NEAR(border, 4, 1e-4);
        EXPECT_NEAR(area(m), 1, 1e-5);
        // uvs interpolated with the positions (here uv = (x, y)).
        ASSERT_EQ(m.uvs.size(), m.positions.size());
        for (size_t i = 0; i < m.positions.size(); ++i) {
            EXPECT_FLOAT_EQ(m.uvs[i].x, m.positions[i].x);
            EXPECT_FLOAT_EQ(m.uvs[i].y, m.positions[i].y);
        }
    }
}

TEST(MeshDisplacement, EdgesAreMeasuredByTheGivenLength) {
    // Measured after a scale of 4 (pbrt measures in render space): 4x the edges, 16x the triangles.
    TriangleMesh a = unit_quad(), b = unit_quad();
    refine_mesh(a, 0.5f, distance, 1u << 20);
    refine_mesh(
        b, 0.5f, [](Vec3 p, Vec3 q) { return 4 * length(p - q); }, 1u << 20);
    EXPECT_GE(b.triangle_count(), 8 * a.triangle_count());
}

TEST(MeshDisplacement, ConstantDisplacementMovesThePlaneAlongItsNormal) {
    TriangleMesh m = unit_quad();
    displace_mesh(
        m, 0.3f, distance, [](Vec3, Vec3, Vec2) { return 0.25f; }, 1u << 20);
    ASSERT_EQ(m.normals.size(), m.positions.size());
    for (size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_FLOAT_EQ(m.positions[i].z, 0.25f);
        EXPECT_NEAR(m.normals[i].z, 1, 1e-6);
    }
    // A given normal is the one displaced along.
    TriangleMesh tilted = unit_quad();
    tilted.normals.assign(4, normalize(Vec3(1, 0, 1)));
    displace_mesh(
        tilted, 2.0f, distance, [](Vec3, Vec3, Vec2) { return 1.0f; }, 1u << 20);
    EXPECT_NEAR(tilted.positions[0].x, 1 / std::sqrt(2.0f), 1e-6);
    EXPECT_NEAR(tilted.positions[0].z, 1 / std::sqrt(2.0f), 1e-6);
}

TEST(MeshDisplacement, CheckerboardDisplacementGivesTwoHeights) {
    // Height 0.1 where floor(2u) + floor(2v) is even, 0 where odd, sampled at the vertices' uv.
    TriangleMesh m = unit_quad();
    const auto checker = [](Vec3, Vec3, Vec2 uv) {
        return (int(std::floor(2 * uv.x)) + int(std::floor(2 * uv.y))) % 2 == 0 ? 0.1f : 0.0f;
    };
    displace_mesh(m, 0.05f, distance, checker, 1u << 20);
    int high = 0, low = 0;
    for (size_t i = 0; i < m.positions.size(); ++i) {
        const float z = m.positions[i].z;
        EXPECT_TRUE(z == 0.1f || z == 0.0f) << z;
        (z > 0.05f ? high : low)++;
        EXPECT_FLOAT_EQ(z, checker({}, {}, m.uvs[i]));
    }
    EXPECT_GT(high, 50);
    EXPECT_GT(low, 50);
    // Normals recomputed: tilted on the steps between the squares, +z on the flat parts.
    bool tilted = false;
    for (const Vec3& n : m.normals) {
        EXPECT_NEAR(length(n), 1, 1e-5);
        tilted |= n.z < 0.9f;
    }
    EXPECT_TRUE(tilted);
}

TEST(MeshDisplacement, TooManyTrianglesIsAnInputError) {
    TriangleMesh m = unit_quad();
    EXPECT_THROW(refine_mesh(m, 1e-4f, distance, 10000), InputError);
}

}  // namespace
}  // namespace phos::scene
