// Tests of RGB to spectrum (spectrum/rgb_sigmoid.h): fits reproduce their RGB; the shipped sRGB
// table is what tools/rgb_sigmoid_table makes; RGB -> spectrum -> RGB through the table round-trips
// within 1e-3 over the sRGB gamut (the unit cube of linear sRGB); the spectra are reflectances
// (within [0, 1] at every wavelength); grey is flat and white is 1.
#include "spectrum/rgb_sigmoid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/rng.h"

namespace phos::spectrum {
namespace {

float max_error(Vec3 a, Vec3 b) {
    return std::max({std::fabs(a.x - b.x), std::fabs(a.y - b.y), std::fabs(a.z - b.z)});
}

TEST(RgbSigmoid, FitsReproduceTheirRgb) {
    for (const Vec3 rgb : {Vec3(0.5f, 0.5f, 0.5f), Vec3(0.8f, 0.1f, 0.1f), Vec3(0.05f, 0.6f, 0.2f),
                           Vec3(0.1f, 0.2f, 0.9f), Vec3(0.9f, 0.9f, 0.02f)}) {
        SigmoidPolynomial s;
        const float e = fit_sigmoid(rgb, s);
        EXPECT_LT(e, 1e-5f) << rgb.x << " " << rgb.y << " " << rgb.z;
        EXPECT_LT(max_error(reflectance_to_srgb(s), rgb), 1e-5f);
    }
}

TEST(RgbSigmoid, GreyIsFlatAndWhiteIsOne) {
    const SigmoidPolynomial grey = RgbSigmoidTable::srgb().lookup(Vec3(0.5f));
    for (float l = 360; l <= 830; l += 10) EXPECT_NEAR(grey(l), 0.5f, 2e-3f) << l;
    const SigmoidPolynomial white = RgbSigmoidTable::srgb().lookup(Vec3(1.0f));
    for (float l = 400; l <= 700; l += 10) EXPECT_NEAR(white(l), 1.0f, 2e-3f) << l;
    const SigmoidPolynomial black = RgbSigmoidTable::srgb().lookup(Vec3(0.0f));
    EXPECT_EQ(black(550), 0.0f);
}

TEST(RgbSigmoid, RoundTripsTheSrgbGamut) {
    // exact(): within 1e-3 (in fact 1e-5) everywhere; lookup() alone within 3e-3.
    const RgbSigmoidTable& t = RgbSigmoidTable::srgb();
    Sampler rng(5);
    float worst_lookup = 0, worst_exact = 0, below = 1, above = 0;
    Vec3 worst_rgb;
    for (int i = 0; i < 20000; ++i) {
        Vec3 rgb(rng.next(), rng.next(), rng.next());
        if (i < 8) rgb = Vec3(float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1));  // the corners
        const SigmoidPolynomial s = t.lookup(rgb), e = t.exact(rgb);
        const float el = max_error(reflectance_to_srgb(s), rgb);
        if (el > worst_lookup) worst_lookup = el, worst_rgb = rgb;
        worst_exact = std::max(worst_exact, max_error(reflectance_to_srgb(e), rgb));
        for (float l = 360; l <= 830; l += 47)
            below = std::min({below, s(l), e(l)}), above = std::max({above, s(l), e(l)});
    }
    std::printf(
        "[ measured ] table of %d^3 x 3: worst round-trip error %.2e by lookup (at %.3f, %.3f, %.3f), "
        "%.2e refined\n",
        t.resolution(), worst_lookup, worst_rgb.x, worst_rgb.y, worst_rgb.z, worst_exact);
    EXPECT_LT(worst_exact, 1e-3f);
    EXPECT_LT(worst_lookup, 3e-3f);
    EXPECT_GE(below, 0.0f);
    EXPECT_LE(above, 1.0f);
}

TEST(RgbSigmoid, TheShippedTableIsWhatTheToolMakes) {
    const RgbSigmoidTable& shipped = RgbSigmoidTable::srgb();
    float worst = 1;
    const RgbSigmoidTable fresh = RgbSigmoidTable::fit(shipped.resolution(), &worst);
    EXPECT_LT(worst, 1e-5f);
    EXPECT_TRUE(fresh.bytes() == shipped.bytes());
}

TEST(RgbSigmoid, BadTableBytesAreRefused) {
    const std::vector<uint8_t> ok = RgbSigmoidTable::srgb().bytes();
    EXPECT_THROW(RgbSigmoidTable::from_bytes(ok.data(), ok.size() - 4), std::runtime_error);
    std::vector<uint8_t> bad = ok;
    bad[0] = 'X';
    EXPECT_THROW(RgbSigmoidTable::from_bytes(bad.data(), bad.size()), std::runtime_error);
}

}  // namespace
}  // namespace phos::spectrum
