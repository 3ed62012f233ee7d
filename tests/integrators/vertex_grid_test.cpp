// The light-vertex hash grid of vcm (vertex_grid.h) against brute force: every point within the
// query radius is visited exactly once, with its squared distance, for the grid's radius and
// smaller ones (vcm's per-pixel radii), including points clustered on a plane (as light vertices
// lie on surfaces) and queries outside the points' bounds.
#include "integrators/vertex_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "core/rng.h"

namespace phos::integrators {
namespace {

std::vector<Vec3> test_points(uint64_t seed, size_t n) {
    Sampler s(seed, 1, 0);
    std::vector<Vec3> p(n);
    for (size_t i = 0; i < n; ++i) {
        const Vec3 u(s.next(), s.next(), s.next());
        // Half the points on the plane y = 0.3 (a surface), half in the unit cube.
        p[i] = i % 2 == 0 ? Vec3(u.x, 0.3f, u.z) : u;
    }
    return p;
}

TEST(VertexGrid, QueriesVisitExactlyThePointsWithinTheRadius) {
    const std::vector<Vec3> points = test_points(7, 3000);
    const float radius = 0.05f;
    VertexGrid grid;
    grid.build(points, radius);
    const std::vector<uint32_t>& order = grid.order();
    ASSERT_EQ(order.size(), points.size());
    Sampler s(9, 2, 0);
    size_t visits = 0, small_visits = 0;
    for (int q = 0; q < 400; ++q) {
        // Queries inside and a little outside the points' bounds.
        const Vec3 c(s.next() * 1.2f - 0.1f, q % 3 == 0 ? 0.3f : s.next() * 1.2f - 0.1f,
                     s.next() * 1.2f - 0.1f);
        for (float scale : {1.0f, 0.5f, 0.25f}) {
            const float r2 = (radius * scale) * (radius * scale);
            std::vector<uint32_t> found;
            grid.query(c, r2, [&](uint32_t slot, float d2) {
                const Vec3 d = points[order[slot]] - c;
                EXPECT_EQ(d2, dot(d, d));
                found.push_back(order[slot]);
            });
            std::vector<uint32_t> expected;
            for (uint32_t i = 0; i < points.size(); ++i) {
                const Vec3 d = points[i] - c;
                if (dot(d, d) <= r2) expected.push_back(i);
            }
            std::sort(found.begin(), found.end());
            EXPECT_EQ(found, expected) << "query " << q << ", radius x" << scale;
            (scale < 1 ? small_visits : visits) += found.size();
        }
    }
    EXPECT_GT(visits, 1000u);  // the queries found enough to mean something
    EXPECT_GT(small_visits, 300u);
}

}  // namespace
}  // namespace phos::integrators
