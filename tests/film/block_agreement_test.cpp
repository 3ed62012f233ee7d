// Block agreement on synthetic images whose noise and bias are known: independent Gaussian noise
// agrees, a block offset by 5 tolerances fails and is named, a 3 % offset of the whole image fails
// at low noise, block-correlated noise is caught by the fitted inflation, a blur passes only with
// the kernel's allowance, black blocks agree, and the tolerance's quantiles are the tables' values.
#include "film/block_agreement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"

namespace phos::film {
namespace {

// A smooth image with structure: a horizontal ramp in red, a vertical one in green, a bump in blue.
Rgb truth(int x, int y) {
    const float bump = std::exp(-((x - 20.0f) * (x - 20.0f) + (y - 30.0f) * (y - 30.0f)) / 200.0f);
    return Rgb(0.2f + 0.01f * float(x), 0.1f + 0.02f * float(y), 0.3f + bump);
}

// `truth` plus independent Gaussian noise of standard deviation `sigma` per pixel and channel
// (Box-Muller over a fixed generator, so the test is the same everywhere).
Image noisy(uint64_t seed, double sigma, int size = 64, const std::function<Rgb(int, int)>& f = truth) {
    std::mt19937_64 rng(seed);
    auto uniform = [&] { return (double(rng() >> 11) + 0.5) * 0x1.0p-53; };
    auto gauss = [&] { return std::sqrt(-2 * std::log(uniform())) * std::cos(2 * M_PI * uniform()); };
    Image img(size, size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const Rgb t = f(x, y);
            img.at(x, y) =
                Rgb(float(t.r + sigma * gauss()), float(t.g + sigma * gauss()), float(t.b + sigma * gauss()));
        }
    return img;
}

BlockSettings settings_for(int comparisons) {
    BlockSettings s;
    s.sigmas = tolerance_sigmas(comparisons);
    return s;
}

Agreement compare(const Image& a, const Image& b, const Image& ra, const Image& rb,
                  const BiasAllowance& bias = {}) {
    return compare_blocks({a, b}, bias, {ra, rb}, {}, settings_for(block_comparisons(a.width, a.height, 8)));
}

TEST(BlockAgreement, IndependentNoiseAgrees) {
    // 20 trials of 192 comparisons each at a combined false-failure chance of 1e-4 each: any
    // failure here would be a fault of the noise model, not bad luck worth mentioning.
    for (uint64_t trial = 0; trial < 20; ++trial) {
        const Image a = noisy(4 * trial, 0.2), b = noisy(4 * trial + 1, 0.2);
        const Image ra = noisy(4 * trial + 2, 0.05), rb = noisy(4 * trial + 3, 0.05);
        const Agreement g = compare(a, b, ra, rb);
        EXPECT_TRUE(g.agrees()) << "trial " << trial << ": " << describe(g.worst);
        EXPECT_EQ(g.blocks.size(), 192u);
        EXPECT_NEAR(g.mean_ratio, 1.0, 0.01);
        // Independent pixels: the block-level differences need no inflation beyond chance.
        EXPECT_LT(g.inflation, 1.5);
        EXPECT_LT(g.worst.excess(), 1.0);
    }
}

// The comparison of block (x, y), channel c.
const BlockComparison& block_at(const Agreement& g, int x, int y, int c) {
    for (const BlockComparison& b : g.blocks)
        if (b.x == x && b.y == y && b.channel == c) return b;
    throw std::runtime_error("no such block");
}

TEST(BlockAgreement, BlockOffsetByFiveTolerancesFailsAndIsNamed) {
    Image a = noisy(1, 0.2), b = noisy(2, 0.2);
    const Image ra = noisy(3, 0.05), rb = noisy(4, 0.05);
    const Agreement before = compare(a, b, ra, rb);
    ASSERT_TRUE(before.agrees());
    ASSERT_EQ(before.blocks.size(), 192u);
    // Offsetting both seeds' pixels leaves their differences (the noise estimate) and the reference
    // unchanged, so the block keeps its tolerance and ends 5 tolerances off (plus its own noise).
    const BlockComparison& was = block_at(before, 16, 8, 1);
    const float offset = float(5 * was.tolerance);
    for (int y = 8; y < 16; ++y)
        for (int x = 16; x < 24; ++x) a.at(x, y).g += offset, b.at(x, y).g += offset;
    const Agreement after = compare(a, b, ra, rb);
    EXPECT_FALSE(after.agrees());
    ASSERT_EQ(after.failing.size(), 1u);
    const BlockComparison& f = after.failing[0];
    EXPECT_EQ(f.x, 16);
    EXPECT_EQ(f.y, 8);
    EXPECT_EQ(f.channel, 1);
    EXPECT_NEAR(f.tolerance, was.tolerance, 1e-6 * was.tolerance);  // float sums
    EXPECT_NEAR(f.excess(), 5, 1.0);
    EXPECT_GT(f.ratio(), 1);
    EXPECT_EQ(after.worst.x, 16);
    EXPECT_EQ(after.worst.y, 8);
    EXPECT_NE(describe(f).find("block (16, 8) green"), std::string::npos) << describe(f);
}

TEST(BlockAgreement, GlobalOffsetOfThreePercentFailsAtLowNoise) {
    Image a = noisy(5, 0.002), b = noisy(6, 0.002);
    const Image ra = noisy(7, 0.002), rb = noisy(8, 0.002);
    ASSERT_TRUE(compare(a, b, ra, rb).agrees());
    for (Image* img : {&a, &b})
        for (Rgb& p : img->pixels) p = p * 1.03f;
    const Agreement g = compare(a, b, ra, rb);
    EXPECT_FALSE(g.mean_agrees());
    EXPECT_NEAR(g.mean_ratio, 1.03, 0.001);
    EXPECT_LT(g.mean_tolerance, 0.01);
    EXPECT_FALSE(g.failing.empty());
}

TEST(BlockAgreement, CorrelatedNoiseIsInflated) {
    // Each 8 x 8 block of each seed shifted by one Gaussian number of deviation 0.05, as photons
    // shared by a block's pixels would: pixel differences alone see only the 0.02 per-pixel noise.
    auto correlated = [](uint64_t seed) {
        Image img = noisy(seed, 0.02);
        const Image shifts = noisy(seed + 100, 0.05, 8, [](int, int) { return Rgb(0.0f); });
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) img.at(x, y) += Rgb(shifts.at(x / 8, y / 8).r);
        return img;
    };
    const Image a = correlated(11), b = correlated(12);
    const Image ra = noisy(13, 0.005), rb = noisy(14, 0.005);
    const Agreement g = compare(a, b, ra, rb);
    // A block mean's variance is 0.05^2 + 0.02^2 / 64; the pixel differences, which carry the block's
    // shift too, give (0.05^2 + 0.02^2) / 64: f = 55, fitted from 64 blocks (+-18 %).
    EXPECT_GT(g.inflation, 30);
    EXPECT_LT(g.inflation, 90);
    EXPECT_TRUE(g.agrees()) << describe(g.worst);
    EXPECT_LT(g.reference_inflation, 1.5);
}

TEST(BlockAgreement, KernelBlurPassesOnlyWithItsAllowance) {
    // The reference: a sharp vertical step at x = 32 (0.2 | 1.0); the tested image: the step blurred
    // by a box of radius 2 pixels, as a density-estimation kernel would blur it.
    auto step = [](int x, int) { return Rgb(x < 32 ? 0.2f : 1.0f); };
    auto blurred = [](int x, int) {
        double s = 0;
        for (int d = -2; d <= 2; ++d) s += x + d < 32 ? 0.2 : 1.0;
        return Rgb(float(s / 5));
    };
    const Image a = noisy(21, 0.001, 64, blurred), b = noisy(22, 0.001, 64, blurred);
    const Image ra = noisy(23, 0.001, 64, step), rb = noisy(24, 0.001, 64, step);
    const Agreement unbiased = compare(a, b, ra, rb);
    EXPECT_FALSE(unbiased.agrees());
    EXPECT_EQ(unbiased.worst.x == 24 || unbiased.worst.x == 32, true) << describe(unbiased.worst);
    const Agreement kernel = compare(a, b, ra, rb, {2.0, 0.0});
    EXPECT_TRUE(kernel.agrees()) << describe(kernel.worst);
}

TEST(BlockAgreement, BlackBlocksAgree) {
    const Image black(16, 16);
    const Agreement g = compare(black, black, black, black);
    EXPECT_TRUE(g.agrees());
    EXPECT_EQ(g.mean_ratio, 1.0);
    EXPECT_EQ(g.worst.excess(), 0.0);
    EXPECT_EQ(g.worst.ratio(), 1.0);
    // Black where the reference is lit is no agreement, however little noise either has.
    const Image lit = noisy(31, 0.0, 16);
    EXPECT_FALSE(compare(black, black, lit, lit).agrees());
}

TEST(BlockAgreement, PartialBlocksAtTheEdges) {
    const Image a = noisy(41, 0.1, 20), b = noisy(42, 0.1, 20), ra = noisy(43, 0.1, 20),
                rb = noisy(44, 0.1, 20);
    EXPECT_EQ(block_comparisons(20, 20, 8), 27);
    const Agreement g = compare(a, b, ra, rb);
    EXPECT_EQ(g.blocks.size(), 27u);
    EXPECT_EQ(g.blocks.back().x, 16);
    EXPECT_EQ(g.blocks.back().y, 16);
    EXPECT_TRUE(g.agrees()) << describe(g.worst);
}

TEST(BlockAgreement, RefusesMismatchedSizes) {
    const Image a(8, 8), b(8, 9);
    EXPECT_THROW(compare_blocks({a, a}, {}, {a, b}, {}, {}), InputError);
    BlockSettings zero;
    zero.block = 0;
    EXPECT_THROW(compare_blocks({a, a}, {}, {a, a}, {}, zero), InputError);
}

TEST(BlockAgreement, ToleranceQuantiles) {
    // Two-sided Gaussian quantiles: 5 % -> 1.960, 1e-4 over 1000 tests -> 1e-7 each -> 5.327.
    EXPECT_NEAR(tolerance_sigmas(1, 0.05), 1.95996, 1e-4);
    EXPECT_NEAR(tolerance_sigmas(1000, 1e-4), 5.3267, 1e-3);
    // Student t at the Gaussian tails (computed by integrating the t density): 64 degrees of
    // freedom at z = 5.3 -> 5.966, 16 -> 9.004; many degrees of freedom -> z.
    EXPECT_NEAR(student_sigmas(5.3, 64), 5.966, 0.005);
    EXPECT_NEAR(student_sigmas(5.3, 16), 9.004, 0.05);
    EXPECT_NEAR(student_sigmas(4.0, 1e6), 4.0, 1e-4);
}

}  // namespace
}  // namespace phos::film
