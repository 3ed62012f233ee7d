// Density grids: pbrt-v4's uniform grid against a brute-force trilinear reference, sparse NanoVDB
// grids against the equivalent uniform grid, conservative max_density, and the majorant DDA.
#include "shading/density_grid.h"

#include <gtest/gtest.h>
#include <nanovdb/util/GridBuilder.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/error.h"

namespace phos::shading {
namespace {

using Rng = std::mt19937;

float uniform(Rng& rng, float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng); }
Vec3 uniform3(Rng& rng, Vec3 a, Vec3 b) {
    return {uniform(rng, a.x, b.x), uniform(rng, a.y, b.y), uniform(rng, a.z, b.z)};
}

scene::Medium random_uniform_medium(Rng& rng, int nmax = 9) {
    scene::Medium m;
    m.name = "grid";
    m.kind = scene::Medium::Kind::UniformGrid;
    std::uniform_int_distribution<int> n(1, nmax);
    m.nx = n(rng), m.ny = n(rng), m.nz = n(rng);
    for (int i = 0; i < m.nx * m.ny * m.nz; ++i)
        m.density.push_back(uniform(rng, 0, 1) < 0.2f ? 0.0f : uniform(rng, 0, 5));
    m.p0 = uniform3(rng, Vec3(-3), Vec3(1));
    m.p1 = m.p0 + uniform3(rng, Vec3(0.5f), Vec3(4));
    return m;
}

// pbrt-v4 SampledGrid::Lookup, in double.
double reference(const scene::Medium& m, Vec3 p) {
    if (p.x < m.p0.x || p.y < m.p0.y || p.z < m.p0.z || p.x > m.p1.x || p.y > m.p1.y || p.z > m.p1.z)
        return 0;
    const int n[3] = {m.nx, m.ny, m.nz};
    double s[3], f[3];
    int i[3];
    for (int a = 0; a < 3; ++a) {
        s[a] = double(p[a] - m.p0[a]) / double(m.p1[a] - m.p0[a]) * n[a] - 0.5;
        i[a] = int(std::floor(s[a]));
        f[a] = s[a] - i[a];
    }
    double sum = 0;
    for (int c = 0; c < 8; ++c) {
        int j[3];
        double w = 1;
        for (int a = 0; a < 3; ++a) {
            const int o = (c >> a) & 1;
            j[a] = i[a] + o;
            w *= o ? f[a] : 1 - f[a];
        }
        if (j[0] < 0 || j[1] < 0 || j[2] < 0 || j[0] >= n[0] || j[1] >= n[1] || j[2] >= n[2]) continue;
        sum += w * m.density[size_t((j[2] * n[1] + j[1]) * n[0] + j[0])];
    }
    return sum;
}

// A sparse medium holding the same samples as `u`: voxel (i, j, k) at the centre of uniform cell
// (i, j, k) (this needs cubic cells), built with NanoVDB's GridBuilder.
scene::Medium sparse_like(const scene::Medium& u, float h, int skip_value_below = -1) {
    nanovdb::GridBuilder<float> builder(0.0f, nanovdb::GridClass::FogVolume);
    auto acc = builder.getAccessor();
    for (int z = 0; z < u.nz; ++z)
        for (int y = 0; y < u.ny; ++y)
            for (int x = 0; x < u.nx; ++x) {
                const float v = u.density[size_t((z * u.ny + y) * u.nx + x)];
                if (v > float(skip_value_below)) acc.setValue(nanovdb::Coord(x, y, z), v);
            }
    const nanovdb::Vec3d origin(u.p0.x + 0.5 * h, u.p0.y + 0.5 * h, u.p0.z + 0.5 * h);
    auto handle = std::make_shared<nanovdb::GridHandle<>>(builder.getHandle<>(h, origin, "density"));
    scene::Medium m;
    m.name = "sparse";
    m.kind = scene::Medium::Kind::Sparse;
    m.sparse.buffer = std::shared_ptr<const void>(handle, handle->data());
    m.sparse.bytes = handle->size();
    m.sparse.file = "(memory)";
    return m;
}

scene::Medium cubic_uniform_medium(Rng& rng, float h, int nmax = 12) {
    scene::Medium m = random_uniform_medium(rng, nmax);
    m.p1 = m.p0 + Vec3(float(m.nx), float(m.ny), float(m.nz)) * h;
    return m;
}

TEST(DensityGrid, HomogeneousHasNone) {
    scene::Medium m;
    EXPECT_EQ(make_density_grid(m), nullptr);
}

TEST(DensityGrid, UniformMatchesBruteForceTrilinear) {
    Rng rng(1);
    for (int g = 0; g < 50; ++g) {
        const scene::Medium m = random_uniform_medium(rng);
        const auto grid = make_density_grid(m);
        ASSERT_NE(grid, nullptr);
        EXPECT_EQ(grid->bounds().lo, m.p0);
        EXPECT_EQ(grid->bounds().hi, m.p1);
        const Vec3 margin = (m.p1 - m.p0) * 0.1f;
        for (int i = 0; i < 2000; ++i) {
            const Vec3 p = uniform3(rng, m.p0 - margin, m.p1 + margin);
            EXPECT_NEAR(grid->density(p), reference(m, p), 1e-4 * (1 + reference(m, p)));
        }
    }
}

TEST(DensityGrid, ConstantGridIsConstantInside) {
    scene::Medium m;
    m.kind = scene::Medium::Kind::UniformGrid;
    m.nx = 4, m.ny = 3, m.nz = 5;
    m.density.assign(60, 2.5f);
    m.p0 = {-1, 0, 2};
    m.p1 = {3, 1.5f, 7};
    const auto grid = make_density_grid(m);
    Rng rng(2);
    // Between the outermost sample positions every lookup blends samples of the grid only.
    const Vec3 cell = (m.p1 - m.p0) * Vec3(1.0f / 4, 1.0f / 3, 1.0f / 5);
    for (int i = 0; i < 10000; ++i) {
        const Vec3 p = uniform3(rng, m.p0 + cell * 0.5f, m.p1 - cell * 0.5f);
        EXPECT_NEAR(grid->density(p), 2.5f, 1e-5f);
    }
    EXPECT_EQ(grid->density(m.p0 - Vec3(0.01f)), 0.0f);
    EXPECT_EQ(grid->density(m.p1 + Vec3(0.01f)), 0.0f);
    EXPECT_FLOAT_EQ(grid->max_density(grid->bounds()), 2.5f);
}

TEST(DensityGrid, UnusableUniformGridsThrow) {
    scene::Medium m;
    m.kind = scene::Medium::Kind::UniformGrid;
    m.nx = 2, m.ny = 2, m.nz = 2;
    m.density.assign(7, 1.0f);
    EXPECT_THROW(make_density_grid(m), InputError);
    m.density.assign(8, 1.0f);
    m.p0 = {0, 1, 0};
    m.p1 = {1, 1, 1};
    EXPECT_THROW(make_density_grid(m), InputError);
}

TEST(DensityGrid, UnusableSparseGridsThrow) {
    scene::Medium m;
    m.kind = scene::Medium::Kind::Sparse;
    EXPECT_THROW(make_density_grid(m), InputError);  // no buffer
    nanovdb::GridBuilder<float> empty(0.0f);
    auto handle =
        std::make_shared<nanovdb::GridHandle<>>(empty.getHandle<>(1.0, nanovdb::Vec3d(0), "density"));
    m.sparse.buffer = std::shared_ptr<const void>(handle, handle->data());
    m.sparse.bytes = handle->size();
    EXPECT_THROW(make_density_grid(m), InputError);  // no active voxel
    nanovdb::GridBuilder<double> dbl(0.0);
    dbl.getAccessor().setValue(nanovdb::Coord(1, 2, 3), 1.0);
    auto dh = std::make_shared<nanovdb::GridHandle<>>(dbl.getHandle<>(1.0, nanovdb::Vec3d(0), "density"));
    m.sparse.buffer = std::shared_ptr<const void>(dh, dh->data());
    m.sparse.bytes = dh->size();
    try {
        make_density_grid(m);
        ADD_FAILURE() << "a double grid was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("not a float grid"), std::string::npos) << e.what();
    }
}

TEST(DensityGrid, SparseMatchesEquivalentUniformGrid) {
    Rng rng(3);
    for (int g = 0; g < 20; ++g) {
        const float h = uniform(rng, 0.05f, 0.6f);
        const scene::Medium u = cubic_uniform_medium(rng, h, 20);
        const scene::Medium s = sparse_like(u, h);
        const auto ug = make_density_grid(u), sg = make_density_grid(s);
        ASSERT_NE(sg, nullptr);
        // The sparse bounds hold the uniform ones (they reach one voxel beyond the active voxels).
        const Bounds sb = sg->bounds();
        for (int a = 0; a < 3; ++a) {
            EXPECT_LE(sb.lo[a], u.p0[a] + 1e-4f);
            EXPECT_GE(sb.hi[a], u.p1[a] - 1e-4f);
        }
        for (int i = 0; i < 3000; ++i) {
            const Vec3 p = uniform3(rng, u.p0, u.p1);
            EXPECT_NEAR(sg->density(p), ug->density(p), 2e-4f * (1 + ug->density(p)));
        }
        for (int i = 0; i < 200; ++i) {  // outside the sparse bounds: 0
            Vec3 p = uniform3(rng, sb.lo, sb.hi);
            p[i % 3] = (i & 4) ? sb.hi[i % 3] + 0.01f : sb.lo[i % 3] - 0.01f;
            EXPECT_EQ(sg->density(p), 0.0f);
        }
    }
}

// For random boxes (inside, straddling and outside the bounds) max_density bounds the density
// at random points of the box.
void check_max_density(const DensityGrid& grid, Rng& rng, int boxes, int points_per_box) {
    const Bounds b = grid.bounds();
    const Vec3 ext = b.extent();
    for (int i = 0; i < boxes; ++i) {
        const Vec3 c = uniform3(rng, b.lo - ext * 0.2f, b.hi + ext * 0.2f);
        const Vec3 half = uniform3(rng, Vec3(0), ext * (i % 3 == 0 ? 0.02f : 0.3f));
        Bounds box;
        box.lo = c - half;
        box.hi = c + half;
        const float m = grid.max_density(box);
        for (int k = 0; k < points_per_box; ++k) {
            const Vec3 p = uniform3(rng, box.lo, box.hi);
            const float d = grid.density(p);
            ASSERT_LE(d, m * (1 + 1e-6f) + 1e-7f) << "box " << i << " point " << k;
        }
    }
}

TEST(DensityGrid, MaxDensityIsConservativeUniform) {
    Rng rng(4);
    for (int g = 0; g < 10; ++g) {
        const auto grid = make_density_grid(random_uniform_medium(rng, 16));
        check_max_density(*grid, rng, 100, 100);  // 10^5 points
    }
}

TEST(DensityGrid, MaxDensityIsConservativeSparse) {
    Rng rng(5);
    for (int g = 0; g < 10; ++g) {
        const float h = uniform(rng, 0.05f, 0.5f);
        const auto grid = make_density_grid(sparse_like(cubic_uniform_medium(rng, h, 40), h, 1));
        check_max_density(*grid, rng, 100, 100);
    }
}

TEST(DensityGrid, SparseMaxDensityIsTight) {
    // One voxel of 7 at the origin: boxes well away from it see 0; a box holding it sees 7.
    nanovdb::GridBuilder<float> builder(0.0f);
    builder.getAccessor().setValue(nanovdb::Coord(100, 100, 100), 1.0f);
    builder.getAccessor().setValue(nanovdb::Coord(0, 0, 0), 7.0f);
    auto handle = std::make_shared<nanovdb::GridHandle<>>(builder.getHandle<>(0.5, nanovdb::Vec3d(0), "d"));
    scene::Medium m;
    m.kind = scene::Medium::Kind::Sparse;
    m.sparse.buffer = std::shared_ptr<const void>(handle, handle->data());
    m.sparse.bytes = handle->size();
    const auto grid = make_density_grid(m);
    Bounds near, far;
    near.lo = Vec3(-0.1f), near.hi = Vec3(0.1f);
    far.lo = Vec3(20), far.hi = Vec3(30);
    EXPECT_FLOAT_EQ(grid->density(Vec3(0)), 7.0f);
    EXPECT_GE(grid->max_density(near), 7.0f);
    EXPECT_EQ(grid->max_density(far), 0.0f);
}

// Reference slab clip of o + t d, t in [t0, t1), against `b`; false if empty.
bool clip(const Bounds& b, Vec3 o, Vec3 d, float t0, float t1, float& lo, float& hi) {
    lo = t0, hi = t1;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) {
            if (o[a] < b.lo[a] || o[a] > b.hi[a]) return false;
            continue;
        }
        float tn = (b.lo[a] - o[a]) / d[a], tf = (b.hi[a] - o[a]) / d[a];
        if (tn > tf) std::swap(tn, tf);
        lo = std::max(lo, tn), hi = std::min(hi, tf);
    }
    return lo < hi;
}

