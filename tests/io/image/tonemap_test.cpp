// Tests of io/image/tonemap: sRGB OETF known values, its inverse, 8-bit rounding/clamping, exposure.
#include "io/image/tonemap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace phos::io {
namespace {

TEST(Tonemap, SrgbOetfKnownValues) {
    EXPECT_FLOAT_EQ(linear_to_srgb(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(linear_to_srgb(1.0f), 1.0f);
    // Linear segment below the 0.0031308 knee: slope 12.92.
    EXPECT_FLOAT_EQ(linear_to_srgb(0.002f), 0.02584f);
    // Power segment: 1.055 * x^(1/2.4) - 0.055.
    EXPECT_NEAR(linear_to_srgb(0.5f), 0.735356983f, 1e-6f);
    EXPECT_NEAR(linear_to_srgb(0.18f), 0.461356129f, 1e-6f);
    // Both segments meet at the knee (continuity).
    EXPECT_NEAR(linear_to_srgb(0.0031308f), 0.04045f, 1e-5f);
}

TEST(Tonemap, SrgbInverseKnownValuesAndRoundTrip) {
    EXPECT_NEAR(srgb_to_linear(0.5f), 0.214041144f, 1e-6f);
    EXPECT_FLOAT_EQ(srgb_to_linear(0.04f), 0.04f / 12.92f);
    for (int i = 0; i <= 100; ++i) {
        const float x = float(i) / 100.0f;
        EXPECT_NEAR(srgb_to_linear(linear_to_srgb(x)), x, 1e-6f) << x;
    }
}

TEST(Tonemap, EightBitRoundingClampingAndNan) {
    EXPECT_EQ(linear_to_srgb8(0.0f), 0);
    EXPECT_EQ(linear_to_srgb8(1.0f), 255);
    EXPECT_EQ(linear_to_srgb8(-3.0f), 0);
    EXPECT_EQ(linear_to_srgb8(7.0f), 255);
    EXPECT_EQ(linear_to_srgb8(std::numeric_limits<float>::infinity()), 255);
    EXPECT_EQ(linear_to_srgb8(std::numeric_limits<float>::quiet_NaN()), 0);
    EXPECT_EQ(linear_to_srgb8(0.5f), 188);   // 0.73536 * 255 = 187.51 -> rounds up
    EXPECT_EQ(linear_to_srgb8(0.18f), 118);  // 0.46136 * 255 = 117.65
    // Every code survives decode + encode exactly.
    for (int c = 0; c < 256; ++c) EXPECT_EQ(linear_to_srgb8(srgb8_to_linear(uint8_t(c))), c) << c;
    EXPECT_FLOAT_EQ(srgb8_to_linear(255), 1.0f);
    EXPECT_FLOAT_EQ(srgb8_to_linear(0), 0.0f);
}

TEST(Tonemap, Exposure) {
    EXPECT_FLOAT_EQ(exposure_scale(0.0f), 1.0f);
    EXPECT_FLOAT_EQ(exposure_scale(1.0f), 2.0f);
    EXPECT_FLOAT_EQ(exposure_scale(-2.0f), 0.25f);

    Image img(2, 1);
    img.at(0, 0) = Rgb(0.25f, 0.5f, 0.0f);
    img.at(1, 0) = Rgb(0.6f, 0.0f, 1.0f);
    const std::vector<uint8_t> bytes = to_srgb8(img, 1.0f);  // doubles: 0.5, 1, 0 / 1.2, 0, 2
    ASSERT_EQ(bytes.size(), 6u);
    EXPECT_EQ(bytes[0], 188);
    EXPECT_EQ(bytes[1], 255);
    EXPECT_EQ(bytes[2], 0);
    EXPECT_EQ(bytes[3], 255);
    EXPECT_EQ(bytes[4], 0);
    EXPECT_EQ(bytes[5], 255);
}

}  // namespace
}  // namespace phos::io
