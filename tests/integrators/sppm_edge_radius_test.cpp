// The pilot's edge-aware radii (pilot_radius.h, bound_radii_at_edges) on point sets with known geometry:
// points on one plane keep their radii; next to a corner or a step a point's r² becomes its
// squared distance to the nearest point across the edge, within [max(r²/4, r2_min), r²]; a step
// off the plane counts where it is high for its distance; and the result is the same for any
// thread count.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "integrators/pilot_radius.h"

namespace phos::integrators {
namespace {

constexpr float kStep = 0.01f;  // spacing of the points (a pixel footprint)
constexpr double kR = 0.08;     // every point's radius before the bound

struct Points {
    std::vector<Vec3> p, n;
    std::vector<double> r2, r2_min;
    void add(Vec3 q, Vec3 normal) {
        p.push_back(q);
        n.push_back(normal);
        r2.push_back(kR * kR);
        r2_min.push_back(double(kStep) * kStep);
    }
};

// The floor z = 0 for x in [0, 0.5), and (corner) the wall x = 0.5 for z in (0, 0.5].
Points corner() {
    Points s;
    for (int i = 0; i < 50; ++i)
        for (int j = 0; j < 20; ++j) s.add(Vec3(float(i) * kStep, float(j) * kStep, 0), Vec3(0, 0, 1));
    for (int k = 1; k <= 50; ++k)
        for (int j = 0; j < 20; ++j) s.add(Vec3(0.5f, float(j) * kStep, float(k) * kStep), Vec3(-1, 0, 0));
    return s;
}

TEST(SppmEdgeRadius, OnePlaneKeepsEveryRadius) {
    Points s;
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j) s.add(Vec3(float(i) * kStep, 0.3f, float(j) * kStep), Vec3(0, -1, 0));
    const std::vector<double> before = s.r2;
    bound_radii_at_edges(s.p, s.n, s.r2, s.r2_min);
    EXPECT_EQ(s.r2, before);
}

TEST(SppmEdgeRadius, PointsNextToACornerAreBoundedByTheirDistanceToTheOtherWall) {
    Points s = corner();
    const size_t floor_points = 50 * 20;
    bound_radii_at_edges(s.p, s.n, s.r2, s.r2_min);
    int bounded = 0;
    for (size_t i = 0; i < floor_points; ++i) {
        // Nearest wall point: (0.5, y, 0.01), at distance sqrt(dx² + 0.01²).
        const double dx = 0.5 - double(s.p[i].x);
        const double d2 = dx * dx + double(kStep) * kStep;
        const double want = std::clamp(d2, std::max(kR * kR / 4, double(kStep) * kStep), kR * kR);
        EXPECT_NEAR(s.r2[i], want, 1e-6 * kR * kR) << "floor point at x = " << s.p[i].x;
        bounded += s.r2[i] < kR * kR;
    }
    EXPECT_GT(bounded, 100);  // the points within kR of the wall
}

TEST(SppmEdgeRadius, AStepOffThePlaneIsAnEdgeWithinTenTimesItsHeight) {
    // Two parallel planes 2 mm apart (a light hanging under a ceiling): same normals, so only the
    // height off the tangent plane (> kEdgePlaneSlope x distance) marks the step: points closer
    // than 2 cm to the other plane's points are bounded, the others keep their radius.
    constexpr float kHeight = 0.002f;
    Points s;
    for (int i = 0; i < 60; ++i)
        for (int j = 0; j < 10; ++j)
            s.add(Vec3(float(i) * kStep, float(j) * kStep, i < 30 ? 0.0f : -kHeight), Vec3(0, 0, -1));
    bound_radii_at_edges(s.p, s.n, s.r2, s.r2_min);
    int bounded = 0;
    for (size_t k = 0; k < s.p.size(); ++k) {
        const int i = int(k / 10);
        const double h = double(i < 30 ? 30 - i : i - 29) * kStep;  // to the nearest column across
        const double d2 = h * h + double(kHeight) * kHeight;
        const bool edge = kHeight > kEdgePlaneSlope * std::sqrt(d2) && d2 < kR * kR;
        const double want =
            edge ? std::clamp(d2, std::max(kR * kR / 4, double(kStep) * kStep), kR * kR) : kR * kR;
        EXPECT_NEAR(s.r2[k], want, 1e-6 * kR * kR) << "column " << i;
        bounded += edge;
    }
    EXPECT_EQ(bounded, 20);  // the column on each side of the step
}

TEST(SppmEdgeRadius, SameResultForAnyThreadCount) {
    Points a = corner(), b = corner();
    tbb::task_arena(1).execute([&] { bound_radii_at_edges(a.p, a.n, a.r2, a.r2_min); });
    tbb::task_arena(2).execute([&] { bound_radii_at_edges(b.p, b.n, b.r2, b.r2_min); });
    EXPECT_EQ(a.r2, b.r2);
}

}  // namespace
}  // namespace phos::integrators