void check_segments(const DensityGrid& grid, const MajorantGrid& maj, Rng& rng, Vec3 o, Vec3 d, float t0,
                    float t1) {
    float lo, hi;
    const bool hit = clip(maj.bounds(), o, d, t0, t1, lo, hi);
    auto it = maj.segments(o, d, t0, t1);
    float ta, tb, m, prev = 0;
    int n = 0;
    while (it.next(ta, tb, m)) {
        ASSERT_TRUE(hit) << "a segment for a ray that misses the bounds";
        ASSERT_LT(ta, tb);
        if (n == 0)
            EXPECT_EQ(ta, lo);
        else
            EXPECT_EQ(ta, prev);
        prev = tb;
        ++n;
        ASSERT_LE(n, 3 * maj.resolution() + 3);
        for (int k = 0; k < 20; ++k) {
            const float t = uniform(rng, ta, tb);
            const float dens = grid.density(o + d * t);
            ASSERT_LE(dens, m * (1 + 1e-6f) + 1e-7f) << "t " << t << " in [" << ta << ", " << tb << ")";
        }
    }
    if (hit) {
        EXPECT_GT(n, 0);
        if (n > 0) {
            EXPECT_EQ(prev, hi);
        }
    } else {
        EXPECT_EQ(n, 0);
    }
}

