// Tests of the photon k-d tree: kNN and range queries against brute force on random, planar,
// duplicate and Cornell-box photon sets, the edge cases (empty map, k > n, radius 0), the split
// invariant, the filtered query, bit-identical builds at 1 and 2 threads, and the in-place build:
// the same tree as from a copy, and the invariants and input indices on large (parallel-path)
// inputs full of equal coordinates; save / load, and the layouts load refuses.
#include "photon/kdtree.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <functional>
#include <set>
#include <string>

#include "core/error.h"
#include "core/rng.h"
#include "photon/knn_brute_force.h"

namespace phos::photon {
namespace {

// A photon at p with normal n; `id` varies its power and wavelengths, so that the checks that a
// tree photon is its input photon compare those fields too.
Photon make_photon(Vec3 p, Vec3 n = Vec3(0, 1, 0), uint32_t id = 0) {
    Spectrum power;
    for (int i = 0; i < spectrum::kSpectrumSamples; ++i) power[i] = 1.0f + float((id + uint32_t(i)) % 5);
    return Photon(p, power, Wavelengths::visible(float(id % 1000) / 1000.0f), Vec3(0, 0, 1), n);
}

std::vector<Photon> random_cube(int n, uint64_t seed) {
    Sampler rng(seed);
    std::vector<Photon> v;
    for (int i = 0; i < n; ++i)
        v.push_back(make_photon(Vec3(rng.next(), rng.next(), rng.next()), Vec3(0, 1, 0), uint32_t(i)));
    return v;
}

// Points on the faces of the unit box (floor, ceiling, three walls), a dense disc on the floor,
// and a few exact duplicates: planar, axis-degenerate data as a Cornell box produces.
std::vector<Photon> cornell_like(int n, uint64_t seed) {
    Sampler rng(seed);
    std::vector<Photon> v;
    for (int i = 0; i < n; ++i) {
        const Vec2 u = rng.next2();
        const uint32_t face = rng.next_index(6);
        Vec3 p, nrm;
        switch (face) {
            case 0:
                p = {u.x, 0, u.y}, nrm = {0, 1, 0};
                break;
            case 1:
                p = {u.x, 1, u.y}, nrm = {0, -1, 0};
                break;
            case 2:
                p = {u.x, u.y, 1}, nrm = {0, 0, -1};
                break;
            case 3:
                p = {0, u.x, u.y}, nrm = {1, 0, 0};
                break;
            case 4:
                p = {1, u.x, u.y}, nrm = {-1, 0, 0};
                break;
            default:
                p = {0.5f + 0.05f * u.x, 0, 0.5f + 0.05f * u.y}, nrm = {0, 1, 0};
                break;
        }
        v.push_back(make_photon(p, nrm, uint32_t(i)));
    }
    for (int i = 0; i < n / 50; ++i) v.push_back(v[rng.next_index(uint32_t(v.size()))]);
    return v;
}

Vec3 random_query(Sampler& rng) { return Vec3(rng.next(), rng.next(), rng.next()) * 1.2f - Vec3(0.1f); }

// Tree answer mapped to input indices, sorted by (dist2, index).
std::vector<Neighbour> tree_knn(const PhotonKdTree& tree, Vec3 q, uint32_t k, float r2, KnnResult* res) {
    std::vector<Neighbour> out(k);
    *res = tree.knn(q, k, r2, out.data());
    out.resize(res->count);
    for (Neighbour& nb : out) nb.index = tree.input_index(nb.index);
    std::sort(out.begin(), out.end(), [](const Neighbour& a, const Neighbour& b) {
        return a.dist2 < b.dist2 || (a.dist2 == b.dist2 && a.index < b.index);
    });
    return out;
}

// The same distances, and the same photons except that photons tied at the k-th distance may be
// swapped for one another.
void expect_same_knn(const std::vector<Photon>& input, const PhotonKdTree& tree, Vec3 q, uint32_t k,
                     float r2) {
    KnnResult got_r;
    const std::vector<Neighbour> got = tree_knn(tree, q, k, r2, &got_r);
    std::vector<Neighbour> want(std::max<uint32_t>(k, 1));
    const KnnResult want_r = testing::knn_brute_force(input, q, k, r2, want.data());
    want.resize(want_r.count);
    ASSERT_EQ(got_r.count, want_r.count) << "k=" << k << " r2=" << r2;
    EXPECT_EQ(got_r.max_dist2, want_r.max_dist2);
    for (size_t i = 0; i < got.size(); ++i) {
        ASSERT_EQ(got[i].dist2, want[i].dist2) << i;
        if (got[i].dist2 < want_r.max_dist2) {
            ASSERT_EQ(got[i].index, want[i].index) << i;
        }
    }
}

std::vector<uint32_t> tree_range(const PhotonKdTree& tree, Vec3 q, float r2) {
    std::vector<uint32_t> v;
    tree.for_each_in_radius(q, r2, [&](uint32_t i, float d2) {
        EXPECT_EQ(d2, detail::dist2(tree.photon(i).position, q));
        v.push_back(tree.input_index(i));
    });
    std::sort(v.begin(), v.end());
    return v;
}

std::vector<uint32_t> brute_range(const std::vector<Photon>& input, Vec3 q, float r2) {
    std::vector<uint32_t> v;
    for (uint32_t i = 0; i < input.size(); ++i)
        if (detail::dist2(input[i].position, q) <= r2) v.push_back(i);
    return v;
}

KdTreeOptions with_index(uint32_t leaf) {
    KdTreeOptions o;
    o.leaf_size = leaf;
    o.keep_input_index = true;
    return o;
}

class KdTreeLeaf : public ::testing::TestWithParam<uint32_t> {};

TEST_P(KdTreeLeaf, KnnMatchesBruteForceRandomCube) {
    const auto input = random_cube(5000, 1);
    const PhotonKdTree tree(input, with_index(GetParam()));
    Sampler rng(2);
    for (int i = 0; i < 300; ++i) {
        const Vec3 q = random_query(rng);
        for (uint32_t k : {1u, 7u, 50u, 200u})
            for (float r2 : {kInf, 0.01f, 0.0004f}) expect_same_knn(input, tree, q, k, r2);
    }
}

TEST_P(KdTreeLeaf, KnnMatchesBruteForceCornellBox) {
    const auto input = cornell_like(8000, 3);
    const PhotonKdTree tree(input, with_index(GetParam()));
    Sampler rng(4);
    for (int i = 0; i < 300; ++i) {
        // Queries on the surfaces (where a renderer asks) and in the air.
        Vec3 q = i % 2 ? input[rng.next_index(uint32_t(input.size()))].position : random_query(rng);
        for (uint32_t k : {1u, 16u, 100u}) {
            for (float r2 : {kInf, 0.0025f, 0.0f}) expect_same_knn(input, tree, q, k, r2);
        }
    }
}

TEST_P(KdTreeLeaf, RangeMatchesBruteForce) {
    const auto input = cornell_like(6000, 5);
    const PhotonKdTree tree(input, with_index(GetParam()));
    Sampler rng(6);
    size_t total = 0;
    for (int i = 0; i < 200; ++i) {
        const Vec3 q = i % 2 ? input[rng.next_index(uint32_t(input.size()))].position : random_query(rng);
        for (float r2 : {0.0f, 0.001f, 0.01f, 0.1f}) {
            const auto want = brute_range(input, q, r2);
            ASSERT_EQ(tree_range(tree, q, r2), want);
            total += want.size();
        }
    }
    EXPECT_GT(total, 10000u);  // the radii really do catch photons
}

TEST_P(KdTreeLeaf, SplitInvariantHolds) {
    const auto input = cornell_like(3000, 7);
    const PhotonKdTree tree(input, with_index(GetParam()));
    const auto P = tree.photons();
    // Every split photon's left range is <= and right range >= its coordinate on its axis.
    std::vector<std::pair<uint32_t, uint32_t>> todo{{0u, uint32_t(P.size())}};
    int splits = 0;
    while (!todo.empty()) {
        auto [b, e] = todo.back();
        todo.pop_back();
        if (e - b <= tree.leaf_size()) {
            for (uint32_t i = b; i < e; ++i) EXPECT_EQ(P[i].split_axis(), 3);
            continue;
        }
        const uint32_t m = b + (e - b) / 2;
        const int a = P[m].split_axis();
        ASSERT_LT(a, 3);
        const float s = detail::coord(P[m].position, a);
        for (uint32_t i = b; i < m; ++i) ASSERT_LE(detail::coord(P[i].position, a), s);
        for (uint32_t i = m + 1; i < e; ++i) ASSERT_GE(detail::coord(P[i].position, a), s);
        ++splits;
        todo.push_back({b, m});
        todo.push_back({m + 1, e});
    }
    EXPECT_GT(splits, 100);
    // The build is a permutation of the input.
    std::vector<uint32_t> idx(P.size());
    for (uint32_t i = 0; i < P.size(); ++i) {
        idx[i] = tree.input_index(i);
        EXPECT_EQ(P[i].position, input[idx[i]].position);
        EXPECT_EQ(P[i].power(), input[idx[i]].power());
        EXPECT_EQ(P[i].lambda_code, input[idx[i]].lambda_code);
        EXPECT_EQ(P[i].flags, input[idx[i]].flags);
    }
    std::sort(idx.begin(), idx.end());
    for (uint32_t i = 0; i < idx.size(); ++i) ASSERT_EQ(idx[i], i);
}

INSTANTIATE_TEST_SUITE_P(LeafSizes, KdTreeLeaf, ::testing::Values(2u, 8u, 16u));

TEST(KdTree, EmptyMap) {
    const PhotonKdTree tree(std::vector<Photon>{}, with_index(8));
    EXPECT_TRUE(tree.empty());
    Neighbour out[4];
    const KnnResult r = tree.knn(Vec3(0.0f), 4, kInf, out);
    EXPECT_EQ(r.count, 0u);
    EXPECT_EQ(r.max_dist2, 0.0f);
    int calls = 0;
    tree.for_each_in_radius(Vec3(0.0f), kInf, [&](uint32_t, float) { ++calls; });
    EXPECT_EQ(calls, 0);
    EXPECT_EQ(PhotonKdTree().knn(Vec3(0.0f), 4, kInf, out).count, 0u);
}

TEST(KdTree, KLargerThanNAndZeroK) {
    const auto input = random_cube(37, 8);
    const PhotonKdTree tree(input, with_index(4));
    expect_same_knn(input, tree, Vec3(0.5f), 100, kInf);
    std::vector<Neighbour> out(100);
    EXPECT_EQ(tree.knn(Vec3(0.5f), 100, kInf, out.data()).count, 37u);
    EXPECT_EQ(tree.knn(Vec3(0.5f), 0, kInf, out.data()).count, 0u);
    EXPECT_EQ(tree.knn(Vec3(0.5f), 5, -1.0f, out.data()).count, 0u);
}

TEST(KdTree, RadiusZeroFindsCoincidentPhotonsOnly) {
    auto input = random_cube(500, 9);
    const Vec3 p = input[123].position;
    input.push_back(make_photon(p));
    input.push_back(make_photon(p));
    const PhotonKdTree tree(input, with_index(8));
    std::vector<Neighbour> out(10);
    const KnnResult r = tree.knn(p, 10, 0.0f, out.data());
    ASSERT_EQ(r.count, 3u);
    EXPECT_EQ(r.max_dist2, 0.0f);
    std::set<uint32_t> got;
    for (uint32_t i = 0; i < r.count; ++i) got.insert(tree.input_index(out[i].index));
    EXPECT_EQ(got, (std::set<uint32_t>{123, 500, 501}));
    EXPECT_EQ(tree_range(tree, p, 0.0f), (std::vector<uint32_t>{123, 500, 501}));
}

TEST(KdTree, AllDuplicates) {
    std::vector<Photon> input(1000, make_photon(Vec3(0.3f, 0.3f, 0.3f)));
    input.push_back(make_photon(Vec3(0.9f, 0.3f, 0.3f)));
    const PhotonKdTree tree(input, with_index(8));
    std::vector<Neighbour> out(1001);
    KnnResult r = tree.knn(Vec3(0.3f, 0.3f, 0.3f), 50, kInf, out.data());
    EXPECT_EQ(r.count, 50u);
    EXPECT_EQ(r.max_dist2, 0.0f);
    r = tree.knn(Vec3(1.0f, 0.3f, 0.3f), 1, kInf, out.data());
    ASSERT_EQ(r.count, 1u);
    EXPECT_EQ(tree.input_index(out[0].index), 1000u);
    r = tree.knn(Vec3(1.0f, 0.3f, 0.3f), 1001, kInf, out.data());
    EXPECT_EQ(r.count, 1001u);
    EXPECT_EQ(tree_range(tree, Vec3(0.3f, 0.3f, 0.3f), 0.01f).size(), 1000u);
}

TEST(KdTree, AllOnAPlaneAndOnALine) {
    Sampler rng(10);
    std::vector<Photon> plane, line;
    for (int i = 0; i < 4000; ++i) {
        plane.push_back(make_photon(Vec3(rng.next(), 0.25f, rng.next())));
        line.push_back(make_photon(Vec3(0.5f, rng.next(), 0.5f)));
    }
    for (const auto* input : {&plane, &line}) {
        const PhotonKdTree tree(*input, with_index(8));
        for (uint32_t i = 0; i < tree.size(); ++i)
            EXPECT_NE(tree.photon(i).split_axis(), input == &plane ? 1 : 0);
        for (int i = 0; i < 200; ++i) {
            const Vec3 q = i % 2 ? (*input)[rng.next_index(4000)].position : random_query(rng);
            expect_same_knn(*input, tree, q, 30, kInf);
            expect_same_knn(*input, tree, q, 30, 0.001f);
        }
    }
}

TEST(KdTree, SortedInputAndHeavyTies) {
    // Presorted input (a common worst case for quickselect pivots) and coordinates taking only a
    // few distinct values (long runs of equal keys in every partition).
    Sampler rng(16);
    std::vector<Photon> sorted = random_cube(30000, 17), ties;
    std::sort(sorted.begin(), sorted.end(),
              [](const Photon& a, const Photon& b) { return a.position.x < b.position.x; });
    for (int i = 0; i < 30000; ++i)
        ties.push_back(
            make_photon(Vec3(float(rng.next_index(3)), float(rng.next_index(4)) * 0.1f, rng.next())));
    for (const auto* input : {&sorted, &ties}) {
        const PhotonKdTree tree(*input, with_index(8));
        for (int i = 0; i < 100; ++i) {
            const Vec3 q = (*input)[rng.next_index(30000)].position + Vec3(0.001f * rng.next());
            expect_same_knn(*input, tree, q, 20, kInf);
            ASSERT_EQ(tree_range(tree, q, 0.002f), brute_range(*input, q, 0.002f));
        }
    }
}

TEST(KdTree, FilteredKnnMatchesBruteForceOnFilteredSet) {
    // A thin wall: photons on both faces of the plane x = 0.5, 1e-3 apart. A normal test must
    // return k photons of the query's side only.
    Sampler rng(11);
    std::vector<Photon> input;
    for (int i = 0; i < 6000; ++i) {
        const bool left = i % 2;
        input.push_back(make_photon(Vec3(left ? 0.4995f : 0.5005f, rng.next(), rng.next()),
                                    Vec3(left ? -1.0f : 1.0f, 0, 0)));
    }
    const PhotonKdTree tree(input, with_index(8));
    std::vector<Photon> right;
    std::vector<uint32_t> right_index;
    for (uint32_t i = 0; i < input.size(); ++i)
        if (input[i].normal().x > 0) right.push_back(input[i]), right_index.push_back(i);
    std::vector<Neighbour> out(40), want(40);
    for (int i = 0; i < 100; ++i) {
        const Vec3 q(0.5005f, rng.next(), rng.next());
        const KnnResult r = tree.knn_if(
            q, 40, 0.01f, out.data(), [](const Photon& p) { return dot(p.normal(), Vec3(1, 0, 0)) > 0.9f; });
        const KnnResult w = testing::knn_brute_force(right, q, 40, 0.01f, want.data());
        ASSERT_EQ(r.count, w.count);
        EXPECT_EQ(r.max_dist2, w.max_dist2);
        std::set<uint32_t> got, exp;
        for (uint32_t j = 0; j < r.count; ++j) got.insert(tree.input_index(out[j].index));
        for (uint32_t j = 0; j < w.count; ++j) exp.insert(right_index[want[j].index]);
        EXPECT_EQ(got, exp);
    }
}

TEST(KdTree, HeapOrderPutsFarthestFirst) {
    const auto input = random_cube(2000, 12);
    const PhotonKdTree tree(input);
    EXPECT_FALSE(tree.has_input_index());
    std::vector<Neighbour> out(25);
    const KnnResult r = tree.knn(Vec3(0.5f), 25, kInf, out.data());
    ASSERT_EQ(r.count, 25u);
    for (const Neighbour& nb : out) {
        EXPECT_LE(nb.dist2, out[0].dist2);
        EXPECT_EQ(nb.dist2, detail::dist2(tree.photon(nb.index).position, Vec3(0.5f)));
    }
    EXPECT_EQ(r.max_dist2, out[0].dist2);
}

TEST(KdTree, BuildIsIdenticalAtOneAndTwoThreads) {
    // Large enough that the parallel paths (subtrees, bounding boxes) are taken.
    const auto input = cornell_like(400000, 13);
    PhotonKdTree t1, t2;
    tbb::task_arena(1).execute([&] { t1.build(input, with_index(8)); });
    tbb::task_arena(2).execute([&] { t2.build(input, with_index(8)); });
    ASSERT_EQ(t1.size(), input.size());
    ASSERT_EQ(t2.size(), input.size());
    EXPECT_EQ(std::memcmp(t1.photons().data(), t2.photons().data(), input.size() * sizeof(Photon)), 0);
    for (uint32_t i = 0; i < t1.size(); ++i) ASSERT_EQ(t1.input_index(i), t2.input_index(i));
    // And the big tree still answers correctly.
    Sampler rng(14);
    for (int i = 0; i < 20; ++i) expect_same_knn(input, t2, random_query(rng), 50, 0.01f);
}

TEST(KdTree, RejectsNonFinitePositions) {
    auto input = random_cube(10, 15);
    input[3].position.y = NAN;
    PhotonKdTree tree;
    EXPECT_THROW(tree.build(input), InputError);
    // The in-place build refuses before touching the array, and names the first bad photon.
    input[7].position.z = -kInf;
    const std::vector<Photon> before = input;
    try {
        tree.build(std::move(input));
        ADD_FAILURE() << "no exception";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "photon map: photon 3 has a non-finite position");
    }
    ASSERT_EQ(input.size(), before.size());
    EXPECT_EQ(std::memcmp(input.data(), before.data(), before.size() * sizeof(Photon)), 0);
    EXPECT_TRUE(tree.empty());
}

// ---- the in-place build and large inputs (the parallel top-level selection) ----

// Every split photon's left range is <= and right range >= its coordinate on its axis, leaf
// photons carry axis 3, and tree photon i is input photon input_index(i) (all its bits but the
// axis), each input photon exactly once.
::testing::AssertionResult valid_tree(const std::vector<Photon>& input, const PhotonKdTree& tree) {
    const auto P = tree.photons();
    if (P.size() != input.size()) return ::testing::AssertionFailure() << "size " << P.size();
    std::vector<std::pair<uint32_t, uint32_t>> todo{{0u, uint32_t(P.size())}};
    size_t splits = 0;
    while (!todo.empty()) {
        const auto [b, e] = todo.back();
        todo.pop_back();
        if (e - b <= tree.leaf_size()) {
            for (uint32_t i = b; i < e; ++i)
                if (P[i].split_axis() != 3) return ::testing::AssertionFailure() << "leaf photon " << i;
            continue;
        }
        const uint32_t m = b + (e - b) / 2;
        const int a = P[m].split_axis();
        if (a > 2) return ::testing::AssertionFailure() << "split photon " << m << " has no axis";
        const float s = detail::coord(P[m].position, a);
        for (uint32_t i = b; i < m; ++i)
            if (!(detail::coord(P[i].position, a) <= s))
                return ::testing::AssertionFailure() << "left of split " << m << ": " << i;
        for (uint32_t i = m + 1; i < e; ++i)
            if (!(detail::coord(P[i].position, a) >= s))
                return ::testing::AssertionFailure() << "right of split " << m << ": " << i;
        ++splits;
        todo.push_back({b, m});
        todo.push_back({m + 1, e});
    }
    if (P.size() > tree.leaf_size() && splits == 0) return ::testing::AssertionFailure() << "no splits";
    if (!tree.has_input_index()) return ::testing::AssertionSuccess();
    std::vector<uint8_t> seen(input.size(), 0);
    for (uint32_t i = 0; i < P.size(); ++i) {
        const uint32_t j = tree.input_index(i);
        if (j >= input.size() || seen[j]++)
            return ::testing::AssertionFailure() << "input_index(" << i << ")";
        Photon want = input[j];
        want.set_split_axis(P[i].split_axis());
        if (std::memcmp(&want, &P[i], sizeof(Photon)) != 0)
            return ::testing::AssertionFailure() << "tree photon " << i << " is not input photon " << j;
    }
    return ::testing::AssertionSuccess();
}

bool same_tree(const PhotonKdTree& a, const PhotonKdTree& b) {
    if (a.size() != b.size() || a.has_input_index() != b.has_input_index()) return false;
    if (std::memcmp(a.photons().data(), b.photons().data(), a.size() * sizeof(Photon)) != 0) return false;
    for (uint32_t i = 0; a.has_input_index() && i < a.size(); ++i)
        if (a.input_index(i) != b.input_index(i)) return false;
    return true;
}

// 2^20 + photons: the Cornell-like walls (coordinates exactly 0 or 1 on one axis each), a quarter
// of them on a coarse lattice of 5 values per axis (long runs of equal coordinates everywhere),
// and exact duplicates.
std::vector<Photon> large_ties(uint64_t seed) {
    std::vector<Photon> v = cornell_like(1 << 20, seed);
    Sampler rng(seed + 1);
    for (size_t i = 0; i < v.size(); i += 4)
        v[i].position =
            Vec3(float(rng.next_index(5)), float(rng.next_index(5)), float(rng.next_index(5))) * 0.25f;
    return v;
}

TEST(KdTree, LoadRestoresTheTreeAndRefusesOtherLayouts) {
    KdTreeOptions o;
    o.leaf_size = 4;
    const PhotonKdTree tree(random_cube(100, 16), o);
    std::string bytes;
    ByteWriter w(bytes);
    tree.save(w);
    const auto load = [](const std::string& b) {
        ByteReader r(b, "'map'");
        PhotonKdTree t;
        t.load(r);
        return t;
    };
    const PhotonKdTree back = load(bytes);
    ASSERT_EQ(back.size(), tree.size());
    EXPECT_EQ(std::memcmp(back.photons().data(), tree.photons().data(), tree.photons().size_bytes()), 0);
    // The photons follow a 4-byte leaf size and an 8-byte count; the root's split photon is 50.
    const size_t root = 4 + 8 + 50 * sizeof(Photon);
    const auto with_root = [&](const std::function<void(Photon&)>& change) {
        std::string b = bytes;
        Photon p;
        std::memcpy(&p, b.data() + root, sizeof p);
        change(p);
        std::memcpy(b.data() + root, &p, sizeof p);
        return b;
    };
    EXPECT_THROW(load(with_root([](Photon& p) { p.set_split_axis(3); })), InputError)
        << "a split photon with no axis (traverse() would index past its 3 coordinates)";
    EXPECT_THROW(load(with_root([](Photon& p) { p.position.x = NAN; })), InputError);
    std::string leaf_marked = bytes;
    Photon first;
    std::memcpy(&first, leaf_marked.data() + 12, sizeof first);
    EXPECT_EQ(first.split_axis(), 3) << "photon 0 lies in a leaf";
    first.set_split_axis(0);
    std::memcpy(leaf_marked.data() + 12, &first, sizeof first);
    EXPECT_THROW(load(leaf_marked), InputError) << "a leaf photon marked as a split";
}

TEST(KdTree, InPlaceBuildMatchesSpanBuild) {
    const auto input = cornell_like(300000, 20);
    for (bool keep : {false, true}) {
        KdTreeOptions o;
        o.keep_input_index = keep;
        const PhotonKdTree from_span(input, o);
        std::vector<Photon> moved = input;
        const Photon* buffer = moved.data();
        PhotonKdTree in_place;
        in_place.build(std::move(moved), o);
        EXPECT_EQ(in_place.photons().data(), buffer);  // the very array, permuted
        EXPECT_TRUE(same_tree(from_span, in_place));
        EXPECT_TRUE(valid_tree(input, in_place));
        EXPECT_EQ(in_place.has_input_index(), keep);
        // And through the constructor.
        EXPECT_TRUE(same_tree(from_span, PhotonKdTree(std::vector<Photon>(input), o)));
    }
    // Rebuilding from the tree's own array (the span aliases photons_) gives a valid tree.
    PhotonKdTree tree(input, with_index(8));
    const std::vector<Photon> own(tree.photons().begin(), tree.photons().end());
    tree.build(tree.photons(), with_index(8));
    EXPECT_TRUE(valid_tree(own, tree));
}

TEST(KdTree, LargeBuildIsIdenticalAtOneAndTwoThreads) {
    // Large enough for the parallel top-level selection (and its exchanges between chunks).
    const auto input = large_ties(21);
    for (uint32_t leaf : {8u, 16u}) {
        PhotonKdTree t1, t2, t2_no_index;
        tbb::task_arena(1).execute([&] { t1.build(input, with_index(leaf)); });
        tbb::task_arena(2).execute([&] { t2.build(std::vector<Photon>(input), with_index(leaf)); });
        KdTreeOptions o;
        o.leaf_size = leaf;
        tbb::task_arena(2).execute([&] { t2_no_index.build(input, o); });
        EXPECT_TRUE(same_tree(t1, t2));
        EXPECT_EQ(
            std::memcmp(t1.photons().data(), t2_no_index.photons().data(), input.size() * sizeof(Photon)), 0);
        EXPECT_TRUE(valid_tree(input, t2));
    }
}

TEST(KdTree, SplitAxisIsTheWidestExtentOfTheNodesPoints) {
    // The layout's contract: each split is along the axis of largest extent of its range's points
    // (the first such axis on a tie). The children's boxes come out of the selections (the
    // chunked one above 2^18 photons, the serial one that takes boxes as it partitions from 2^16,
    // the plain one below), so a box missing any photon shows here as a wrong axis somewhere.
    for (const auto& input : {cornell_like(600000, 31), large_ties(25)}) {
        PhotonKdTree tree;
        tbb::task_arena(2).execute([&] { tree.build(input, with_index(8)); });
        const auto P = tree.photons();
        std::vector<std::pair<uint32_t, uint32_t>> todo{{0u, uint32_t(P.size())}};
        uint32_t checked = 0;
        while (!todo.empty()) {
            const auto [b, e] = todo.back();
            todo.pop_back();
            if (e - b <= tree.leaf_size()) continue;
            float lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf};
            for (uint32_t i = b; i < e; ++i) {
                for (int a = 0; a < 3; ++a) {
                    lo[a] = std::min(lo[a], detail::coord(P[i].position, a));
                    hi[a] = std::max(hi[a], detail::coord(P[i].position, a));
                }
            }
            int widest = 0;
            for (int a = 1; a < 3; ++a)
                if (hi[a] - lo[a] > hi[widest] - lo[widest]) widest = a;
            const uint32_t m = b + (e - b) / 2;
            ASSERT_EQ(P[m].split_axis(), widest) << "node [" << b << ", " << e << ")";
            ++checked;
            todo.push_back({b, m});
            todo.push_back({m + 1, e});
        }
        EXPECT_GT(checked, 30000u);
    }
}

