// Area lights against closed forms: Monte Carlo irradiance from sample_Li under a rectangle (mesh),
// a transformed rectangle, a disk, an annulus, an ellipse (non-uniformly scaled disk) and spheres;
// one- and two-sidedness; and the emitting-side rule (reverse_orientation XOR handedness swap).
// Irradiance is checked at every wavelength sample: the closed form per unit radiance times what
// the light's RGB colour emits there (read as an illuminant).
#include <gtest/gtest.h>

#include <utility>

#include "core/transform.h"
#include "light_test_util.h"
#include "shading/area_light.h"

namespace phos::shading {
namespace {

using test::expect_means;
using test::SpectralStat;

// The wavelengths the irradiance is estimated at.
const Wavelengths& kLambda = spectral::fixed_lambda();

// Irradiance at x (normal n) estimated from N sample_Li samples: mean of L cos+ / pdf, at each
// wavelength of kLambda.
SpectralStat irradiance(const Light& light, Vec3 x, Vec3 n, int N, uint64_t seed) {
    Sampler rng(seed);
    SpectralStat e;
    for (int i = 0; i < N; ++i) {
        const LightLiSample s = light.sample_Li(x, rng.next2(), kLambda);
        e.add(s.pdf > 0 ? s.L * float(std::max(0.0, test::dot_d(s.wi, n)) / s.pdf) : Spectrum(0.0f));
    }
    return e;
}

// What a light of RGB colour L emits at kLambda, times `factor` (a closed form per unit radiance).
Spectrum emitted(float L, double factor = 1) { return spectral::emitted(Rgb(L), kLambda) * float(factor); }

std::vector<Vec3> world_vertices(const scene::Shape& s) {
    std::vector<Vec3> v;
    for (Vec3 p : s.mesh.positions) v.push_back(s.to_world.point(p));
    return v;
}

TEST(AreaLight, RectangleIrradianceMatchesLambert) {
    const scene::Shape rect = test::rectangle_y(-0.5f, 0.5f, -0.25f, 0.75f, 1.5f);
    const AreaLight light(test::area_light_record(Rgb(2.0f)), rect);
    EXPECT_NEAR(light.sampler().area(), 1.0f, 1e-6f);
    const Vec3 up{0, 1, 0};
    int i = 0;
    for (Vec3 x : {Vec3(0, 0, 0), Vec3(1, 0, 0.3f), Vec3(-0.7f, 0, -1.2f), Vec3(2, 0, 2)}) {
        const double closed = test::lambert_irradiance(rect.mesh.positions, x, up, 1.0);
        expect_means(irradiance(light, x, up, 40000, 100 + uint64_t(i++)), emitted(2, closed),
                     "rectangle irradiance");
    }
    // A tilted receiver as well.
    const Vec3 tilted = normalize(Vec3(0.3f, 1, -0.2f));
    expect_means(irradiance(light, {0.2f, 0, 0.1f}, tilted, 40000, 9),
                 emitted(2, test::lambert_irradiance(rect.mesh.positions, {0.2f, 0, 0.1f}, tilted, 1.0)),
                 "tilted");
}

TEST(AreaLight, TransformedMeshUsesWorldSpaceGeometry) {
    // Unit square in object space, stretched non-uniformly, tilted and moved up.
    scene::Shape rect = test::rectangle_y(0, 1, 0, 1, 0);
    rect.to_world = Transform::translate({-0.8f, 2, -0.3f}) * Transform::rotate(20, {1, 0, 0}) *
                    Transform::rotate(35, {0, 1, 0}) * Transform::scale({2, 1, 0.5f});
    const AreaLight light(test::area_light_record(Rgb(1.5f)), rect);
    EXPECT_NEAR(light.sampler().area(), 1.0f, 1e-5f);  // 2 x 0.5
    const std::vector<Vec3> poly = world_vertices(rect);
    const Vec3 up{0, 1, 0};
    int i = 0;
    for (Vec3 x : {Vec3(0, 0, 0), Vec3(0.5f, 0, 0.5f), Vec3(-1, 0, -0.5f)}) {
        expect_means(irradiance(light, x, up, 40000, 200 + uint64_t(i++)),
                     emitted(1.5f, test::lambert_irradiance(poly, x, up, 1.0)), "transformed rectangle");
    }
}

TEST(AreaLight, DiskAndAnnulusOnAxis) {
    const float r = 0.8f, h = 1.7f, ri = 0.3f, L = 3;
    const AreaLight d(test::area_light_record(Rgb(L)), test::disk({0, h, 0}, {0, -1, 0}, r));
    const AreaLight a(test::area_light_record(Rgb(L)), test::disk({0, h, 0}, {0, -1, 0}, r, ri));
    // Per unit radiance.
    const double disk_e = kPi * r * r / (r * r + h * h);
    const double ring_e = disk_e - kPi * ri * ri / (ri * ri + h * h);
    expect_means(irradiance(d, {0, 0, 0}, {0, 1, 0}, 40000, 1), emitted(L, disk_e), "disk");
    expect_means(irradiance(a, {0, 0, 0}, {0, 1, 0}, 40000, 2), emitted(L, ring_e), "annulus");
    EXPECT_NEAR(d.sampler().area(), kPi * r * r, 1e-5f);
    EXPECT_NEAR(a.sampler().area(), kPi * (r * r - ri * ri), 1e-5f);
}

TEST(AreaLight, EllipseFromNonUniformlyScaledDisk) {
    scene::Shape s = test::disk({0, 0, 0}, {0, -1, 0}, 1);
    s.to_world = Transform::translate({0.3f, 1.2f, -0.2f}) * Transform::scale({1.5f, 1, 0.6f});
    const AreaLight light(test::area_light_record(Rgb(1.0f)), s);
    EXPECT_NEAR(light.sampler().area(), kPi * 1.5f * 0.6f, 1e-5f);
    // The ellipse as a fine inscribed polygon (area error ~ (2 pi / n)^2 / 6, negligible).
    std::vector<Vec3> poly;
    const int n = 2048;
    for (int k = 0; k < n; ++k) {
        const float phi = 2 * kPi * float(k) / n;
        poly.push_back(s.to_world.point({std::cos(phi), 0, std::sin(phi)}));
    }
    int i = 0;
    for (Vec3 x : {Vec3(0, 0, 0), Vec3(1, 0, 0.5f), Vec3(-0.5f, 0, -1)})
        expect_means(irradiance(light, x, {0, 1, 0}, 40000, 300 + uint64_t(i++)),
                     emitted(1, test::lambert_irradiance(poly, x, {0, 1, 0}, 1.0)), "ellipse");
}

TEST(AreaLight, SphereIrradiance) {
    // E = pi L (r/d)^2 cos(theta) while the whole visible cap is above the receiver's horizon.
    const float L = 2, r = 1, d = 3;
    const AreaLight plain(test::area_light_record(Rgb(L)), test::sphere({0, d, 0}, r));
    scene::Shape scaled = test::sphere({0, 0, 0}, 2);
    scaled.to_world =
        Transform::translate({0, d, 0}) * Transform::rotate(40, {1, 1, 0}) * Transform::scale(Vec3(0.5f));
    const AreaLight similar(test::area_light_record(Rgb(L)), scaled);
    EXPECT_NEAR(similar.sampler().area(), 4 * kPi, 1e-4f);
    EXPECT_FALSE(similar.sampler().tessellated());
    int i = 0;
    for (float theta : {0.0f, 0.4f, 1.0f}) {
        const Vec3 n{std::sin(theta), std::cos(theta), 0};
        const Spectrum closed = emitted(L, kPi * (r / d) * (r / d) * std::cos(theta));
        expect_means(irradiance(plain, {0, 0, 0}, n, 40000, 400 + uint64_t(i++)), closed, "sphere");
        expect_means(irradiance(similar, {0, 0, 0}, n, 40000, 500 + uint64_t(i++)), closed, "scaled sphere");
    }
}

TEST(AreaLight, OneSidedAndTwoSided) {
    const scene::Shape rect = test::rectangle_y(-0.5f, 0.5f, -0.5f, 0.5f, 1);
    const AreaLight one(test::area_light_record(Rgb(1.0f)), rect);
    const AreaLight two(test::area_light_record(Rgb(1.0f), true), rect);
    const Spectrum white = emitted(1);  // RGB white: D65-shaped
    EXPECT_FALSE(white.is_black());
    EXPECT_EQ(one.Le({0, -1, 0}, {0, -1, 0}, kLambda), white);
    EXPECT_EQ(one.Le({0, -1, 0}, {0, 1, 0}, kLambda), Spectrum(0.0f));
    EXPECT_EQ(two.Le({0, -1, 0}, {0, 1, 0}, kLambda), white);
    // From above (behind the emitting side) a one-sided light delivers nothing.
    Sampler rng(5);
    for (int i = 0; i < 100; ++i) {
        const Vec2 u = rng.next2();
        EXPECT_TRUE(one.sample_Li({0, 2, 0}, u, kLambda).L.is_black());
        EXPECT_EQ(two.sample_Li({0, 2, 0}, u, kLambda).L, white);
        EXPECT_EQ(one.sample_Li({0, 0, 0}, u, kLambda).L, white);
    }
    EXPECT_NEAR(two.power().r, 2 * one.power().r, 1e-6f);
}

// A two-sided light (a .scn glow) lights its back as its front: Lambert's irradiance at mirrored
// points on either side, and sample_Li's density agrees with pdf_Li on both sides.
TEST(AreaLight, TwoSidedLightsBothSidesAlike) {
    const scene::Shape rect = test::rectangle_y(-0.5f, 0.5f, -0.25f, 0.75f, 1.5f);
    const AreaLight light(test::area_light_record(Rgb(2.0f), true), rect);
    int i = 0;
    for (const auto& [x, n] :
         {std::pair<Vec3, Vec3>{{0.3f, 0, 0.1f}, {0, 1, 0}}, {{0.3f, 3, 0.1f}, {0, -1, 0}}}) {
        const Spectrum closed = emitted(2, test::lambert_irradiance(rect.mesh.positions, x, n, 1.0));
        expect_means(irradiance(light, x, n, 40000, 700 + uint64_t(i++)), closed, "two-sided irradiance");
        Sampler rng(710 + uint64_t(i));
        for (int k = 0; k < 100; ++k) {
            const LightLiSample s = light.sample_Li(x, rng.next2(), kLambda);
            ASSERT_GT(s.pdf, 0);
            EXPECT_EQ(s.L, emitted(2));
            EXPECT_NEAR(light.pdf_Li(x, s.wi, s.p_light, s.n_light), s.pdf, 1e-4f * s.pdf);
        }
    }
    // Mirrored points see the same irradiance (1.5 below and above the light).
    EXPECT_NEAR(test::lambert_irradiance(rect.mesh.positions, {0.3f, 0, 0.1f}, {0, 1, 0}, 2.0),
                test::lambert_irradiance(rect.mesh.positions, {0.3f, 3, 0.1f}, {0, -1, 0}, 2.0), 1e-6);
}

// Expected emitting normals, by the accel layer's rules (see shape_sampler.h): analytic shapes use
// to_world.normal(object normal) flipped if reverse XOR swaps; meshes the world-space edge cross
// product flipped if reverse XOR swaps; boxes are meshes wound counter-clockwise from outside.
bool flipped(const scene::Shape& s) { return s.reverse_orientation != s.to_world.swaps_handedness(); }
Vec3 analytic_normal(const scene::Shape& s, Vec3 n_obj) {
    return normalize(s.to_world.normal(n_obj)) * (flipped(s) ? -1.0f : 1.0f);
}
Vec3 mesh_normal(const scene::Shape& s, Vec3 a, Vec3 b, Vec3 c) {
    const Vec3 wa = s.to_world.point(a), wb = s.to_world.point(b), wc = s.to_world.point(c);
    return normalize(cross(wb - wa, wc - wa)) * (flipped(s) ? -1.0f : 1.0f);
}

TEST(AreaLight, EmittingSideFollowsOrientationRule) {
    const Transform mirror = Transform::translate({0.5f, 0, 0}) * Transform::scale({1, 1, -1});
    const Transform plain = Transform::rotate(30, {0, 0, 1});
    for (bool reverse : {false, true})
        for (const Transform* t : {&plain, &mirror}) {
            // Disk (object normal +y), sphere (outward), mesh (counter-clockwise front = -y here),
            // unit box.
            scene::Shape d = test::disk({0, 0, 0}, {0, 1, 0}, 1);
            scene::Shape sp = test::sphere({0, 0, 0}, 1);
            scene::Shape m = test::rectangle_y(0, 1, 0, 1, 0);
            scene::Shape box;
            box.kind = scene::Shape::Kind::Box;
            for (scene::Shape* s : {&d, &sp, &m, &box}) {
                s->reverse_orientation = reverse;
                s->to_world = *t;
            }
            const ShapeSampler ds(d), ss(sp), ms(m), bs(box);
            const Vec3 mesh_n = mesh_normal(m, m.mesh.positions[0], m.mesh.positions[1], m.mesh.positions[2]);
            Sampler rng(17);
            for (int i = 0; i < 50; ++i) {
                const Vec2 u = rng.next2();
                const ShapeSample a = ds.sample_area(u), b = ss.sample_area(u), c = ms.sample_area(u);
                EXPECT_NEAR(dot(a.n, analytic_normal(d, {0, 1, 0})), 1.0f, 1e-5f) << reverse;
                const Vec3 p_obj = t->inverse().point(b.p);
                EXPECT_NEAR(dot(b.n, analytic_normal(sp, p_obj)), 1.0f, 1e-5f) << reverse;
                EXPECT_NEAR(dot(c.n, mesh_n), 1.0f, 1e-5f) << reverse;
                // Box face: the outward direction in world space is that of to_world.normal of the
                // object face normal; mesh rule = outward unless reversed.
                const ShapeSample e = bs.sample_area(u);
                const Vec3 q = t->inverse().point(e.p);
                const Vec3 centre_dir = normalize(t->normal(q - Vec3(0.5f)));
                EXPECT_GT(dot(e.n, centre_dir) * (reverse ? -1.0f : 1.0f), 0.0f) << reverse;
            }
        }
}

TEST(AreaLight, MeshShadingNormalsPickTheEmittingSide) {
    // Same rectangle (geometric front -y) with vertex normals pointing up: the accel layer turns
    // the geometric normal towards them, so the light emits upwards.
    scene::Shape m = test::rectangle_y(0, 1, 0, 1, 0);
    m.mesh.normals.assign(4, Vec3(0, 1, 0));
    const ShapeSampler s(m);
    Sampler rng(3);
    for (int i = 0; i < 20; ++i) EXPECT_NEAR(s.sample_area(rng.next2()).n.y, 1.0f, 1e-6f);
    m.reverse_orientation = true;  // shading normals flip with reverse_orientation
    const ShapeSampler r(m);
    for (int i = 0; i < 20; ++i) EXPECT_NEAR(r.sample_area(rng.next2()).n.y, -1.0f, 1e-6f);
}

}  // namespace
}  // namespace phos::shading
