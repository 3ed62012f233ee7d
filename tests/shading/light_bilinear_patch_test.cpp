// Area lights on exact bilinear patches: the area by quadrature, samples uniform by area (chi-square
// against the areas of sub-patches), pdfs consistent with sampling, direct light against a
// brute-force quadrature, and the patch's front as the accelerator's.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "scene/bilinear_patch.h"
#include "shading/shape_sampler.h"
#include "support/chi_square.h"

namespace phos::shading {
namespace {

constexpr float kH = 1.5f;

// p(u, v) = (u, v, h u v) over the unit square: (u, v) is read back from (x, y).
scene::Shape saddle() {
    scene::Shape s;
    s.kind = scene::Shape::Kind::Mesh;
    s.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, kH}};
    s.mesh.patches = {0, 1, 2, 3};
    return s;
}

Vec3 at(float u, float v) { return {u, v, kH * u * v}; }

TEST(BilinearPatchLight, AreaIsTheQuadratureAndSamplesAreUniformByArea) {
    const ShapeSampler sampler(saddle());
    // A fine midpoint sum of |dp/du x dp/dv| = sqrt(1 + h^2 (u^2 + v^2)).
    double fine = 0;
    constexpr int kN = 1000;
    for (int i = 0; i < kN; ++i)
        for (int j = 0; j < kN; ++j) {
            const double u = (i + 0.5) / kN, v = (j + 0.5) / kN;
            fine += std::sqrt(1 + double(kH) * kH * (u * u + v * v));
        }
    fine /= double(kN) * kN;
    EXPECT_NEAR(sampler.area(), fine, 1e-5 * fine);
    EXPECT_NEAR(scene::patch_area({at(0, 0), at(1, 0), at(0, 1), at(1, 1)}), fine, 1e-6 * fine);

    constexpr int kCells = 8, kSamples = 80000;
    std::vector<double> counts(kCells * kCells, 0), expected(kCells * kCells, 0);
    for (int i = 0; i < kCells; ++i)
        for (int j = 0; j < kCells; ++j) {
            const float u0 = float(i) / kCells, u1 = float(i + 1) / kCells, v0 = float(j) / kCells,
                        v1 = float(j + 1) / kCells;
            // A bilinear patch restricted to a rectangle of (u, v) is the bilinear patch of its corners.
            expected[size_t(i * kCells + j)] =
                kSamples * scene::patch_area({at(u0, v0), at(u1, v0), at(u0, v1), at(u1, v1)}) /
                sampler.area();
        }
    Sampler rng(41);
    for (int k = 0; k < kSamples; ++k) {
        const ShapeSample s = sampler.sample_area(rng.next2());
        ASSERT_NEAR(s.p.z, kH * s.p.x * s.p.y, 1e-5f);
        ASSERT_TRUE(s.p.x >= 0 && s.p.x <= 1 && s.p.y >= 0 && s.p.y <= 1);
        // The front: dp/du x dp/dv = (-h v, -h u, 1).
        ASSERT_GT(dot(s.n, normalize(Vec3(-kH * s.p.y, -kH * s.p.x, 1))), 0.99999f);
        EXPECT_FLOAT_EQ(s.pdf, 1 / sampler.area());
        const int i = std::min(kCells - 1, int(s.p.x * kCells)),
                  j = std::min(kCells - 1, int(s.p.y * kCells));
        counts[size_t(i * kCells + j)] += 1;
    }
    const test::ChiSquareResult c = test::chi_square(counts, expected);
    EXPECT_TRUE(c.passed) << c.detail;
}

TEST(BilinearPatchLight, DirectLightMatchesQuadratureAndPdfsAgree) {
    const ShapeSampler sampler(saddle());
    for (const Vec3 ref : {Vec3(0.3f, 0.4f, 2), Vec3(2, -1, 1), Vec3(0.5f, 0.5f, -1)}) {
        // Irradiance-like integral of a one-sided emitter: sum of cos_l / d^2 dA over the front.
        double quad = 0;
        constexpr int kN = 500;
        for (int i = 0; i < kN; ++i)
            for (int j = 0; j < kN; ++j) {
                const float u = (float(i) + 0.5f) / kN, v = (float(j) + 0.5f) / kN;
                const Vec3 p = at(u, v), nn = Vec3(-kH * v, -kH * u, 1);
                const Vec3 d = p - ref;
                const float cos_l = -dot(normalize(nn), d) / length(d);
                if (cos_l > 0) quad += double(cos_l / length_squared(d) * length(nn));
            }
        quad /= double(kN) * kN;
        Sampler rng(43);
        double est = 0;
        constexpr int kSamples = 200000;
        for (int k = 0; k < kSamples; ++k) {
            const ShapeSample s = sampler.sample(ref, rng.next2());
            if (!(s.pdf > 0)) continue;
            const Vec3 wi = normalize(s.p - ref);
            // The same density (float rounding of 1 / cos grows at grazing angles).
            const float cos_l = std::fabs(dot(s.n, wi));
            EXPECT_NEAR(sampler.pdf(ref, wi, s.p, s.n), s.pdf, 1e-5f / cos_l * s.pdf);
            if (dot(s.n, -wi) > 0) est += 1.0 / s.pdf;
        }
        est /= kSamples;
        EXPECT_NEAR(est, quad, 0.01 * quad + 1e-4) << ref.x << " " << ref.y << " " << ref.z;
    }
}

TEST(BilinearPatchLight, FlippedPatchesAndShadingNormalsOrientTheFront) {
    scene::Shape s = saddle();
    s.mesh.patches_flipped = true;
    Sampler rng(47);
    const ShapeSampler flipped(s);
    for (int k = 0; k < 100; ++k) EXPECT_LT(flipped.sample_area(rng.next2()).n.z, 0);
    // With per-vertex normals the front is their side, whatever the flag says.
    s.mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    const ShapeSampler with_normals(s);
    for (int k = 0; k < 100; ++k) EXPECT_GT(with_normals.sample_area(rng.next2()).n.z, 0);
}

}  // namespace
}  // namespace phos::shading
