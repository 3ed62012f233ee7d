// Tests of the delta lights: point (irradiance on a plane, legacy attenuation, emission), spot (cone,
// fall-off models, exact power, emission distribution) and directional (irradiance, emission disk).
// Intensities are spectral: the closed forms per unit intensity times what the light's RGB colour
// emits (read as an illuminant), at every wavelength sample.
#include <gtest/gtest.h>

#include "light_test_util.h"
#include "shading/directional_light.h"
#include "shading/point_light.h"
#include "shading/spot_light.h"

namespace phos::shading {
namespace {

using test::expect_mean;
using test::expect_means;
using test::RunningStat;
using test::SpectralStat;

const Wavelengths& kLambda = spectral::fixed_lambda();

// What a light of RGB colour c emits at kLambda.
Spectrum emitted(Rgb c) { return spectral::emitted(c, kLambda); }

scene::Light point_record(Vec3 p, Rgb I) {
    scene::Light l;
    l.kind = scene::Light::Kind::Point;
    l.position = p;
    l.color = I;
    return l;
}

TEST(PointLight, IrradianceOnPlaneIsExact) {
    const Vec3 pos{0.3f, 2.0f, -0.4f};
    const PointLight light(point_record(pos, Rgb(5, 2, 1)), {});
    const Vec3 n{0, 1, 0};
    const Spectrum I = emitted(Rgb(5, 2, 1));
    for (Vec3 x : {Vec3(0, 0, 0), Vec3(1.5f, 0, 2), Vec3(-3, 0, 0.5f), Vec3(0.3f, 0, -0.4f)}) {
        const LightLiSample s = light.sample_Li(x, {0.37f, 0.81f}, kLambda);
        ASSERT_TRUE(s.delta);
        ASSERT_EQ(s.pdf, 1.0f);
        const Vec3 d = pos - x;
        const double dist = std::sqrt(test::dot_d(d, d));
        const double cos_theta = d.y / dist;
        // E = I cos / d^2 at every wavelength (the colour's spectrum, not just its red).
        EXPECT_TRUE(spectral::spectra_near(s.L * dot(s.wi, n), I * float(cos_theta / (dist * dist)), 1e-5));
        EXPECT_NEAR(s.distance, dist, 1e-5 * dist);
        EXPECT_NEAR(length(s.wi), 1.0f, 1e-6f);
        EXPECT_EQ(s.p_light, pos);
    }
}

TEST(PointLight, LegacyAttenuationOnlyWhenAsked) {
    scene::Light rec = point_record({0, 3, 0}, Rgb(2.0f));
    rec.attenuation = {1, 0.5f, 0.25f};
    const PointLight physical(rec, {});
    const PointLight legacy(rec, {.legacy_attenuation = true});
    const Spectrum I = emitted(Rgb(2.0f));
    EXPECT_TRUE(spectral::spectra_near(physical.sample_Li({0, 0, 0}, {}, kLambda).L, I / 9.0f, 1e-6));
    EXPECT_TRUE(
        spectral::spectra_near(legacy.sample_Li({0, 0, 0}, {}, kLambda).L, I / (1 + 1.5f + 2.25f), 1e-6));
    EXPECT_NEAR(legacy.power().r, 4 * kPi * 2, 1e-4f);  // photons never see the attenuation
}

TEST(PointLight, EmissionIsUniformAndCarriesPower) {
    const PointLight light(point_record({1, 2, 3}, Rgb(1.5f)), {});
    EXPECT_NEAR(light.power().r, 4 * kPi * 1.5f, 1e-5f);
    Sampler rng(7);
    RunningStat wz, wx;
    SpectralStat weight;
    for (int i = 0; i < 20000; ++i) {
        const LightLeSample s = light.sample_Le(rng.next2(), rng.next2(), kLambda);
        EXPECT_EQ(s.ray.origin, Vec3(1, 2, 3));
        weight.add(s.weight);
        wz.add(s.ray.dir.z);
        wx.add(s.ray.dir.x);
    }
    expect_means(weight, emitted(Rgb(1.5f)) * float(4 * kPi), "point weight");
    expect_mean(wz, 0.0, "mean direction z");  // uniform sphere: zero mean, var 1/3
    expect_mean(wx, 0.0, "mean direction x");
}

scene::Light spot_record(float cutoff, float dropoff, float falloff_start = -1) {
    scene::Light l;
    l.kind = scene::Light::Kind::Spot;
    l.position = {0, 4, 0};
    l.direction = {0.3f, -1, 0.2f};
    l.color = Rgb(3, 2, 1);
    l.cutoff = cutoff;
    l.dropoff = dropoff;
    l.falloff_start = falloff_start;
    return l;
}

TEST(SpotLight, IntensityInsideAndOutsideTheCone) {
    const SpotLight spot(spot_record(0.5f, 3), {});
    const Vec3 axis = normalize(Vec3(0.3f, -1, 0.2f));
    const Frame f(axis);
    for (float angle : {0.0f, 0.2f, 0.45f, 0.49f, 0.51f, 1.0f, 2.5f}) {
        const Vec3 dir = f.to_world({std::sin(angle), 0, std::cos(angle)});
        const Vec3 x = Vec3(0, 4, 0) + dir * 2.0f;
        const LightLiSample s = spot.sample_Li(x, {}, kLambda);
        const float expected = angle <= 0.5f ? std::pow(std::cos(angle), 3.0f) / 4 : 0;  // per unit I
        EXPECT_TRUE(spectral::spectra_near(s.L, emitted(Rgb(3, 2, 1)) * expected, 1e-5, 1e-7)) << angle;
    }
}

// Integral of the fall-off over the sphere by the midpoint rule in cos(theta), fine enough that
// its error is far below the tolerance.
double numeric_power(const SpotLight& spot, double I) {
    const int n = 200000;
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += spot.falloff(float(-1 + 2 * (i + 0.5) / n));
    return 2 * kPi * I * sum * 2 / n;
}

TEST(SpotLight, PowerIsTheExactIntegral) {
    struct Case {
        float cutoff, dropoff, start;
        double closed;  // 2 pi I x closed form, I = 3 (red)
    };
    const double I = 3;
    const Case cases[] = {
        {0.5f, 0, -1, 2 * kPi * I * (1 - std::cos(0.5))},
        {0.5f, 3, -1, 2 * kPi * I * (1 - std::pow(std::cos(0.5), 4)) / 4},
        {1.2f, 10, -1, 2 * kPi * I * (1 - std::pow(std::cos(1.2), 11)) / 11},
        {2.0f, 0, -1, 2 * kPi * I * (1 - std::cos(2.0))},  // wider than a hemisphere
        {0.6f, 0, 0.4f, 2 * kPi * I * (1 - (std::cos(0.4) + std::cos(0.6)) / 2)},
    };
    for (const Case& c : cases) {
        const SpotLight spot(spot_record(c.cutoff, c.dropoff, c.start), {});
        EXPECT_NEAR(spot.power().r, c.closed, 1e-4 * c.closed) << c.cutoff << " " << c.dropoff;
        EXPECT_NEAR(numeric_power(spot, I), c.closed, 1e-4 * c.closed) << c.cutoff << " " << c.dropoff;
    }
}

TEST(SpotLight, EmissionStaysInTheConeAndFollowsTheFalloff) {
    struct Case {
        float cutoff, dropoff, start;
    };
    for (const Case c : {Case{0.5f, 0, -1}, Case{0.7f, 5, -1}, Case{2.0f, 0, -1}, Case{0.6f, 0, 0.3f}}) {
        const SpotLight spot(spot_record(c.cutoff, c.dropoff, c.start), {});
        const float cos_cut = std::cos(c.cutoff);
        // Histogram of cos(theta) over [cos_cut, 1] against the fall-off integral in each bin.
        const int bins = 16, n = 40000;
        std::vector<int> count(bins, 0);
        Sampler rng(11);
        SpectralStat weight;
        for (int i = 0; i < n; ++i) {
            const LightLeSample s = spot.sample_Le(rng.next2(), rng.next2(), kLambda);
            const float z = dot(s.ray.dir, spot.axis());
            ASSERT_GE(z, cos_cut - 1e-6f) << "direction left the cone";
            ASSERT_NEAR(length(s.ray.dir), 1.0f, 1e-5f);
            weight.add(s.weight);
            count[std::clamp(int((z - cos_cut) / (1 - cos_cut) * bins), 0, bins - 1)]++;
        }
        // The power per unit intensity (its green, I_g = 2, checked against the closed forms
        // above) times the emission spectrum.
        expect_means(weight, emitted(Rgb(3, 2, 1)) * (spot.power().g / 2), "spot weight");
        std::vector<double> expected(bins);
        double total = 0;
        for (int b = 0; b < bins; ++b) {
            const int m = 2000;
            for (int k = 0; k < m; ++k)
                expected[b] += spot.falloff(cos_cut + (1 - cos_cut) * float((b + (k + 0.5) / m) / bins));
            total += expected[b];
        }
        for (int b = 0; b < bins; ++b) {
            const double p = expected[b] / total;
            const double sigma = std::sqrt(n * p * (1 - p)) + 1;
            EXPECT_NEAR(count[b], n * p, 5 * sigma) << "bin " << b << " cutoff " << c.cutoff;
        }
    }
}

TEST(DirectionalLight, IrradianceAndEmissionDisk) {
    scene::Light rec;
    rec.kind = scene::Light::Kind::Directional;
    rec.direction = {1, -2, 0.5f};
    rec.color = Rgb(4, 2, 1);
    const SceneSphere sphere{{1, 0, -1}, 3};
    const DirectionalLight light(rec, sphere);
    const Vec3 d = normalize(rec.direction);
    const Spectrum E = emitted(rec.color);
    const LightLiSample s = light.sample_Li({0.5f, 0, 0}, {}, kLambda);
    EXPECT_TRUE(s.delta);
    EXPECT_NEAR(dot(s.wi, -d), 1.0f, 1e-6f);
    // Irradiance on a horizontal plane: E cos(theta).
    EXPECT_TRUE(spectral::spectra_near(s.L * dot(s.wi, Vec3(0, 1, 0)), E * (2 / std::sqrt(5.25f)), 1e-5));
    EXPECT_NEAR(light.power().r, 4 * kPi * 9, 1e-3f);
    Sampler rng(3);
    SpectralStat weight;
    for (int i = 0; i < 20000; ++i) {
        const LightLeSample e = light.sample_Le(rng.next2(), rng.next2(), kLambda);
        ASSERT_NEAR(dot(e.ray.dir, d), 1.0f, 1e-6f);
        const Vec3 rel = e.ray.origin - sphere.center;
        // On the disk tangent to the bounding sphere, upstream.
        ASSERT_NEAR(dot(rel, d), -3.0f, 1e-4f);
        ASSERT_LE(length(rel - d * dot(rel, d)), 3.0f + 1e-4f);
        weight.add(e.weight);
    }
    // pi R^2 E: the disk photons start from.
    expect_means(weight, E * float(kPi * 9), "directional weight");
}

}  // namespace
}  // namespace phos::shading