TEST(KdTree, BuildThreadTimesFitTheBuild) {
    // -v's split of the build's thread time: work on ranges of 2^18 photons and more counts as
    // top levels (none in a smaller build), the rest below them; on one thread the two together
    // fit in the build's own time (timing a piece twice, or nested pieces, would not).
    const auto small = cornell_like(100000, 41), large = cornell_like(700000, 42);
    for (const auto* input : {&small, &large}) {
        PhotonKdTree tree;
        double wall = 0;
        tbb::task_arena(1).execute([&] {
            const auto t0 = std::chrono::steady_clock::now();
            tree.build(*input, with_index(8));
            wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        });
        const KdBuildStats& s = tree.build_stats();
        EXPECT_GT(s.below_seconds, 0.0);
        if (input == &small) {
            EXPECT_EQ(s.top_seconds, 0.0);
        } else {
            EXPECT_GT(s.top_seconds, 0.0);
        }
        EXPECT_LE(s.top_seconds + s.below_seconds, wall);
    }
    // A tree read back was not built here: it forgets its last build's figures.
    std::string bytes;
    ByteWriter out(bytes);
    PhotonKdTree(small, with_index(8)).save(out);
    PhotonKdTree reused(large, with_index(8));
    ASSERT_GT(reused.build_stats().top_seconds, 0.0);
    ByteReader in(bytes, "'map'");
    reused.load(in);
    EXPECT_EQ(reused.build_stats().top_seconds + reused.build_stats().below_seconds, 0.0);
}

