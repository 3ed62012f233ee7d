// Loop subdivision: face counts, closed meshes stay closed manifolds, the masks' closed-form results
// (a tetrahedron's corners, a planar grid reproduced), convergence inside the hull, boundaries kept
// on their curve, unit normals all on one side (pbrt-v4's: against the winding), and bad meshes
// refused.
#include "scene/loop_subdivision.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "core/error.h"

namespace phos::scene {
namespace {

// A regular tetrahedron centred on the origin (vertices alternate cube corners), outward winding.
void tetrahedron(std::vector<Vec3>& p, std::vector<uint32_t>& idx) {
    p = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    idx = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2};
}

// The cube [-1, 1]^3 as 12 triangles wound counter-clockwise from outside.
void cube(std::vector<Vec3>& p, std::vector<uint32_t>& idx) {
    p.clear();
    for (int i = 0; i < 8; ++i)
        p.push_back({i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f});
    const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    idx.clear();
    for (const auto& q : quads) idx.insert(idx.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
}

// An n x n grid of squares on z = 0 in [0, n]^2, two triangles each, counter-clockwise from +z.
void grid(int n, std::vector<Vec3>& p, std::vector<uint32_t>& idx) {
    p.clear();
    idx.clear();
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) p.push_back({float(i), float(j), 0});
    const auto at = [n](int i, int j) { return uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            idx.insert(idx.end(),
                       {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
}

// Each undirected edge's count of triangles running it each way.
std::map<std::pair<uint32_t, uint32_t>, std::pair<int, int>> edge_uses(const TriangleMesh& m) {
    std::map<std::pair<uint32_t, uint32_t>, std::pair<int, int>> uses;
    for (size_t i = 0; i < m.indices.size(); i += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = m.indices[i + size_t(k)], b = m.indices[i + size_t((k + 1) % 3)];
            auto& u = uses[{std::min(a, b), std::max(a, b)}];
            (a < b ? u.first : u.second)++;
        }
    return uses;
}

TEST(LoopSubdivision, ClosedMeshStaysClosedManifoldWithFourToTheLevelsFaces) {
    std::vector<Vec3> p;
    std::vector<uint32_t> idx;
    tetrahedron(p, idx);
    for (int levels = 0; levels <= 4; ++levels) {
        const TriangleMesh m = loop_subdivide(p, idx, levels);
        const size_t faces = size_t(4) << (2 * levels);
        ASSERT_EQ(m.triangle_count(), faces) << levels;
        const auto uses = edge_uses(m);
        for (const auto& [edge, u] : uses) ASSERT_TRUE(u.first == 1 && u.second == 1) << levels;
        // Euler characteristic of a sphere: V - E + F = 2, and every vertex is used.
        EXPECT_EQ(long(m.positions.size()) - long(uses.size()) + long(faces), 2);
        ASSERT_EQ(m.normals.size(), m.positions.size());
    }
}

TEST(LoopSubdivision, TetrahedronCornersMatchTheMasksClosedForm) {
    // Valence 3 everywhere: one level moves a corner p0 to p0 / 4 (sum of the corners is 0), its
    // ring to p0 / 4 + pi / 4; the limit rule (gamma = 1/5) then gives p0 / 5, as the limit of the
    // unrefined tetrahedron does directly.
    std::vector<Vec3> p;
    std::vector<uint32_t> idx;
    tetrahedron(p, idx);
    for (int levels : {0, 1}) {
        const TriangleMesh m = loop_subdivide(p, idx, levels);
        for (const Vec3& corner : p) {
            float best = 1e9f;
            for (const Vec3& q : m.positions) best = std::min(best, length(q - corner * 0.2f));
            EXPECT_LT(best, 1e-6f) << levels;
        }
    }
}

TEST(LoopSubdivision, PlanarGridIsReproducedAndStaysOnItsPlane) {
    std::vector<Vec3> p;
    std::vector<uint32_t> idx;
    grid(6, p, idx);
    const TriangleMesh m = loop_subdivide(p, idx, 2);
    EXPECT_EQ(m.triangle_count(), idx.size() / 3 * 16);
    int interior_found = 0;
    for (size_t v = 0; v < m.positions.size(); ++v) {
        EXPECT_EQ(m.positions[v].z, 0.0f);
        // Unit, and against the winding's +z, as pbrt-v4's tangent masks give them.
        EXPECT_NEAR(m.normals[v].z, -1.0f, 1e-6f);
        // Loop's masks reproduce linear functions: away from the boundary's corners the regular
        // grid maps onto itself, so every interior point lies on the quarter-step lattice.
        const Vec3 q = m.positions[v];
        // A straight stretch of boundary stays on its line (the corners are cut, as Loop's rules do).
        if (q.x > 1.5f && q.x < 4.5f && q.y < 0.5f) {
            EXPECT_TRUE(q.y == 0 || q.y >= 0.2f) << q.y;
        }
        if (q.x > 1.5f && q.x < 4.5f && q.y > 1.5f && q.y < 4.5f) {
            EXPECT_NEAR(q.x * 4, std::round(q.x * 4), 1e-4f);
            EXPECT_NEAR(q.y * 4, std::round(q.y * 4), 1e-4f);
            ++interior_found;
        }
    }
    EXPECT_EQ(interior_found, 11 * 11);  // the lattice points of (1.5, 4.5)^2 at quarter steps
}

TEST(LoopSubdivision, CubeConvergesInsideItsHullWithOutwardNormals) {
    std::vector<Vec3> p;
    std::vector<uint32_t> idx;
    cube(p, idx);
    TriangleMesh coarser;
    float prev_turn = 2, prev_worst = -1;
    for (int levels : {1, 2, 3}) {
        const TriangleMesh m = loop_subdivide(p, idx, levels);
        for (size_t v = 0; v < m.positions.size(); ++v) {
            const Vec3 q = m.positions[v], n = m.normals[v];
            EXPECT_LE(std::max({std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)}), 1.0f);
            EXPECT_GT(length(q), 0.5f);
            EXPECT_NEAR(length(n), 1.0f, 1e-5f);
            EXPECT_LT(dot(n, q), 0.0f);  // against the outward winding, as pbrt-v4's
        }
        // Limit positions are points of the one limit surface: a vertex kept by the next level
        // (the even vertices come first, in order) lands on the same point.
        float worst = 1;
        for (size_t v = 0; v < coarser.positions.size(); ++v) {
            EXPECT_LT(length(m.positions[v] - coarser.positions[v]), 2e-6f) << levels << " " << v;
            worst = std::min(worst, dot(m.normals[v], coarser.normals[v]));
        }
        // pbrt applies the tangent masks to limit positions (not to control points), so a kept
        // vertex's normal moves a little between levels, less and less as they refine.
        if (levels > 1) {
            EXPECT_GT(worst, 0.998f) << levels;  // 3.6 degrees
        }
        if (levels > 2) {
            EXPECT_GT(worst, prev_worst) << levels;
        }
        prev_worst = worst;
        // Smooth: the largest turn of the normal along an edge shrinks with refinement.
        float turn = 0;
        for (size_t i = 0; i < m.indices.size(); i += 3)
            for (int k = 0; k < 3; ++k)
                turn = std::max(turn, 1 - dot(m.normals[m.indices[i + size_t(k)]],
                                              m.normals[m.indices[i + size_t((k + 1) % 3)]]));
        EXPECT_LT(turn, prev_turn) << levels;
        prev_turn = turn;
        coarser = m;
    }
}

TEST(LoopSubdivision, BoundaryVerticesStayOnTheBoundaryCurve) {
    // An open pyramid (no base): its boundary is the square z = 0, |x|, |y| <= 1. The boundary rules
    // use boundary vertices only, so the boundary becomes a cubic B-spline of that square: in the
    // plane z = 0, inside the square, and the boundary edges double each level.
    const std::vector<Vec3> p = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, 1}};
    const std::vector<uint32_t> idx = {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
    for (int levels : {1, 2, 3}) {
        const TriangleMesh m = loop_subdivide(p, idx, levels);
        int boundary_edges = 0;
        for (const auto& [edge, u] : edge_uses(m)) {
            if (u.first + u.second != 1) continue;
            ++boundary_edges;
            for (uint32_t v : {edge.first, edge.second}) {
                const Vec3 q = m.positions[v];
                EXPECT_NEAR(q.z, 0.0f, 1e-6f);
                EXPECT_LE(std::max(std::fabs(q.x), std::fabs(q.y)), 1.0f);
            }
        }
        EXPECT_EQ(boundary_edges, 4 << levels);
        for (size_t v = 0; v < m.positions.size(); ++v) {
            EXPECT_NEAR(length(m.normals[v]), 1.0f, 1e-5f);
            EXPECT_LT(m.normals[v].z, 0.0f);  // against the winding (its outside is up), as pbrt-v4's
        }
    }
}

TEST(LoopSubdivision, UnusedVerticesAreDroppedAndBadMeshesRefused) {
    std::vector<Vec3> p;
    std::vector<uint32_t> idx;
    tetrahedron(p, idx);
    p.push_back({5, 5, 5});  // used by nothing
    EXPECT_EQ(loop_subdivide(p, idx, 1).positions.size(), 10u);

    EXPECT_THROW(loop_subdivide(p, {0, 1, 7}, 1), InputError);           // out of range
    EXPECT_THROW(loop_subdivide(p, {0, 1, 1}, 1), InputError);           // degenerate
    EXPECT_THROW(loop_subdivide(p, {0, 1}, 1), InputError);              // not triangles
    EXPECT_THROW(loop_subdivide(p, idx, -1), InputError);                // negative levels
    EXPECT_THROW(loop_subdivide(p, {0, 1, 2, 0, 1, 3}, 1), InputError);  // inconsistent orientation
    // Three triangles on one edge.
    EXPECT_THROW(loop_subdivide(p, {0, 1, 2, 1, 0, 3, 1, 0, 4}, 1), InputError);
    // Two fans touching at vertex 0 only (a bow tie).
    const std::vector<Vec3> bow = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
    EXPECT_THROW(loop_subdivide(bow, {0, 1, 2, 0, 3, 4}, 1), InputError);
}

}  // namespace
}  // namespace phos::scene
