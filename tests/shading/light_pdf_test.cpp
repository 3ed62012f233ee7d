// Consistency of sample_Li and pdf_Li for area lights: pdf_Li of each returned sample equals its
// pdf, and E[1/pdf] equals the solid angle the sampled surface covers (counted once per surface
// layer: 4 pi from inside a closed shape). Also the geometry and areas of every shape kind,
// including the tessellated fall-back under non-uniform scales.
#include <gtest/gtest.h>

#include "core/transform.h"
#include "light_test_util.h"
#include "shading/area_light.h"

namespace phos::shading {
namespace {

using test::expect_mean;
using test::RunningStat;

// Samples from `ref`, checks pdf_Li against every sample and returns the stats of 1/pdf.
RunningStat inverse_pdf(const Light& light, Vec3 ref, int N, uint64_t seed) {
    Sampler rng(seed);
    RunningStat s;
    for (int i = 0; i < N; ++i) {
        const LightLiSample ls = light.sample_Li(ref, rng.next2(), spectral::fixed_lambda());
        if (ls.pdf > 0) {
            const float again = light.pdf_Li(ref, ls.wi, ls.p_light, ls.n_light);
            EXPECT_NEAR(again, ls.pdf, 1e-4f * ls.pdf);
            EXPECT_NEAR(length(ls.p_light - ref), ls.distance, 1e-4f * ls.distance);
        }
        s.add(ls.pdf > 0 ? 1.0 / ls.pdf : 0.0);
    }
    return s;
}

// Solid angle of triangle (a, b, c) seen from x (Van Oosterom & Strackee).
double triangle_solid_angle(Vec3 x, Vec3 a, Vec3 b, Vec3 c) {
    const Vec3 ra = a - x, rb = b - x, rc = c - x;
    const double la = length(ra), lb = length(rb), lc = length(rc);
    const double num = std::fabs(test::dot_d(ra, cross(rb, rc)));
    const double den =
        la * lb * lc + test::dot_d(ra, rb) * lc + test::dot_d(ra, rc) * lb + test::dot_d(rb, rc) * la;
    return 2 * std::atan2(num, den);
}

scene::Light rec() { return test::area_light_record(Rgb(1.0f)); }

TEST(AreaLightPdf, RectangleDiskAndSphereSolidAngles) {
    const scene::Shape rect = test::rectangle_y(-0.5f, 0.5f, -0.25f, 0.75f, 1.5f);
    const AreaLight r(rec(), rect);
    const auto& v = rect.mesh.positions;
    for (Vec3 x : {Vec3(0, 0, 0), Vec3(1, 0.5f, -1)}) {
        const double omega =
            triangle_solid_angle(x, v[0], v[1], v[2]) + triangle_solid_angle(x, v[0], v[2], v[3]);
        expect_mean(inverse_pdf(r, x, 30000, 1), omega, "rectangle solid angle");
    }
    const float rad = 0.8f, h = 1.7f;
    const AreaLight d(rec(), test::disk({0, h, 0}, {0, -1, 0}, rad));
    expect_mean(inverse_pdf(d, {0, 0, 0}, 30000, 2), 2 * kPi * (1 - h / std::sqrt(h * h + rad * rad)),
                "disk");

    const AreaLight s(rec(), test::sphere({1, 2, 3}, 0.7f));
    for (float dist : {0.75f, 1.5f, 6.0f}) {
        const Vec3 ref = Vec3(1, 2, 3) + normalize(Vec3(1, -2, 0.5f)) * dist;
        const double cos_max = std::sqrt(1 - 0.49 / (dist * dist));
        const RunningStat st = inverse_pdf(s, ref, 20000, 3);
        expect_mean(st, 2 * kPi * (1 - cos_max), "sphere cone");
        EXPECT_LT(st.std_error(), 1e-6);  // cone sampling: 1/pdf is the constant solid angle
    }
    // A tiny, far sphere goes through the small-angle branch.
    const AreaLight tiny(rec(), test::sphere({0, 0, 0}, 0.01f));
    const RunningStat st = inverse_pdf(tiny, {0, 10, 0}, 1000, 4);
    EXPECT_NEAR(st.mean(), kPi * 1e-6, 1e-3 * kPi * 1e-6);
}

TEST(AreaLightPdf, SampledConePointsLieOnTheVisibleCap) {
    const Vec3 c{1, 2, 3};
    const AreaLight s(rec(), test::sphere(c, 0.7f));
    const Vec3 ref{3, 2.5f, 2};
    Sampler rng(8);
    const Wavelengths& lambda = spectral::fixed_lambda();
    const Spectrum white = spectral::emitted(Rgb(1.0f), lambda);  // RGB white read as an illuminant
    for (int i = 0; i < 2000; ++i) {
        const LightLiSample ls = s.sample_Li(ref, rng.next2(), lambda);
        ASSERT_NEAR(length(ls.p_light - c), 0.7f, 1e-4f);
        EXPECT_LE(dot(ls.n_light, ls.wi), 1e-3f);  // faces the reference point
        EXPECT_EQ(ls.L, white);
    }
}

// From inside a closed shape every direction meets the surface once: E[1/pdf] = 4 pi.
TEST(AreaLightPdf, ClosedShapesFromInside) {
    std::vector<scene::Shape> shapes;
    shapes.push_back(test::sphere({0, 0, 0}, 1));
    scene::Shape box;
    box.kind = scene::Shape::Kind::Box;
    box.box_min = {-1, -0.5f, -2};
    box.box_max = {1.5f, 0.5f, 0.3f};
    shapes.push_back(box);
    scene::Shape cyl;
    cyl.kind = scene::Shape::Kind::Cylinder;
    cyl.radius = 0.6f;
    cyl.height = 1.4f;
    cyl.axis = normalize(Vec3(1, 1, 0));
    shapes.push_back(cyl);
    scene::Shape cone = cyl;
    cone.kind = scene::Shape::Kind::Cone;
    shapes.push_back(cone);
    // Non-uniform scales: an ellipsoid, a squashed cylinder and cone (tessellated fall-back), and a
    // sheared box (exact).
    for (scene::Shape s : {shapes[0], shapes[2], shapes[3]}) {
        s.to_world = Transform::rotate(25, {0, 0, 1}) * Transform::scale({1.6f, 0.7f, 1.1f});
        shapes.push_back(s);
    }
    scene::Shape sheared = box;
    Mat4 m, inv;  // x += 0.4 y, and its inverse
    m(0, 1) = 0.4f;
    inv(0, 1) = -0.4f;
    sheared.to_world = Transform(m, inv);
    shapes.push_back(sheared);

    int k = 0;
    for (const scene::Shape& s : shapes) {
        const AreaLight light(rec(), s);
        // A point well inside: the object-space centre (offset towards the base for cones).
        Vec3 inside = s.kind == scene::Shape::Kind::Box ? (s.box_min + s.box_max) * 0.5f : s.center;
        if (s.kind == scene::Shape::Kind::Cone) inside = inside - s.axis * (0.25f * s.height);
        const Vec3 ref = s.to_world.point(inside);
        const RunningStat st = inverse_pdf(light, ref, 40000, 10 + uint64_t(k));
        // Tessellated parts: their density is right to ~0.1% (see shape_sampler.h).
        const double slack = (light.sampler().tessellated() ? 3e-3 : 1e-5) * 4 * kPi;
        EXPECT_NEAR(st.mean(), 4 * kPi, test::kSigmas * st.std_error() + slack) << "shape " << k;
        ++k;
    }
}

TEST(ShapeSampler, AreasOfEveryKind) {
    scene::Shape cyl;
    cyl.kind = scene::Shape::Kind::Cylinder;
    cyl.radius = 0.5f;
    cyl.height = 2;
    const float r = 0.5f, h = 2;
    EXPECT_NEAR(ShapeSampler(cyl).area(), 2 * kPi * r * h + 2 * kPi * r * r, 1e-4f);
    cyl.capped = false;
    EXPECT_NEAR(ShapeSampler(cyl).area(), 2 * kPi * r * h, 1e-4f);
    scene::Shape cone = cyl;
    cone.kind = scene::Shape::Kind::Cone;
    cone.capped = true;
    EXPECT_NEAR(ShapeSampler(cone).area(), kPi * r * std::sqrt(r * r + h * h) + kPi * r * r, 1e-4f);
    scene::Shape box;
    box.kind = scene::Shape::Kind::Box;
    box.box_min = {0, 0, 0};
    box.box_max = {1, 2, 3};
    box.to_world = Transform::scale({2, 1, 1});
    EXPECT_NEAR(ShapeSampler(box).area(), 2 * (2 * 2 + 2 * 3 + 2 * 3), 1e-4f);
    // Cylinder stretched along its own axis stays circular: the tessellation's area is within
    // (2 pi / 256)^2 / 6 of the true one.
    cyl.to_world = Transform::scale({1, 2, 1});
    const ShapeSampler stretched(cyl);
    EXPECT_TRUE(stretched.tessellated());
    EXPECT_NEAR(stretched.area(), 2 * kPi * r * 2 * h, 3e-4f * 2 * kPi * r * 2 * h);
    // Prolate spheroid (a, a, c), c > a: area 2 pi a^2 (1 + c / (a e) asin e), e^2 = 1 - a^2/c^2.
    scene::Shape sph = test::sphere({0, 0, 0}, 1);
    const double a = 0.8, c = 1.5, e = std::sqrt(1 - a * a / (c * c));
    sph.to_world = Transform::scale({float(a), float(a), float(c)});
    const double spheroid = 2 * kPi * a * a * (1 + c / (a * e) * std::asin(e));
    EXPECT_NEAR(ShapeSampler(sph).area(), spheroid, 1e-3 * spheroid);
}

TEST(ShapeSampler, SamplesLieOnTheSurfaceWithOutwardNormals) {
    const Transform t = Transform::translate({1, -1, 2}) * Transform::rotate(30, {1, 2, 3}) *
                        Transform::scale({1.5f, 0.5f, 1});
    scene::Shape sph = test::sphere({0.2f, 0, 0}, 1);
    sph.to_world = t;
    scene::Shape cyl;
    cyl.kind = scene::Shape::Kind::Cylinder;
    cyl.radius = 0.5f;
    cyl.height = 2;
    cyl.capped = false;
    cyl.to_world = t;
    scene::Shape cone = cyl;
    cone.kind = scene::Shape::Kind::Cone;
    const Vec3 ax{0, 1, 0};
    for (const scene::Shape* s : {&sph, &cyl, &cone}) {
        const ShapeSampler sampler(*s);
        Sampler rng(21);
        for (int i = 0; i < 500; ++i) {
            const ShapeSample ss = sampler.sample_area(rng.next2());
            const Vec3 q = t.inverse().point(ss.p);
            Vec3 n_obj;
            if (s == &sph) {
                ASSERT_NEAR(length(q - s->center), 1.0f, 1e-4f);
                n_obj = q - s->center;
            } else if (s == &cyl) {
                const Vec3 radial = q - ax * q.y;
                ASSERT_NEAR(length(radial), 0.5f, 1e-4f);
                ASSERT_LE(std::fabs(q.y), 1.0f + 1e-4f);
                n_obj = radial;
            } else {
                const float depth = 1 - q.y;  // below the apex at y = 1
                const Vec3 radial = q - ax * q.y;
                ASSERT_NEAR(length(radial), 0.5f * depth / 2, 1e-4f);
                n_obj = normalize(radial) * 2.0f + ax * 0.5f;
            }
            EXPECT_NEAR(dot(ss.n, normalize(t.normal(n_obj))), 1.0f, 1e-4f);
            EXPECT_NEAR(ss.pdf, 1 / sampler.area(), 1e-6f);
        }
    }
}

}  // namespace
}  // namespace phos::shading
