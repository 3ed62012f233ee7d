// The hit-point hash grid must return exactly the points whose own radius contains the query point
// (each once), as a brute-force scan does, for mixed radii, clustered points and far queries.
#include "photon/hitpoint_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "core/rng.h"

namespace phos::photon {
namespace {

std::vector<uint32_t> brute_force(const std::vector<Vec3>& pos, const std::vector<float>& r2, Vec3 q) {
    std::vector<uint32_t> out;
    for (size_t i = 0; i < pos.size(); ++i) {
        const Vec3 d = q - pos[i];
        if (r2[i] > 0 && d.x * d.x + d.y * d.y + d.z * d.z <= r2[i]) out.push_back(uint32_t(i));
    }
    return out;
}

void check(float cell_factor, uint64_t seed, float spread = 0.05f, int max_levels = HitPointGrid::kMaxLevels,
           size_t min_levels = 1) {
    Sampler s(seed);
    std::vector<Vec3> pos;
    std::vector<float> r2;
    for (int i = 0; i < 3000; ++i) {
        // Half on a plane (as visible points on a wall), half in a volume; some points disabled.
        const Vec3 p = i % 2 ? Vec3(s.next(), 0.25f, s.next()) : Vec3(s.next(), s.next(), s.next());
        const float r = 0.005f + spread * s.next() * s.next();
        pos.push_back(p);
        r2.push_back(i % 17 == 0 ? 0.0f : r * r);
    }
    HitPointGrid grid;
    grid.set_cell_factor(cell_factor);
    grid.set_max_levels(max_levels);
    grid.build(pos, r2);
    EXPECT_GE(grid.level_count(), min_levels);
    EXPECT_LE(grid.level_count(), size_t(max_levels));
    size_t total = 0;
    for (int k = 0; k < 4000; ++k) {
        Vec3 q = k % 2 ? Vec3(s.next(), 0.25f + 0.01f * (s.next() - 0.5f), s.next())
                       : Vec3(1.4f * s.next() - 0.2f, 1.4f * s.next() - 0.2f, 1.4f * s.next() - 0.2f);
        std::vector<uint32_t> got;
        grid.query(q, [&](uint32_t i) { got.push_back(i); });
        std::sort(got.begin(), got.end());
        const auto want = brute_force(pos, r2, q);
        ASSERT_EQ(got, want) << "query " << k;  // sorted, so duplicates would show
        total += want.size();
    }
    EXPECT_GT(total, 2000u);  // the queries really do find points
}

TEST(HitPointGrid, QueryEqualsBruteForce) { check(2.0f, 1); }
TEST(HitPointGrid, QueryEqualsBruteForceSmallCells) { check(0.6f, 2); }
// Cells follow the mean radius, so discs far larger than the mean span many cells.
TEST(HitPointGrid, QueryEqualsBruteForceWideRadiusSpread) { check(2.0f, 3, 0.3f); }

// Radii over three decades (long SPPM renders: pixels that never got a photon keep their first
// radius): several radius classes, each its own grid; and the same points in a single grid.
TEST(HitPointGrid, QueryEqualsBruteForceRadiusClasses) {
    check(2.0f, 4, 0.5f, HitPointGrid::kMaxLevels, 3);
    check(2.0f, 4, 0.5f, 1, 1);
    check(0.6f, 5, 0.5f, 3, 2);
}

TEST(HitPointGrid, EmptyAndDisabled) {
    HitPointGrid grid;
    grid.build({}, {});
    int n = 0;
    grid.query(Vec3(0.0f), [&](uint32_t) { ++n; });
    grid.build({Vec3(0.0f)}, {0.0f});
    grid.query(Vec3(0.0f), [&](uint32_t) { ++n; });
    EXPECT_EQ(n, 0);
    grid.build({Vec3(0.0f)}, {1.0f});
    grid.query(Vec3(0.5f, 0.5f, 0.5f), [&](uint32_t) { ++n; });
    EXPECT_EQ(n, 1);
}

}  // namespace
}  // namespace phos::photon
