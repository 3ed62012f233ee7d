// Tests of the Fresnel functions (shading/fresnel.h) against closed-form values: normal incidence,
// Brewster's angle, total internal reflection, reciprocity, Schlick's error, conductors.
#include "shading/fresnel.h"

#include <gtest/gtest.h>

namespace phos::shading {
namespace {

TEST(Fresnel, NormalIncidence) {
    for (float n : {1.33f, 1.5f, 2.4f}) {
        const float r0 = ((n - 1) / (n + 1)) * ((n - 1) / (n + 1));
        EXPECT_NEAR(fresnel_dielectric(1.0f, n), r0, 1e-6f);
        EXPECT_NEAR(fresnel_dielectric(1.0f, 1 / n), r0, 1e-6f);  // same from inside
        EXPECT_NEAR(fresnel_schlick(1.0f, n), r0, 1e-6f);
    }
    EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04f, 1e-6f);
    EXPECT_EQ(fresnel_dielectric(0.7f, 1.0f), 0.0f);  // no interface, no reflection
}

TEST(Fresnel, BrewsterAngle) {
    // At tan(theta) = n the p-polarised reflectance vanishes; the unpolarised value is s / 2.
    // For n = 1.5: theta_t = 90 deg - theta_B, R_s = sin^2(theta_B - theta_t) = 0.147929.
    const float n = 1.5f, theta_b = std::atan(n);
    const auto r = fresnel_dielectric_polarised(std::cos(theta_b), n);
    EXPECT_NEAR(r.p, 0.0f, 1e-6f);
    const float theta_t = 0.5f * kPi - theta_b;
    const float rs = std::sin(theta_b - theta_t) * std::sin(theta_b - theta_t);
    EXPECT_NEAR(r.s, rs, 1e-5f);
    EXPECT_NEAR(r.s, 0.147929f, 1e-5f);
    EXPECT_NEAR(fresnel_dielectric(std::cos(theta_b), n), 0.5f * rs, 1e-5f);
    // Away from it p is positive.
    EXPECT_GT(fresnel_dielectric_polarised(std::cos(theta_b + 0.2f), n).p, 1e-3f);
}

TEST(Fresnel, TotalInternalReflectionAndGrazing) {
    const float n = 1.5f, sin_c = 1 / n;  // critical angle from inside
    const float cos_c = std::sqrt(1 - sin_c * sin_c);
    EXPECT_EQ(fresnel_dielectric(cos_c * 0.99f, 1 / n), 1.0f);
    EXPECT_LT(fresnel_dielectric(cos_c * 1.01f, 1 / n), 1.0f);
    EXPECT_EQ(fresnel_schlick(cos_c * 0.99f, 1 / n), 1.0f);
    EXPECT_NEAR(fresnel_dielectric(0.0f, n), 1.0f, 1e-6f);
    // Reflectance grows monotonically towards grazing incidence from outside.
    float prev = 0;
    for (int i = 0; i <= 100; ++i) {
        const float r = fresnel_dielectric(1 - i / 100.0f, n);
        EXPECT_GE(r, prev - 1e-7f);
        prev = r;
    }
}

TEST(Fresnel, NegativeCosineMeansOtherSide) {
    for (float c : {0.1f, 0.5f, 0.9f}) {
        EXPECT_FLOAT_EQ(fresnel_dielectric(-c, 1.5f), fresnel_dielectric(c, 1 / 1.5f));
        EXPECT_FLOAT_EQ(fresnel_schlick(-c, 1.5f), fresnel_schlick(c, 1 / 1.5f));
    }
}

TEST(Fresnel, Reciprocity) {
    // The reflectance of a ray and of its refracted reverse are equal (Stokes relations).
    const float n = 1.5f;
    for (int i = 1; i < 20; ++i) {
        const float cos_i = i / 20.0f;
        const float sin_t = std::sqrt(1 - cos_i * cos_i) / n, cos_t = std::sqrt(1 - sin_t * sin_t);
        EXPECT_NEAR(fresnel_dielectric(cos_i, n), fresnel_dielectric(cos_t, 1 / n), 1e-5f);
    }
}

TEST(Fresnel, SchlickCloseToExact) {
    // Schlick's maximum absolute error is 0.036 for n = 1.5 and 0.060 for n = 1.33 (near grazing
    // from outside, near the critical angle from inside); its mean error is far smaller.
    for (float n : {1.33f, 1.5f}) {
        float max_err_out = 0, max_err_in = 0;
        double mean_err = 0;
        for (int i = 0; i <= 1000; ++i) {
            const float c = i / 1000.0f;
            const float eo = std::fabs(fresnel_schlick(c, n) - fresnel_dielectric(c, n));
            const float ei = std::fabs(fresnel_schlick(c, 1 / n) - fresnel_dielectric(c, 1 / n));
            max_err_out = std::max(max_err_out, eo);
            max_err_in = std::max(max_err_in, ei);
            mean_err += eo / 1001;
        }
        EXPECT_LT(max_err_out, 0.065f) << n;
        EXPECT_LT(max_err_in, 0.065f) << n;
        EXPECT_LT(mean_err, 0.02) << n;
        EXPECT_GT(max_err_out, 0.0f);  // it is an approximation after all
    }
}

TEST(Fresnel, ConductorReducesToDielectric) {
    for (float n : {1.2f, 1.5f, 2.0f, 1 / 1.5f})
        for (int i = 0; i <= 20; ++i) {
            const float c = i / 20.0f;
            EXPECT_NEAR(fresnel_conductor(c, n, 0.0f), fresnel_dielectric(c, n), 2e-5f) << n << " " << c;
        }
}

TEST(Fresnel, ConductorValues) {
    // Normal incidence: ((n-1)^2 + k^2) / ((n+1)^2 + k^2). Gold-like n = 0.2, k = 3.
    const float n = 0.2f, k = 3.0f;
    EXPECT_NEAR(fresnel_conductor(1.0f, n, k), ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k),
                1e-5f);
    EXPECT_NEAR(fresnel_conductor(0.0f, n, k), 1.0f, 1e-5f);
    for (int i = 0; i <= 20; ++i) {
        const float r = fresnel_conductor(i / 20.0f, n, k);
        EXPECT_GE(r, 0.0f);
        EXPECT_LE(r, 1.0f + 1e-6f);
    }
    // Absorption raises reflectance over the dielectric with the same n.
    EXPECT_GT(fresnel_conductor(0.8f, 1.5f, 1.0f), fresnel_dielectric(0.8f, 1.5f));
    const Rgb rgb = fresnel_conductor(0.5f, Rgb(0.2f, 0.9f, 1.5f), Rgb(3.0f, 2.5f, 0.0f));
    EXPECT_FLOAT_EQ(rgb.g, fresnel_conductor(0.5f, 0.9f, 2.5f));
    EXPECT_NEAR(rgb.b, fresnel_dielectric(0.5f, 1.5f), 2e-5f);
}

TEST(Fresnel, ThinSheet) {
    // R + T^2 R / (1 - R^2) simplifies to 2R / (1 + R).
    for (float r : {0.0f, 0.04f, 0.3f, 0.9f}) EXPECT_NEAR(thin_sheet_reflectance(r), 2 * r / (1 + r), 1e-6f);
    EXPECT_EQ(thin_sheet_reflectance(1.0f), 1.0f);
}

}  // namespace
}  // namespace phos::shading
