// Area lights on partial spheres (pbrt's zmin, zmax, phimax): the area is Archimedes' phimax r
// (zmax - zmin), samples cover exactly the part and uniformly (chi-square over equal-area cells),
// pdfs agree with sampling, direct light matches a brute-force quadrature over the part, and photons
// leave from the part only.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "shading/area_light.h"
#include "shading/shape_sampler.h"
#include "spectral_test_util.h"
#include "support/chi_square.h"

namespace phos::shading {
namespace {

constexpr float kR = 1.0f, kZmin = -0.4f, kZmax = 0.9f, kPhimax = 4.5f, kScale = 2.0f;

scene::Shape partial(const Transform& to_world) {
    scene::Shape s;
    s.kind = scene::Shape::Kind::Sphere;
    s.radius = kR;
    s.axis = {0, 0, 1};
    s.partial = true;
    s.z_min = kZmin, s.z_max = kZmax, s.phi_max = kPhimax;
    s.to_world = to_world;
    return s;
}

// A similarity: rotation, uniform scale 2 and a translation.
Transform similarity() {
    return Transform::translate({1, -2, 0.5f}) * Transform::rotate(35, normalize(Vec3(1, 2, 3))) *
           Transform::scale(Vec3(kScale));
}

// Object-space z and phi of a world point, and its distance from the centre.
void object_coords(const Transform& t, Vec3 p, float& z, float& phi, float& r) {
    const Vec3 q = t.inverse().point(p);
    z = q.z;
    phi = std::atan2(q.y, q.x);
    if (phi < 0) phi += 2 * kPi;
    r = length(q);
}

TEST(PartialSphereLight, AreaSamplesCoverThePartUniformly) {
    const Transform t = similarity();
    const ShapeSampler sampler(partial(t));
    EXPECT_FALSE(sampler.tessellated());
    EXPECT_NEAR(sampler.area(), kPhimax * kR * (kZmax - kZmin) * kScale * kScale, 1e-4);
    constexpr int kZBins = 8, kPhiBins = 8, kN = 64000;
    std::vector<double> counts(kZBins * kPhiBins, 0),
        expected(kZBins * kPhiBins, double(kN) / (kZBins * kPhiBins));
    Sampler rng(17);
    for (int i = 0; i < kN; ++i) {
        const ShapeSample s = sampler.sample_area(rng.next2());
        float z, phi, r;
        object_coords(t, s.p, z, phi, r);
        ASSERT_NEAR(r, kR, 1e-5f);
        ASSERT_GE(z, kZmin - 1e-5f);
        ASSERT_LE(z, kZmax + 1e-5f);
        ASSERT_LE(phi, kPhimax + 1e-5f);
        // Outward normal.
        ASSERT_GT(dot(s.n, normalize(s.p - t.point(Vec3(0.0f)))), 0.9999f);
        EXPECT_FLOAT_EQ(s.pdf, 1 / sampler.area());
        // Equal-area cells (Archimedes): equal steps in z and in phi.
        const int zi = std::min(kZBins - 1, int((z - kZmin) / (kZmax - kZmin) * kZBins));
        const int pi = std::min(kPhiBins - 1, int(phi / kPhimax * kPhiBins));
        counts[size_t(zi * kPhiBins + pi)] += 1;
    }
    const test::ChiSquareResult c = test::chi_square(counts, expected);
    EXPECT_TRUE(c.passed) << c.detail;
}

TEST(PartialSphereLight, DirectLightMatchesQuadratureAndPdfsAgree) {
    const Transform t = similarity();
    const ShapeSampler sampler(partial(t));
    const Vec3 c = t.point(Vec3(0.0f));
    // Reference points outside, some seeing the outside of the part and some its inside through the
    // cut; irradiance from a one-sided unit emitter (no occlusion, as sample() itself).
    for (const Vec3 ref : {c + Vec3(5, 1, 0), c + Vec3(-1, -4, 3), c + Vec3(0.5f, 0.2f, -6)}) {
        // Quadrature over (z, phi): dA = r dz dphi (x scale^2), midpoints.
        constexpr int kN = 600;
        double quad = 0;
        for (int i = 0; i < kN; ++i)
            for (int j = 0; j < kN; ++j) {
                const float z = kZmin + (kZmax - kZmin) * (float(i) + 0.5f) / kN;
                const float phi = kPhimax * (float(j) + 0.5f) / kN;
                const float rho = std::sqrt(kR * kR - z * z);
                const Vec3 q(rho * std::cos(phi), rho * std::sin(phi), z);
                const Vec3 p = t.point(q), n = normalize(t.normal(q));
                const Vec3 d = p - ref;
                const float d2 = length_squared(d);
                const float cos_l = -dot(n, d) / std::sqrt(d2);
                const float cos_r = 1;  // irradiance on a sphere of directions: just solid angle
                if (cos_l > 0) quad += double(cos_l * cos_r / d2);
            }
        quad *= double(kR * (kZmax - kZmin) * kPhimax * kScale * kScale) / (double(kN) * kN);
        Sampler rng(23);
        double est = 0;
        constexpr int kSamples = 200000;
        for (int i = 0; i < kSamples; ++i) {
            const ShapeSample s = sampler.sample(ref, rng.next2());
            if (!(s.pdf > 0)) continue;
            const Vec3 wi = normalize(s.p - ref);
            // The same density (float rounding of 1 / cos grows at grazing angles).
            const float cos_l = std::fabs(dot(s.n, wi));
            EXPECT_NEAR(sampler.pdf(ref, wi, s.p, s.n), s.pdf, 1e-5f / cos_l * s.pdf);
            if (dot(s.n, -wi) > 0) est += 1.0 / s.pdf;
        }
        est /= kSamples;
        EXPECT_NEAR(est, quad, 0.01 * quad) << ref.x << " " << ref.y << " " << ref.z;
    }
}

TEST(PartialSphereLight, PhotonsLeaveFromThePartAndPowerUsesItsArea) {
    const Transform t = similarity();
    scene::Scene sc;
    sc.materials.emplace_back();
    sc.add_area_light(partial(t), Rgb(1.0f));
    const AreaLight light(sc.lights[0], sc.shapes[0]);
    const float area = kPhimax * kR * (kZmax - kZmin) * kScale * kScale;
    EXPECT_NEAR(light.power().r, kPi * area, 1e-3f * kPi * area);
    Sampler rng(29);
    for (int i = 0; i < 2000; ++i) {
        const LightLeSample s = light.sample_Le(rng.next2(), rng.next2(), spectral::fixed_lambda());
        float z, phi, r;
        object_coords(t, s.ray.origin, z, phi, r);
        ASSERT_NEAR(r, kR, 1e-5f);
        ASSERT_TRUE(z >= kZmin - 1e-5f && z <= kZmax + 1e-5f && phi <= kPhimax + 1e-5f);
        ASSERT_GT(dot(s.ray.dir, s.n), 0.0f);
    }
}

TEST(PartialSphereLight, NonUniformScaleStaysOnThePart) {
    const Transform t = Transform::scale({1, 2, 0.5f});
    const ShapeSampler sampler(partial(t));
    EXPECT_TRUE(sampler.tessellated());
    Sampler rng(31);
    for (int i = 0; i < 5000; ++i) {
        const ShapeSample s = sampler.sample_area(rng.next2());
        float z, phi, r;
        object_coords(t, s.p, z, phi, r);
        ASSERT_NEAR(r, kR, 1e-4f);
        ASSERT_TRUE(z >= kZmin - 1e-4f && z <= kZmax + 1e-4f && phi <= kPhimax + 1e-4f) << z << " " << phi;
    }
}

}  // namespace
}  // namespace phos::shading