TEST(MajorantGrid, CellsBoundTheDensity) {
    Rng rng(6);
    const auto grid = make_density_grid(random_uniform_medium(rng, 24));
    MajorantGrid maj(*grid, 8);
    ASSERT_EQ(maj.resolution(), 8);
    const Bounds b = maj.bounds();
    for (int i = 0; i < 20000; ++i) {
        const Vec3 p = uniform3(rng, b.lo, b.hi);
        const Vec3 u = (p - b.lo) * Vec3(8 / b.extent().x, 8 / b.extent().y, 8 / b.extent().z);
        const int x = std::min(7, int(u.x)), y = std::min(7, int(u.y)), z = std::min(7, int(u.z));
        EXPECT_LE(grid->density(p), maj.max_at(x, y, z) * (1 + 1e-6f));
    }
}

void check_random_rays(const DensityGrid& grid, int res, Rng& rng) {
    const MajorantGrid maj(grid, res);
    const Bounds b = maj.bounds();
    const Vec3 ext = b.extent();
    for (int i = 0; i < 3000; ++i) {
        Vec3 o = uniform3(rng, b.lo - ext, b.hi + ext);
        Vec3 target = uniform3(rng, b.lo, b.hi);
        if (i % 5 == 0) o = uniform3(rng, b.lo, b.hi);  // starting inside
        Vec3 d = (target - o) * uniform(rng, 0.1f, 10.0f);
        if (i % 7 == 1) d[i % 3] = 0;  // axis-parallel in one or two axes
        if (i % 7 == 2) d[i % 3] = 0, d[(i + 1) % 3] = 0;
        if (i % 11 == 3) d = -d;  // often missing, or leaving
        if (d.x == 0 && d.y == 0 && d.z == 0) d.x = 1;
        float t0 = i % 4 == 0 ? uniform(rng, -1, 1) : 0.0f;
        float t1 = i % 3 == 0 ? uniform(rng, t0, 2) : 1e30f;
        check_segments(grid, maj, rng, o, d, t0, t1);
        if (::testing::Test::HasFatalFailure()) return;
    }
    // Rays along the grid planes and edges, and rays missing the box.
    for (int i = 0; i < 200; ++i) {
        const int a = i % 3;
        Vec3 o = uniform3(rng, b.lo, b.hi);
        const int k = int(uniform(rng, 0, float(res) + 0.99f));
        o[(a + 1) % 3] = b.lo[(a + 1) % 3] + ext[(a + 1) % 3] * (float(k) / float(res));
        o[a] = b.lo[a] - 1;
        Vec3 d(0);
        d[a] = uniform(rng, 0.2f, 3.0f);
        check_segments(grid, maj, rng, o, d, 0, 1e30f);
        Vec3 miss = o;
        miss[(a + 2) % 3] = b.hi[(a + 2) % 3] + 0.5f;
        auto it = maj.segments(miss, d, 0, 1e30f);
        float ta, tb, m;
        EXPECT_FALSE(it.next(ta, tb, m));
        auto behind = maj.segments(o, -d, 0, 1e30f);  // pointing away
        EXPECT_FALSE(behind.next(ta, tb, m));
    }
}

