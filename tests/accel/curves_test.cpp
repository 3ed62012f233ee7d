// Curves through Embree's curve geometry (accel/curves.h): a straight cylinder curve against the
// analytic cylinder (distance, normal, uv), flat curves facing the ray, ribbons following their
// normals, transforms and instances, occlusion, packets, and rays spawned from curve hits.
#include <gtest/gtest.h>

#include <cmath>

#include "accel/embree_scene.h"
#include "accel/scene_builders.h"

namespace phos::testing {
namespace {

using scene::CurveSet;
using scene::Shape;

// One cubic Bezier segment from (-1, 0, 0) to (1, 0, 0) with equally spaced control points (so
// the curve parameter u is (x + 1) / 2) and constant radius r.
Shape straight_curve(CurveSet::Type type, float r, Vec3 normal = {0, 0, 1}) {
    Shape s;
    s.kind = Shape::Kind::Curves;
    s.material = 3;
    s.curves.type = type;
    s.curves.basis = CurveSet::Basis::Bezier;
    for (int k = 0; k < 4; ++k) {
        s.curves.points.push_back({-1.0f + 2.0f * float(k) / 3.0f, 0, 0});
        s.curves.radii.push_back(r);
        if (type == CurveSet::Type::Ribbon) s.curves.normals.push_back(normal);
    }
    s.curves.segments = {0};
    return s;
}

scene::Scene single(Shape s) {
    scene::Scene sc;
    sc.shapes.push_back(std::move(s));
    return sc;
}

void expect_vec(Vec3 a, Vec3 b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// The first hit of o + t d on the infinite cylinder of radius r around the x axis, or -1.
double cylinder_t(Vec3 o, Vec3 d, double r) {
    const double a = double(d.y) * d.y + double(d.z) * d.z, b = double(o.y) * d.y + double(o.z) * d.z,
                 c = double(o.y) * o.y + double(o.z) * o.z - r * r;
    const double disc = b * b - a * c;
    if (disc < 0 || a == 0) return -1;
    return (-b - std::sqrt(disc)) / a;
}

TEST(Curves, CylinderCurveMatchesTheAnalyticCylinder) {
    const float r = 0.25f;
    const scene::Scene sc = single(straight_curve(CurveSet::Type::Cylinder, r));
    const accel::EmbreeScene es(sc);
    Sampler rng(7, 1);
    int hits = 0;
    for (int i = 0; i < 200; ++i) {
        // Rays from random directions at points of the tube away from its open ends.
        const float x = -0.6f + 1.2f * rng.next(), phi = 2 * kPi * rng.next();
        const Vec3 target{x, r * std::cos(phi), r * std::sin(phi)};
        const Vec3 outward{0, std::cos(phi), std::sin(phi)};
        Vec3 d = random_unit(rng);
        if (dot(d, outward) > -0.2f) d = d - outward * (2 * dot(d, outward) + 0.5f);
        d = normalize(d);
        const Vec3 o = target - d * 3.0f;
        const double t = cylinder_t(o, d, r);
        ASSERT_GT(t, 0);
        const Vec3 p = o + d * float(t);
        if (std::fabs(p.x) > 0.8f) continue;  // the analytic first hit is near an end
        accel::SurfaceHit h;
        ASSERT_TRUE(es.intersect({o, d}, h)) << i;
        ++hits;
        EXPECT_NEAR(h.t, t, 2e-4) << i;
        expect_vec(h.p, p, 2e-4f);
        const Vec3 n = normalize(Vec3(0, p.y, p.z));
        expect_vec(h.ng, n, 2e-3f);
        expect_vec(h.ns, h.ng, 0);
        EXPECT_NEAR(h.uv.x, (p.x + 1) / 2, 1e-3) << i;  // u along the curve
        EXPECT_GE(h.uv.y, 0);
        EXPECT_LE(h.uv.y, 1);
        EXPECT_NEAR(std::fabs(h.dpdu.x), 1, 1e-5);
        EXPECT_EQ(h.material, 3);
        EXPECT_EQ(h.shape, 0);
        EXPECT_EQ(h.primitive, 0);
        EXPECT_EQ(h.area_light, -1);
    }
    EXPECT_GT(hits, 150);
    // Seen straight on, v runs across the width: 0.5 on the axis, towards 0 and 1 at the sides
    // (pbrt-v4: v > 0.5 on the side of d x dC/du, here -y).
    accel::SurfaceHit h;
    ASSERT_TRUE(es.intersect({{0.2f, 0, 5}, {0, 0, -1}}, h));
    EXPECT_NEAR(h.t, 5 - r, 1e-4);
    EXPECT_NEAR(h.uv.y, 0.5, 1e-3);
    ASSERT_TRUE(es.intersect({{0.2f, -0.2f, 5}, {0, 0, -1}}, h));
    EXPECT_NEAR(h.uv.y, 0.5 + 0.2 / (2 * r), 1e-3);
    ASSERT_TRUE(es.intersect({{0.2f, 0.2f, 5}, {0, 0, -1}}, h));
    EXPECT_NEAR(h.uv.y, 0.5 - 0.2 / (2 * r), 1e-3);
    // Beside the tube: nothing; shadow rays see it.
    EXPECT_FALSE(es.intersect({{0.2f, 0.3f, 5}, {0, 0, -1}}, h));
    EXPECT_TRUE(es.occluded({{0.2f, 0.1f, 5}, {0, 0, -1}}));
    EXPECT_FALSE(es.occluded({{0.2f, 0.3f, 5}, {0, 0, -1}}));
    EXPECT_FALSE(es.occluded({{0.2f, 0.1f, 5}, {0, 0, -1}, 0.0f, 4.5f}));
}

TEST(Curves, RadiusVariesAlongTheCurve) {
    Shape s = straight_curve(CurveSet::Type::Cylinder, 0.1f);
    s.curves.radii = {0.1f, 0.2f, 0.3f, 0.4f};  // linear in u: 0.1 at x = -1 to 0.4 at x = 1
    const scene::Scene sc = single(s);
    const accel::EmbreeScene es(sc);
    for (float x : {-0.5f, 0.0f, 0.5f}) {
        const float r = 0.1f + 0.3f * (x + 1) / 2;
        accel::SurfaceHit h;
        ASSERT_TRUE(es.intersect({{x, 0, 5}, {0, 0, -1}}, h));
        // The tube's surface is inclined where the radius changes: the hit lies within a little of
        // the radius at x.
        EXPECT_NEAR(h.t, 5 - r, 0.01) << x;
    }
}

TEST(Curves, FlatCurveFacesTheRay) {
    const float r = 0.1f;
    const scene::Scene sc = single(straight_curve(CurveSet::Type::Flat, r));
    const accel::EmbreeScene es(sc);
    for (const Vec3 d : {Vec3(0, 0, -1), normalize(Vec3(0, 1, -1)), normalize(Vec3(0, -1, -0.2f)),
                         normalize(Vec3(0.3f, 0.5f, 0.6f))}) {
        const Vec3 target{0.2f, 0, 0};
        accel::SurfaceHit h;
        ASSERT_TRUE(es.intersect({target - d * 4.0f, d}, h)) << d.x << " " << d.y << " " << d.z;
        EXPECT_NEAR(h.t, 4, 1e-3);
        // The normal is -d without its component along the curve (+-x).
        const Vec3 facing = normalize(Vec3(0, -d.y, -d.z));
        expect_vec(h.ng, facing, 1e-3f);
        EXPECT_NEAR(h.uv.y, 0.5, 1e-2);
        // Within the half-width across the ray the band is hit, beyond it not.
        const Vec3 across = normalize(cross(d, Vec3(1, 0, 0)));
        EXPECT_TRUE(es.intersect({target + across * 0.07f - d * 4.0f, d}, h));
        EXPECT_FALSE(es.intersect({target + across * 0.14f - d * 4.0f, d}, h));
    }
    // ReverseOrientation turns the normal away from the ray.
    Shape rev = straight_curve(CurveSet::Type::Flat, r);
    rev.reverse_orientation = true;
    accel::SurfaceHit h;
    const scene::Scene rev_scene = single(rev);
    ASSERT_TRUE(accel::EmbreeScene(rev_scene).intersect({{0, 0, 4}, {0, 0, -1}}, h));
    expect_vec(h.ng, {0, 0, -1}, 1e-4f);
}

TEST(Curves, RibbonFollowsItsNormals) {
    const float r = 0.25f;
    // A ribbon in the plane y + z = 0 (normal (0, 1, 1) / sqrt 2) seen from +z: the normal is the
    // ribbon's, not the ray's, and the band's width lies in that plane.
    const Vec3 n = normalize(Vec3(0, 1, 1));
    const scene::Scene sc = single(straight_curve(CurveSet::Type::Ribbon, r, n));
    const accel::EmbreeScene es(sc);
    accel::SurfaceHit h;
    ASSERT_TRUE(es.intersect({{0.3f, 0, 5}, {0, 0, -1}}, h));
    EXPECT_NEAR(h.t, 5, 1e-3);
    expect_vec(h.ng, n, 1e-3f);
    // From below, the normal still points along the ribbon's normals.
    ASSERT_TRUE(es.intersect({{0.3f, 0, -5}, {0, 0, 1}}, h));
    expect_vec(h.ng, n, 1e-3f);
    // A point of the band at distance 0.2 from the axis: (0.3, 0.2 / sqrt 2, -0.2 / sqrt 2).
    const float k = 0.2f / std::sqrt(2.0f);
    ASSERT_TRUE(es.intersect({{0.3f, k, 5}, {0, 0, -1}}, h));
    EXPECT_NEAR(h.t, 5 + k, 1e-3);
    // Beyond the half-width (0.3 from the axis) nothing.
    EXPECT_FALSE(es.intersect({{0.3f, 0.3f / std::sqrt(2.0f), 5}, {0, 0, -1}}, h));
    // Normals the other way: the ribbon's normal flips with them.
    const scene::Scene flipped_scene = single(straight_curve(CurveSet::Type::Ribbon, r, -n));
    const accel::EmbreeScene flipped(flipped_scene);
    ASSERT_TRUE(flipped.intersect({{0.3f, 0, 5}, {0, 0, -1}}, h));
    expect_vec(h.ng, -n, 1e-3f);
}

TEST(Curves, BSplineBasisAndSeveralSegments) {
    // A uniform cubic B-spline with control points on the x axis at -2..2 (unit spacing): its two
    // segments run from x = -1 to 0 and 0 to 1.
    Shape s;
    s.kind = Shape::Kind::Curves;
    s.curves.type = CurveSet::Type::Cylinder;
    s.curves.basis = CurveSet::Basis::BSpline;
    for (int k = -2; k <= 2; ++k) {
        s.curves.points.push_back({float(k), 0, 0});
        s.curves.radii.push_back(0.2f);
    }
    s.curves.segments = {0, 1};
    const scene::Scene sc = single(s);
    const accel::EmbreeScene es(sc);
    accel::SurfaceHit h;
    ASSERT_TRUE(es.intersect({{-0.25f, 0, 5}, {0, 0, -1}}, h));
    EXPECT_EQ(h.primitive, 0);
    EXPECT_NEAR(h.uv.x, 0.75, 1e-3);
    EXPECT_NEAR(h.t, 4.8, 1e-4);
    ASSERT_TRUE(es.intersect({{0.25f, 0, 5}, {0, 0, -1}}, h));
    EXPECT_EQ(h.primitive, 1);
    EXPECT_NEAR(h.uv.x, 0.25, 1e-3);
    EXPECT_FALSE(es.intersect({{1.5f, 0, 5}, {0, 0, -1}}, h));
}

TEST(Curves, TransformsScaleTheRadiusAndInstancesCarryCurves) {
    // Scaled by 2 and moved up by 1: radius 0.5 around the line z = 1, x in [-2, 2].
    Shape s = straight_curve(CurveSet::Type::Cylinder, 0.25f);
    s.to_world = Transform::translate({0, 0, 1}) * Transform::scale(Vec3(2.0f));
    accel::SurfaceHit h;
    const scene::Scene moved = single(s);
    ASSERT_TRUE(accel::EmbreeScene(moved).intersect({{1.5f, 0, 5}, {0, 0, -1}}, h));
    EXPECT_NEAR(h.t, 3.5, 1e-3);
    expect_vec(h.ng, {0, 0, 1}, 1e-3f);

    // The same curve in an object placed twice.
    scene::Scene sc;
    sc.objects.push_back({"hair", {straight_curve(CurveSet::Type::Cylinder, 0.25f)}});
    sc.instances.push_back({0, Transform::translate({0, 0, 1}) * Transform::scale(Vec3(2.0f))});
    sc.instances.push_back({0, Transform::translate({0, 5, 0}) * Transform::rotate(90, {0, 1, 0})});
    const accel::EmbreeScene es(sc);
    ASSERT_TRUE(es.intersect({{1.5f, 0, 5}, {0, 0, -1}}, h));
    EXPECT_NEAR(h.t, 3.5, 1e-3);
    expect_vec(h.p, {1.5f, 0, 1.5f}, 1e-3f);
    expect_vec(h.ng, {0, 0, 1}, 1e-3f);
    EXPECT_EQ(h.instance, 0);
    EXPECT_NEAR(h.uv.x, (0.75 + 1) / 2, 1e-3);
    // Rotated about y: the curve runs along z at y = 5; hit from +x.
    ASSERT_TRUE(es.intersect({{5, 5, 0.5f}, {-1, 0, 0}}, h));
    EXPECT_EQ(h.instance, 1);
    EXPECT_NEAR(h.t, 4.75, 1e-3);
    expect_vec(h.ng, {1, 0, 0}, 1e-3f);
}

TEST(Curves, PacketsGiveTheSingleRayHits) {
    const scene::Scene sc = single(straight_curve(CurveSet::Type::Cylinder, 0.25f));
    const accel::EmbreeScene es(sc);
    Ray rays[16];
    for (int k = 0; k < 16; ++k)
        rays[k] = {{-0.9f + 0.12f * float(k), 0.3f - 0.04f * float(k), 5}, {0, 0, -1}};
    accel::SurfaceHit hits[16];
    bool found[16];
    es.intersect16(rays, 16, hits, found);
    for (int k = 0; k < 16; ++k) {
        accel::SurfaceHit h;
        ASSERT_EQ(found[k], es.intersect(rays[k], h)) << k;
        if (!found[k]) continue;
        EXPECT_EQ(hits[k].t, h.t);
        EXPECT_EQ(hits[k].p.x, h.p.x);
        EXPECT_EQ(hits[k].ng.y, h.ng.y);
        EXPECT_EQ(hits[k].uv.y, h.uv.y);
    }
}

// Rays spawned from a hit leave it: outward from a tube without hitting it again, inward to its
// far wall; from a flat curve, away on either side.
TEST(Curves, SpawnedRaysLeaveTheCurve) {
    const float r = 0.25f;
    const scene::Scene tube = single(straight_curve(CurveSet::Type::Cylinder, r));
    const accel::EmbreeScene es(tube);
    Sampler rng(11, 2);
    for (int i = 0; i < 50; ++i) {
        const Vec3 o{-0.5f + rng.next(), 0.1f * (rng.next() - 0.5f), 5};
        accel::SurfaceHit h;
        ASSERT_TRUE(es.intersect({o, {0, 0, -1}}, h));
        Vec3 out = random_unit(rng);
        if (dot(out, h.ng) < 0) out = -out;
        accel::SurfaceHit again;
        EXPECT_FALSE(es.intersect(accel::spawn_ray(h, out), again)) << i << " t " << again.t;
        // Straight through: the far wall, a chord of the tube away.
        if (es.intersect(accel::spawn_ray(h, {0, 0, -1}), again)) {
            const float y = h.p.y;
            EXPECT_NEAR(again.t, 2 * std::sqrt(r * r - y * y), 1e-3) << i;
        } else {
            ADD_FAILURE() << "no far wall " << i;
        }
    }
    // A flat ribbon (normal +z): rays leaving either side do not meet it again.
    const scene::Scene ribbon_scene = single(straight_curve(CurveSet::Type::Ribbon, r));
    const accel::EmbreeScene ribbon(ribbon_scene);
    for (int i = 0; i < 50; ++i) {
        accel::SurfaceHit h;
        const float z = rng.next() < 0.5f ? 5.0f : -5.0f;
        ASSERT_TRUE(ribbon.intersect({{-0.5f + rng.next(), 0.4f * (rng.next() - 0.5f), z}, {0, 0, -z}}, h));
        const Vec3 out = random_unit(rng);
        accel::SurfaceHit again;
        EXPECT_FALSE(ribbon.intersect(accel::spawn_ray(h, out), again)) << i << " t " << again.t;
    }
    const scene::Scene flat_scene = single(straight_curve(CurveSet::Type::Flat, r));
    const accel::EmbreeScene flat(flat_scene);
    for (int i = 0; i < 20; ++i) {
        accel::SurfaceHit h;
        ASSERT_TRUE(flat.intersect({{-0.5f + rng.next(), 0.05f, 5}, {0, 0, -1}}, h));
        const Vec3 out = random_unit(rng);
        accel::SurfaceHit again;
        EXPECT_FALSE(flat.intersect(accel::spawn_ray(h, out), again)) << i;
    }
}

}  // namespace
}  // namespace phos::testing
