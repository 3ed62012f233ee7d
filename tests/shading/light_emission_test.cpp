// Photon emission (sample_Le) of area lights: the mean weight equals pi L A (x2 when two-sided) at
// every wavelength (L the light's RGB read as an illuminant), and its colour through the film is
// power() = pi L A in RGB, for every shape kind; power() matches the closed-form area, directions
// leave from the emitting side, cosine-distributed.
#include <gtest/gtest.h>

#include "core/transform.h"
#include "light_test_util.h"
#include "shading/area_light.h"

namespace phos::shading {
namespace {

using test::expect_mean;
using test::expect_means;
using test::RunningStat;
using test::SpectralStat;

struct Case {
    const char* name;
    scene::Shape shape;
    double area;  // closed form
    bool two_sided = false;
};

std::vector<Case> cases() {
    std::vector<Case> out;
    out.push_back({"rectangle", test::rectangle_y(-1, 1, 0, 0.5f, 2), 1.0});
    scene::Shape stretched = test::rectangle_y(0, 1, 0, 1, 0);
    stretched.to_world = Transform::rotate(50, {1, 0, 1}) * Transform::scale({3, 1, 0.25f});
    out.push_back({"scaled mesh", stretched, 0.75});
    out.push_back({"two-sided disk", test::disk({0, 1, 0}, {1, 1, 0}, 0.5f), kPi * 0.25, true});
    out.push_back({"annulus", test::disk({0, 1, 0}, {0, 0, 1}, 0.5f, 0.25f), kPi * (0.25 - 0.0625)});
    out.push_back({"sphere", test::sphere({0, 0, 0}, 0.3f), 4 * kPi * 0.09});
    scene::Shape box;
    box.kind = scene::Shape::Kind::Box;
    box.box_min = {0, 0, 0};
    box.box_max = {1, 0.5f, 2};
    out.push_back({"box", box, 2 * (0.5 + 2 + 1)});
    scene::Shape cyl;
    cyl.kind = scene::Shape::Kind::Cylinder;
    cyl.radius = 0.5f;
    cyl.height = 1;
    cyl.to_world = Transform::translate({1, 2, 3}) * Transform::scale(Vec3(2.0f));
    out.push_back({"cylinder", cyl, 2 * kPi * 1 * 2 + 2 * kPi * 1});
    scene::Shape cone = cyl;
    cone.kind = scene::Shape::Kind::Cone;
    out.push_back({"cone", cone, kPi * 1 * std::sqrt(5.0) + kPi});
    return out;
}

TEST(AreaLightEmission, MeanWeightIsPowerAndPowerIsPiLA) {
    const Rgb L(2, 1, 0.5f);
    const Wavelengths& lambda = spectral::fixed_lambda();
    const Spectrum Le = spectral::emitted(L, lambda);  // what the light emits at `lambda`
    int seed = 0;
    for (const Case& c : cases()) {
        const AreaLight light(test::area_light_record(L, c.two_sided), c.shape);
        const double sides = c.two_sided ? 2 : 1;
        EXPECT_NEAR(light.power().r, kPi * 2 * c.area * sides, 1e-4 * kPi * 2 * c.area * sides) << c.name;
        Sampler rng(uint64_t(++seed));
        RunningStat cos_mean;
        SpectralStat weight;
        // The weight's colour through the film, each sample at its own stratified wavelengths.
        RunningStat colour[3];
        int back = 0;
        const int N = 20000;
        for (int i = 0; i < N; ++i) {
            const Vec2 u_pos = rng.next2(), u_dir = rng.next2();
            const LightLeSample s = light.sample_Le(u_pos, u_dir, lambda);
            ASSERT_NEAR(length(s.ray.dir), 1.0f, 1e-5f);
            weight.add(s.weight);
            const Wavelengths li = spectral::stratified_lambda(i, N);
            const Rgb rgb = spectrum::to_srgb(light.sample_Le(u_pos, u_dir, li).weight, li);
            for (int k = 0; k < 3; ++k) colour[k].add(rgb[k]);
            // s.n is the side the photon leaves from; for one-sided lights it is the emitting normal,
            // which must agree with sample_Li's normal at that point (Le non-zero leaving along n).
            const float c_out = dot(s.ray.dir, s.n);
            ASSERT_GE(c_out, -1e-6f) << c.name;
            cos_mean.add(c_out);
            if (!c.two_sided) {
                EXPECT_EQ(light.Le(s.n, s.ray.dir, lambda), Le);
            } else if (dot(s.n, normalize(c.shape.normal)) < 0) {
                ++back;
            }
            EXPECT_NEAR(s.pdf_pos, 1 / light.sampler().area(), 1e-6f);
        }
        expect_means(weight, Le * float(kPi * c.area * sides), c.name);
        // The film sees power() (the exact fit's RGB is within 1e-5 of L; 2e-3 relative covers
        // the CIE tables' interpolation against the fit's 1 nm sums).
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(colour[k].mean(), light.power()[k],
                        test::kSigmas * colour[k].std_error() + 2e-3 * light.power()[k])
                << c.name << " channel " << k;
        }
        // Cosine-weighted hemisphere: E[cos] = 2/3.
        expect_mean(cos_mean, 2.0 / 3.0, c.name);
        if (c.two_sided) {
            EXPECT_NEAR(back, N / 2, 5 * std::sqrt(N / 4.0)) << "both sides emit";
        }
    }
}

}  // namespace
}  // namespace phos::shading