TEST(MajorantGrid, SegmentsAreContiguousAndBoundTheUniformDensity) {
    Rng rng(7);
    for (int g = 0; g < 6; ++g) {
        const auto grid = make_density_grid(random_uniform_medium(rng, 20));
        check_random_rays(*grid, g % 2 ? 16 : 5, rng);
        if (HasFatalFailure()) return;
    }
}

TEST(MajorantGrid, SegmentsAreContiguousAndBoundTheSparseDensity) {
    Rng rng(8);
    for (int g = 0; g < 4; ++g) {
        const float h = uniform(rng, 0.05f, 0.5f);
        const auto grid = make_density_grid(sparse_like(cubic_uniform_medium(rng, h, 30), h, 1));
        check_random_rays(*grid, 16, rng);
        if (HasFatalFailure()) return;
    }
}

TEST(MajorantGrid, EmptyRangeAndDegenerateInput) {
    Rng rng(9);
    const auto grid = make_density_grid(random_uniform_medium(rng));
    const MajorantGrid maj(*grid, 4);
    const Vec3 c = maj.bounds().center();
    float ta, tb, m;
    auto empty = maj.segments(c, Vec3(1, 0, 0), 0.5f, 0.5f);
    EXPECT_FALSE(empty.next(ta, tb, m));
    auto nan = maj.segments(c, Vec3(std::nanf(""), 0, 0), 0, 1);
    EXPECT_FALSE(nan.next(ta, tb, m));
    auto one = maj.segments(c, Vec3(1, 0, 0), 0, 1e-6f);  // inside one cell
    ASSERT_TRUE(one.next(ta, tb, m));
    EXPECT_EQ(ta, 0.0f);
    EXPECT_EQ(tb, 1e-6f);
    EXPECT_FALSE(one.next(ta, tb, m));
}

}  // namespace
}  // namespace phos::shading
