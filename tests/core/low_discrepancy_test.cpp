// Tests of the scrambled low-discrepancy sequences (core/low_discrepancy.h): the tabulated Sobol
// dimension equals its definition, the index shuffle maps aligned blocks onto aligned blocks, and
// every aligned block of 2^k padded points is a (0,k,2)-net (each elementary interval of area
// 2^-k holds exactly one point), for any key.
#include "core/low_discrepancy.h"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace phos {
namespace {

// Sobol's second dimension by its definition: columns v_0 = 2^31, v_j+1 = v_j ^ (v_j >> 1).
uint32_t sobol2_reference(uint32_t s) {
    uint32_t y = 0;
    for (uint32_t i = s, v = 0x80000000u; i != 0; i >>= 1, v ^= v >> 1)
        if (i & 1u) y ^= v;
    return y;
}

uint32_t radical_inverse_reference(uint32_t s) {
    uint32_t x = 0;
    for (int j = 0; j < 32; ++j)
        if ((s >> j) & 1u) x |= 0x80000000u >> j;
    return x;
}

TEST(LowDiscrepancy, TablesEqualTheDefinitions) {
    Sampler rng(7);
    for (int i = 0; i < 100000; ++i) {
        const uint32_t s = i < 5000 ? uint32_t(i) : uint32_t(rng.next_bits());
        ASSERT_EQ(sobol2_bits(s), sobol2_reference(s)) << s;
        ASSERT_EQ(radical_inverse_bits(s), radical_inverse_reference(s)) << s;
    }
}

TEST(LowDiscrepancy, ShuffleMapsAlignedBlocksOntoAlignedBlocks) {
    Sampler rng(11);
    for (int trial = 0; trial < 50; ++trial) {
        const uint32_t key = uint32_t(rng.next_bits());
        for (int k = 1; k <= 12; ++k) {
            const uint32_t n = 1u << k;
            for (uint32_t block : {0u, 1u, 5u, 1000u}) {
                std::set<uint32_t> low;
                const uint32_t high = shuffle_index(block * n, key) >> k;
                for (uint32_t i = 0; i < n; ++i) {
                    const uint32_t t = shuffle_index(block * n + i, key);
                    ASSERT_EQ(t >> k, high) << "key " << key << " k " << k;
                    low.insert(t & (n - 1));
                }
                ASSERT_EQ(low.size(), n);  // a permutation of the block
            }
        }
    }
}

// Every elementary interval [a 2^-i, (a+1) 2^-i) x [b 2^-(k-i), (b+1) 2^-(k-i)) holds one point.
void expect_net(const std::vector<Vec2>& pts, int k) {
    for (int i = 0; i <= k; ++i) {
        std::vector<int> count(size_t(1) << k, 0);
        for (const Vec2& p : pts) {
            const int a = int(p.x * float(1 << i)), b = int(p.y * float(1 << (k - i)));
            ++count[size_t(a) * (size_t(1) << (k - i)) + size_t(b)];
        }
        for (int c : count) ASSERT_EQ(c, 1) << "intervals 2^-" << i << " x 2^-" << k - i;
    }
}

TEST(LowDiscrepancy, PaddedPointsOfEveryAlignedBlockFormANet) {
    Sampler rng(3);
    for (int trial = 0; trial < 20; ++trial) {
        const uint64_t key = rng.next_bits();
        for (int k : {2, 5, 8}) {
            const uint32_t n = 1u << k;
            for (uint32_t block : {0u, 3u}) {
                std::vector<Vec2> pts;
                std::vector<int> strata(n, 0);
                for (uint32_t s = block * n; s < (block + 1) * n; ++s) {
                    pts.push_back(padded_point2(s, key));
                    ++strata[size_t(padded_point1(s, key) * float(n))];
                }
                expect_net(pts, k);
                for (int c : strata) ASSERT_EQ(c, 1);
            }
        }
    }
}

TEST(LowDiscrepancy, DifferentKeysGiveDifferentSequences) {
    // Padding: two dimensions of one pixel must not repeat each other's points.
    int same = 0;
    for (uint32_t s = 0; s < 256; ++s) {
        const Vec2 a = padded_point2(s, 1), b = padded_point2(s, 2);
        same += a.x == b.x || a.y == b.y;
    }
    EXPECT_LT(same, 3);
}

}  // namespace
}  // namespace phos
