// Tests of the standard illuminants' tables (spectrum/standard_illuminants.h): each one's
// chromaticity through the CIE 1931 observer is the one CIE 15:2004 publishes for it (ACES D60:
// SMPTE ST 2065-1's white), illuminant A follows Planck's law at the CIE's own constants, the
// fluorescent lamps carry their mercury lines, and pbrt-v4's names find them.
#include "spectrum/standard_illuminants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "spectrum/color.h"
#include "spectrum/piecewise_linear.h"

namespace phos::spectrum {
namespace {

float value_at(const StandardIlluminant& s, float lambda) {
    const std::vector<float> l = s.wavelengths();
    return piecewise_linear(
        l.size(), [&](size_t i) { return l[i]; }, [&](size_t i) { return s.value[i]; }, lambda);
}

TEST(StandardIlluminants, ChromaticitiesAreThePublishedOnes) {
    // (x, y) of CIE 15:2004 tables T.3 and T.8 (computed there from the 5 nm tables; here the tables
    // are linear between their samples and integrated at 1 nm: 2e-3 covers the difference).
    const struct {
        const char* name;
        double x, y;
    } published[] = {{"A", 0.44757, 0.40745}, {"D50", 0.34567, 0.35850}, {"acesD60", 0.32168, 0.33767},
                     {"F1", 0.3131, 0.3371},  {"F2", 0.3721, 0.3751},    {"F3", 0.4091, 0.3941},
                     {"F4", 0.4402, 0.4031},  {"F5", 0.3138, 0.3452},    {"F6", 0.3779, 0.3882},
                     {"F7", 0.3129, 0.3292},  {"F8", 0.3458, 0.3586},    {"F9", 0.3741, 0.3727},
                     {"F10", 0.3458, 0.3588}, {"F11", 0.3805, 0.3769},   {"F12", 0.4370, 0.4042}};
    ASSERT_EQ(standard_illuminants().size(), std::size(published));
    for (const auto& p : published) {
        const auto s = standard_illuminant(p.name);
        ASSERT_TRUE(s.has_value()) << p.name;
        const Vec3 xyz = integrate_xyz([&](double l) { return double(value_at(*s, float(l))); });
        const double sum = double(xyz.x) + xyz.y + xyz.z, x = xyz.x / sum, y = xyz.y / sum;
        std::printf("[ measured ] %-8s x %.5f (%.5f), y %.5f (%.5f)\n", p.name, x, p.x, y, p.y);
        EXPECT_NEAR(x, p.x, 2e-3) << p.name;
        EXPECT_NEAR(y, p.y, 2e-3) << p.name;
    }
}

TEST(StandardIlluminants, AFollowsPlancksLawAtTheCieConstants) {
    // CIE A: 100 (560 / λ)^5 (e^(c2 / (560 T)) − 1) / (e^(c2 / (λ T)) − 1), c2 = 1.435e7 nm K,
    // T = 2848 K (the 2856 K of today's c2).
    const auto s = standard_illuminant("stdillum-A");
    ASSERT_TRUE(s.has_value());
    const double c2 = 1.435e7, T = 2848;
    for (int l = 300; l <= 830; l += 5) {
        const double planck =
            100 * std::pow(560.0 / l, 5) * std::expm1(c2 / (560 * T)) / std::expm1(c2 / (l * T));
        EXPECT_NEAR(value_at(*s, float(l)), planck, 1e-4 * planck) << l << " nm";
    }
    EXPECT_NEAR(value_at(*s, 560), 100.0f, 1e-3f);
}

TEST(StandardIlluminants, FluorescentLampsHaveTheirMercuryLines) {
    // The 435.8 nm and 546.1 nm mercury lines stand far above their neighbours in every F lamp.
    for (int i = 1; i <= 12; ++i) {
        const auto s = standard_illuminant("stdillum-F" + std::to_string(i));
        ASSERT_TRUE(s.has_value()) << i;
        EXPECT_EQ(s->lambda_first, 380.0f);
        EXPECT_EQ(s->value.size(), 81u);
        for (float line : {435.0f, 545.0f})
            EXPECT_GT(value_at(*s, line), 1.4f * value_at(*s, line - 10)) << "F" << i << " at " << line;
    }
}

TEST(StandardIlluminants, PbrtNamesFindThemAndD65IsNotAmongThem) {
    EXPECT_EQ(standard_illuminant("stdillum-F11")->name, "F11");
    EXPECT_EQ(standard_illuminant("illum-acesD60")->name, "acesD60");
    EXPECT_EQ(standard_illuminant("D50")->name, "D50");
    EXPECT_FALSE(standard_illuminant("stdillum-D65").has_value());
    EXPECT_FALSE(standard_illuminant("stdillum-F13").has_value());
}

}  // namespace
}  // namespace phos::spectrum
