// Tests of the photon-sphere BVH (photon/beam_bvh.h): segment queries against brute force over
// every sphere (the same spheres, the same sum up to float rounding) on random spheres and
// segments, axis-aligned and degenerate segments, the node invariants, and bit-identical builds at
// 1 and 2 threads; save / load, and the shapes load refuses.
#include "photon/beam_bvh.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/rng.h"

namespace phos::photon {
namespace {

// n spheres in the unit cube with radii in [r_lo, r_hi] and distinct powers.
std::vector<PhotonSphere> random_spheres(int n, float r_lo, float r_hi, uint64_t seed) {
    Sampler rng(seed);
    std::vector<PhotonSphere> v;
    for (int i = 0; i < n; ++i) {
        const Vec3 p(rng.next(), rng.next(), rng.next());
        const Rgb power(0.5f + rng.next(), 0.5f + rng.next(), 0.5f + rng.next());
        const Vec3 wi = normalize(Vec3(rng.next() - 0.5f, rng.next() - 0.5f, 1.0f));
        v.push_back({p, r_lo + (r_hi - r_lo) * rng.next(), power, wi});
    }
    return v;
}

struct Query {
    Vec3 o, d;
    float t_end;
};

// Segments starting inside and outside the cube, of all lengths, some along the axes (zero
// direction components) and some starting exactly on a sphere's centre plane.
std::vector<Query> random_queries(int n, uint64_t seed) {
    Sampler rng(seed);
    std::vector<Query> q;
    for (int i = 0; i < n; ++i) {
        Vec3 o(1.6f * rng.next() - 0.3f, 1.6f * rng.next() - 0.3f, 1.6f * rng.next() - 0.3f);
        Vec3 d(rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f);
        if (i % 7 == 0) d = Vec3(0.0f), d[int(rng.next_index(3))] = rng.next() < 0.5f ? -1.0f : 1.0f;
        if (i % 11 == 0) d.z = 0;
        if (length(d) < 1e-3f) d = Vec3(1, 0, 0);
        const float t_end = i % 5 == 0 ? 0.05f * rng.next() : 2.5f * rng.next();
        q.push_back({o, normalize(d), t_end});
    }
    return q;
}

struct Found {
    std::vector<uint32_t> indices;
    double weight = 0;  // sum of power * chord length over the hits (float, in visiting order)
};

Found from_bvh(const BeamBvh& bvh, const Query& q) {
    Found f;
    float sum = 0;
    bvh.for_each_hit(q.o, q.d, q.t_end, [&](uint32_t i, const SphereHit& h) {
        f.indices.push_back(i);
        sum += bvh.spheres()[i].power.g * (h.t1 - h.t0);
    });
    f.weight = sum;
    std::sort(f.indices.begin(), f.indices.end());
    return f;
}

Found from_brute_force(const BeamBvh& bvh, const Query& q) {
    Found f;
    float sum = 0;
    for_each_hit_brute_force(bvh.spheres(), q.o, q.d, q.t_end, [&](uint32_t i, const SphereHit& h) {
        f.indices.push_back(i);
        sum += bvh.spheres()[i].power.g * (h.t1 - h.t0);
    });
    f.weight = sum;
    return f;
}

void expect_matches_brute_force(const BeamBvh& bvh, const std::vector<Query>& queries, size_t* total_hits) {
    for (size_t k = 0; k < queries.size(); ++k) {
        const Found a = from_bvh(bvh, queries[k]), b = from_brute_force(bvh, queries[k]);
        ASSERT_EQ(a.indices, b.indices) << "query " << k;
        // Float sums of up to a few thousand positive terms in two orders: a few 1e-7 relative.
        EXPECT_NEAR(a.weight, b.weight, 1e-5 * b.weight + 1e-30) << "query " << k;
        *total_hits += a.indices.size();
    }
}

TEST(BeamBvh, SegmentQueriesMatchBruteForce) {
    for (uint32_t leaf : {1u, 4u, 16u}) {
        BeamBvh bvh;
        bvh.build(random_spheres(20000, 0.005f, 0.08f, 11), leaf);
        ASSERT_EQ(bvh.size(), 20000u);
        size_t hits = 0;
        expect_matches_brute_force(bvh, random_queries(400, 12), &hits);
        std::printf("[ measured ] leaf size %u: %zu hits in 400 segments\n", leaf, hits);
        EXPECT_GT(hits, 400u * 10) << "the queries meet many spheres (the test has power)";
    }
}

TEST(BeamBvh, WidelyVaryingRadiiAndDuplicates) {
    // Radii spanning three orders of magnitude, plus exact duplicates of some spheres and spheres
    // sharing one centre: boxes nest and overlap in every way.
    std::vector<PhotonSphere> s = random_spheres(3000, 0.0005f, 0.3f, 21);
    for (int i = 0; i < 300; ++i) s.push_back(s[size_t(i * 7)]);
    for (int i = 0; i < 50; ++i) s.push_back({Vec3(0.5f), 0.01f * float(i + 1), Rgb(1.0f), Vec3(0, 0, 1)});
    BeamBvh bvh;
    bvh.build(s, 4);
    size_t hits = 0;
    expect_matches_brute_force(bvh, random_queries(300, 22), &hits);
    EXPECT_GT(hits, 0u);
}

TEST(BeamBvh, ChordIsClippedToTheSegment) {
    BeamBvh bvh;
    bvh.build({{Vec3(0, 0, 2), 0.5f, Rgb(1.0f), Vec3(0, 0, 1)}});
    // Along +z from the origin: the ball spans t in [1.5, 2.5].
    std::vector<SphereHit> h;
    const auto query = [&](Vec3 o, float t_end) {
        h.clear();
        bvh.for_each_hit(o, Vec3(0, 0, 1), t_end, [&](uint32_t, const SphereHit& x) { h.push_back(x); });
    };
    query(Vec3(0.0f), 10.0f);
    ASSERT_EQ(h.size(), 1u);
    EXPECT_FLOAT_EQ(h[0].t0, 1.5f);
    EXPECT_FLOAT_EQ(h[0].t1, 2.5f);
    EXPECT_FLOAT_EQ(h[0].t, 2.0f);
    EXPECT_FLOAT_EQ(h[0].dist2, 0.0f);
    query(Vec3(0.0f), 2.0f);  // ends at the centre
    ASSERT_EQ(h.size(), 1u);
    EXPECT_FLOAT_EQ(h[0].t1, 2.0f);
    query(Vec3(0, 0, 2.2f), 10.0f);  // starts inside
    ASSERT_EQ(h.size(), 1u);
    EXPECT_FLOAT_EQ(h[0].t0, 0.0f);
    EXPECT_NEAR(h[0].t1, 0.3f, 1e-6f);
    query(Vec3(0.0f), 1.5f);  // ends where the ball starts: a point, not a chord
    EXPECT_TRUE(h.empty());
    query(Vec3(0, 0, 3.0f), 10.0f);  // starts behind it
    EXPECT_TRUE(h.empty());
    query(Vec3(0.5f, 0, 0), 10.0f);  // grazes it: distance = radius
    EXPECT_TRUE(h.empty());
    query(Vec3(0.3f, 0.4f - 1e-4f, 0), 10.0f);  // just inside the rim
    EXPECT_EQ(h.size(), 1u);
}

TEST(BeamBvh, EmptyAndDegenerate) {
    BeamBvh empty;
    int calls = 0;
    empty.for_each_hit(Vec3(0.0f), Vec3(1, 0, 0), 1.0f, [&](uint32_t, const SphereHit&) { ++calls; });
    empty.build({});
    empty.for_each_hit(Vec3(0.0f), Vec3(1, 0, 0), 1.0f, [&](uint32_t, const SphereHit&) { ++calls; });
    EXPECT_EQ(calls, 0);
    BeamBvh bvh;
    bvh.build(random_spheres(100, 0.1f, 0.2f, 3));
    bvh.for_each_hit(Vec3(0.5f), Vec3(1, 0, 0), 0.0f, [&](uint32_t, const SphereHit&) { ++calls; });
    EXPECT_EQ(calls, 0) << "a zero-length segment meets nothing";
    std::vector<PhotonSphere> bad = random_spheres(10, 0.1f, 0.2f, 4);
    bad[3].radius = std::nanf("");
    EXPECT_THROW(bvh.build(bad), InputError);
}

TEST(BeamBvh, NodesBoundTheirSpheres) {
    BeamBvh bvh;
    bvh.build(random_spheres(2000, 0.01f, 0.1f, 5), 4);
    const auto nodes = bvh.nodes();
    size_t covered = 0;
    for (const BeamBvh::Node& n : nodes) {
        if (n.count == 0) {
            ASSERT_LT(n.offset, nodes.size());
            continue;
        }
        EXPECT_LE(n.count, 4u);
        covered += n.count;
        for (uint32_t i = n.offset; i < n.offset + n.count; ++i) {
            const PhotonSphere& s = bvh.spheres()[i];
            for (int a = 0; a < 3; ++a) {
                EXPECT_LE(n.lo[a], s.position[a] - s.radius);
                EXPECT_GE(n.hi[a], s.position[a] + s.radius);
            }
        }
    }
    EXPECT_EQ(covered, 2000u) << "every sphere in exactly one leaf";
}

TEST(BeamBvh, LoadRestoresTheTreeAndRefusesOtherShapes) {
    BeamBvh bvh;
    bvh.build(random_spheres(300, 0.01f, 0.1f, 6), 4);
    ASSERT_TRUE(BeamBvh::is_tree(bvh.nodes(), bvh.size()));
    std::string bytes;
    ByteWriter w(bytes);
    bvh.save(w);
    {
        ByteReader r(bytes, "'beams'");
        BeamBvh back;
        back.load(r);
        ASSERT_EQ(back.nodes().size(), bvh.nodes().size());
        EXPECT_EQ(std::memcmp(back.nodes().data(), bvh.nodes().data(), bvh.nodes().size_bytes()), 0);
    }
    // Each of these would make for_each_hit loop forever, overflow its stack or read past an array.
    const size_t n = bvh.nodes().size();
    std::vector<BeamBvh::Node> nodes(bvh.nodes().begin(), bvh.nodes().end());
    const auto refused = [&](const char* why) {
        EXPECT_FALSE(BeamBvh::is_tree(nodes, bvh.size())) << why;
        nodes.assign(bvh.nodes().begin(), bvh.nodes().end());
    };
    ASSERT_EQ(nodes[0].count, 0u);
    nodes[0].offset = 0;
    refused("a right child pointing at its parent (a cycle)");
    nodes[0].offset = 1;
    refused("a right child equal to the left one");
    nodes[0].offset = uint32_t(n);
    refused("a right child past the array");
    nodes[n - 1].count = 0, nodes[n - 1].offset = uint32_t(n - 1);
    refused("an interior node in the last slot (its left child would be past the array)");
    for (BeamBvh::Node& node : nodes)
        if (node.count > 0) node.offset = uint32_t(bvh.size());
    refused("leaves past the spheres");
    // A chain 70 deep: every interior node's left child is a leaf.
    std::vector<BeamBvh::Node> chain(141);
    for (uint32_t i = 0; i < 140; i += 2) chain[i].offset = i + 2, chain[i + 1].count = 1;
    chain[140].count = 1;
    EXPECT_FALSE(BeamBvh::is_tree(chain, 1)) << "deeper than for_each_hit's stack";
    chain.resize(121), chain[120].count = 1, chain[120].offset = 0;
    EXPECT_TRUE(BeamBvh::is_tree(chain, 1)) << "61 deep fits";
}

TEST(BeamBvh, BitIdenticalAtOneAndTwoThreads) {
    // Large enough that the top levels build in parallel.
    const std::vector<PhotonSphere> s = random_spheres(60000, 0.005f, 0.05f, 9);
    BeamBvh a, b;
    tbb::task_arena(1).execute([&] { a.build(s); });
    tbb::task_arena(2).execute([&] { b.build(s); });
    ASSERT_EQ(a.nodes().size(), b.nodes().size());
    EXPECT_EQ(std::memcmp(a.nodes().data(), b.nodes().data(), a.nodes().size_bytes()), 0);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.spheres().data(), b.spheres().data(), a.spheres().size_bytes()), 0);
}

}  // namespace
}  // namespace phos::photon