TEST(KdTree, LargeBuildInvariantsOnDegenerateInputs) {
    // Inputs that stress the selection: ties everywhere, all duplicates, two values per axis,
    // a plane, presorted and reverse-sorted input, plus a kNN spot check on each.
    const uint32_t n = (1 << 20) + 3;
    Sampler rng(22);
    std::vector<std::vector<Photon>> inputs;
    inputs.push_back(large_ties(23));
    inputs.emplace_back(n, make_photon(Vec3(0.5f, 0.25f, 0.75f)));
    inputs.back()[n / 3].position = Vec3(0.6f, 0.25f, 0.75f);
    std::vector<Photon> two, plane;
    for (uint32_t i = 0; i < n; ++i) {
        two.push_back(
            make_photon(Vec3(float(rng.next_index(2)), float(rng.next_index(2)), float(rng.next_index(2)))));
        plane.push_back(make_photon(Vec3(rng.next(), 0.25f, rng.next())));
    }
    inputs.push_back(std::move(two));
    inputs.push_back(std::move(plane));
    std::vector<Photon> sorted = random_cube(int(n), 24);
    std::sort(sorted.begin(), sorted.end(),
              [](const Photon& a, const Photon& b) { return a.position.x < b.position.x; });
    inputs.push_back(sorted);
    std::reverse(sorted.begin(), sorted.end());
    inputs.push_back(std::move(sorted));
    for (size_t c = 0; c < inputs.size(); ++c) {
        SCOPED_TRACE(c);
        const auto& input = inputs[c];
        PhotonKdTree tree;
        tbb::task_arena(2).execute([&] { tree.build(input, with_index(8)); });
        ASSERT_TRUE(valid_tree(input, tree));
        for (int i = 0; i < 3; ++i)
            expect_same_knn(input, tree, input[rng.next_index(n)].position, 20, 1e-4f);
    }
}

}  // namespace
}  // namespace phos::photon
