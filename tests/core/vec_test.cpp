// core/vec.h: next_float against std::nextafter, bit for bit (ray spawning uses it instead).
#include "core/vec.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

#include "core/rng.h"

namespace phos {
namespace {

TEST(NextFloat, EqualsStdNextafterBitForBit) {
    const float inf = std::numeric_limits<float>::infinity();
    const float special[] = {0.0f,          -0.0f,          kInf,      -kInf,      1e38f,     -1e38f,
                             3.4028235e38f, -3.4028235e38f, 0x1p-149f, -0x1p-149f, 0x1p-126f, -0x1p-126f,
                             1.0f,          -1.0f,          inf,       -inf};
    int mismatches = 0;
    const auto check = [&](float x, float toward) {
        if (std::bit_cast<uint32_t>(next_float(x, toward)) !=
            std::bit_cast<uint32_t>(std::nextafter(x, toward)))
            ++mismatches;
    };
    for (float x : special)
        for (float t : special) check(x, t);
    Sampler rng(3);
    for (int i = 0; i < 1000000; ++i) {
        // Random bit patterns (every exponent, denormals) that are not NaN.
        const float x = std::bit_cast<float>(uint32_t(rng.next_bits()));
        if (std::isnan(x)) continue;
        check(x, kInf);
        check(x, -kInf);
        check(x, 0.0f);
        check(x, -0.0f);
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_TRUE(std::isnan(next_float(std::nanf(""), 1.0f)));
    EXPECT_TRUE(std::isnan(next_float(1.0f, std::nanf(""))));
}

}  // namespace
}  // namespace phos
