// Tests of the film's white balance (spectrum/color.h): the source white of a temperature lies on
// the CIE daylight locus from 4000 K (D65's chromaticity at 6504 K) and is the Planckian's below;
// the adaptation maps that white to the sRGB white (1, 1, 1), keeps luminance-neutral greys grey,
// and is the identity for 0 (no white balance) and nearly so at D65.
#include <gtest/gtest.h>

#include <cmath>

#include "spectrum/blackbody.h"
#include "spectrum/color.h"

namespace phos::spectrum {
namespace {

Vec3 srgb_of_xyz(Vec3 xyz) { return spectrum::apply(xyz_to_srgb(), xyz); }

TEST(WhiteBalance, SourceWhiteIsTheDaylightLocusOrThePlanckian) {
    // CIE D65 is the daylight illuminant of 6504 K: (0.3127, 0.3290).
    const Vec3 d65 = white_balance_source(6504.0f / 1.4388f * 1.4380f);
    const float sum = d65.x + d65.y + d65.z;
    EXPECT_NEAR(d65.y, 1.0f, 1e-6f);
    EXPECT_NEAR(d65.x / sum, 0.3127f, 2e-4f);
    EXPECT_NEAR(d65.y / sum, 0.3290f, 2e-4f);
    // D50 (5003 K): (0.3457, 0.3585).
    const Vec3 d50 = white_balance_source(5003.0f / 1.4388f * 1.4380f);
    EXPECT_NEAR(d50.x / (d50.x + d50.y + d50.z), 0.3457f, 2e-4f);
    EXPECT_NEAR(d50.y / (d50.x + d50.y + d50.z), 0.3585f, 2e-4f);
    // Below 4000 K, the Planckian of the (rescaled) temperature.
    const Blackbody b(3000.0 * 1.4388 / 1.4380);
    const Vec3 p = integrate_xyz([&](double l) { return double(b(float(l))); });
    const Vec3 w = white_balance_source(3000.0f);
    EXPECT_NEAR(w.x, p.x / p.y, 1e-5f);
    EXPECT_NEAR(w.z, p.z / p.y, 1e-5f);
}

TEST(WhiteBalance, TheSourceWhiteBecomesTheSrgbWhite) {
    for (float kelvin : {1800.0f, 2700.0f, 3200.0f, 4000.0f, 5000.0f, 6500.0f, 9000.0f, 20000.0f}) {
        const Mat3 m = white_balance(kelvin);
        const Vec3 white = spectrum::apply(m, srgb_of_xyz(white_balance_source(kelvin)));
        EXPECT_NEAR(white.x, 1.0f, 1e-5f) << kelvin;
        EXPECT_NEAR(white.y, 1.0f, 1e-5f) << kelvin;
        EXPECT_NEAR(white.z, 1.0f, 1e-5f) << kelvin;
        for (size_t i = 0; i < 3; ++i)
            for (size_t j = 0; j < 3; ++j) EXPECT_TRUE(std::isfinite(m[i][j])) << kelvin;
    }
    // A warm light balanced for its own temperature comes out grey: a 2700 K Planckian (the white
    // balance reads 2700 K as a Planckian of 2700 × 1.4388 / 1.4380 K, 0.06 % hotter).
    const Blackbody b(2700);
    const Vec3 rgb = srgb_of_xyz(integrate_xyz([&](double l) { return double(b(float(l))); }));
    const Vec3 balanced = spectrum::apply(white_balance(2700), rgb);
    EXPECT_GT(rgb.x, 1.5f * rgb.z);
    EXPECT_NEAR(balanced.x / balanced.y, 1.0f, 2e-3f);
    EXPECT_NEAR(balanced.z / balanced.y, 1.0f, 2e-3f);
}

TEST(WhiteBalance, ZeroIsTheIdentityAndD65NearlySo) {
    const Mat3 none = white_balance(0);
    const Mat3 d65 = white_balance(6504.0f / 1.4388f * 1.4380f);
    for (size_t i = 0; i < 3; ++i)
        for (size_t j = 0; j < 3; ++j) {
            EXPECT_EQ(none[i][j], i == j ? 1.0 : 0.0);
            EXPECT_NEAR(d65[i][j], i == j ? 1.0 : 0.0, 2e-3);
        }
}

}  // namespace
}  // namespace phos::spectrum
