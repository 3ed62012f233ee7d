// Partial spheres (pbrt's zmin, zmax, phimax): hits against a brute-force reference (both roots of
// the full sphere, each kept only inside the ranges), the inside seen through the cut, pbrt's (u, v),
// tight bounds, and instances and transforms.
#include <gtest/gtest.h>

#include <cmath>

#include "accel/embree_scene.h"
#include "accel/scene_builders.h"

namespace phos::testing {
namespace {

using scene::Shape;

Shape partial_sphere(float r, float zmin, float zmax, float phimax) {
    Shape s = sphere({0, 0, 0}, r);
    s.axis = {0, 0, 1};
    s.partial = true;
    s.z_min = zmin, s.z_max = zmax, s.phi_max = phimax;
    return s;
}

scene::Scene single(Shape s) {
    scene::Scene sc;
    sc.shapes.push_back(std::move(s));
    return sc;
}

// The closest t of o + t d (object space = world space here) on the part, or -1: both roots of the
// full sphere in long double, each tested against the ranges. `ambiguous`: a root lies within 1e-4
// of a cut edge, or the ray grazes the sphere, where rounding may decide either way.
double reference_t(Vec3 o, Vec3 d, double r, double zmin, double zmax, double phimax, bool& ambiguous) {
    const long double a = (long double)d.x * d.x + (long double)d.y * d.y + (long double)d.z * d.z;
    const long double b = (long double)o.x * d.x + (long double)o.y * d.y + (long double)o.z * d.z;
    const long double c = (long double)o.x * o.x + (long double)o.y * o.y + (long double)o.z * o.z - r * r;
    const long double disc = b * b - a * c;
    ambiguous = std::fabs(disc) < 1e-6L;
    if (disc < 0) return -1;
    double found = -1;
    for (long double t : {(-b - std::sqrt(disc)) / a, (-b + std::sqrt(disc)) / a}) {
        if (t <= 0) continue;
        const long double x = o.x + t * d.x, y = o.y + t * d.y, z = o.z + t * d.z;
        long double phi = std::atan2(y, x);
        if (phi < 0) phi += 2 * 3.14159265358979323846L;
        if (std::fabs(z - zmin) < 1e-4 || std::fabs(z - zmax) < 1e-4 || std::fabs(phi - phimax) < 1e-4 ||
            phi < 1e-4 || phi > 2 * 3.14159265358979323846L - 1e-4)
            ambiguous = true;
        if (found < 0 && z >= zmin && z <= zmax && phi <= phimax) found = double(t);
    }
    return found;
}

TEST(PartialSphere, HitsMatchTheBruteForceReference) {
    const float r = 1.5f, zmin = -0.6f, zmax = 1.1f, phimax = 4.0f;
    const scene::Scene sc = single(partial_sphere(r, zmin, zmax, phimax));
    const accel::EmbreeScene es(sc);
    Sampler rng(3);
    int hits = 0, through = 0, near_edge = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 o = random_in(rng, Vec3(-4.0f), Vec3(4.0f));
        // Aim near the sphere so most rays meet it, many through the cut.
        const Vec3 target = random_in(rng, Vec3(-1.5f), Vec3(1.5f));
        if (length(o) < r * 1.01f) continue;
        const Vec3 d = normalize(target - o);
        bool edge = false;
        const double t_ref = reference_t(o, d, r, zmin, zmax, phimax, edge);
        accel::SurfaceHit h;
        const bool hit = es.intersect({o, d}, h);
        if (edge) {
            ++near_edge;
            continue;
        }
        ASSERT_EQ(hit, t_ref > 0) << i;
        if (!hit) continue;
        ++hits;
        EXPECT_NEAR(h.t, t_ref, 1e-4 * (1 + t_ref)) << i;
        EXPECT_NEAR(length(h.p), r, 1e-5f);
        EXPECT_NEAR(length(h.ng), 1, 1e-5);
        // The outward normal, whichever side the ray came from.
        EXPECT_GT(dot(h.ng, h.p), 0.99f * r);
        if (dot(h.ng, d) > 0) ++through;  // the inside, seen through the cut
    }
    EXPECT_GT(hits, 5000);
    EXPECT_GT(through, 500);
    EXPECT_LT(near_edge, 200);
}

TEST(PartialSphere, TheInsideIsVisibleThroughTheCutAndOcclusionAgrees) {
    // The lower hemisphere (zmax = 0), a bowl: a ray down the axis passes the open top and meets
    // the bottom from inside.
    const scene::Scene sc = single(partial_sphere(1, -1, 0, 2 * kPi));
    const accel::EmbreeScene es(sc);
    accel::SurfaceHit h;
    ASSERT_TRUE(es.intersect({{0, 0, 5}, {0, 0, -1}}, h));
    EXPECT_NEAR(h.t, 6, 1e-5);
    EXPECT_NEAR(h.p.z, -1, 1e-5);
    EXPECT_NEAR(h.ng.z, -1, 1e-5);  // outward: away from the viewer
    // From below, the outside of the bowl.
    ASSERT_TRUE(es.intersect({{0, 0, -5}, {0, 0, 1}}, h));
    EXPECT_NEAR(h.t, 4, 1e-5);
    // A horizontal ray above the bowl misses it; one below z = 0 hits it.
    EXPECT_FALSE(es.intersect({{-5, 0, 0.1f}, {1, 0, 0}}, h));
    EXPECT_FALSE(es.occluded({{-5, 0, 0.1f}, {1, 0, 0}}));
    EXPECT_TRUE(es.occluded({{-5, 0, -0.1f}, {1, 0, 0}}));
    // A quarter-turn wedge removed (phimax = 270 degrees): the ray along +y... from -y towards +y at
    // x = -0.5 first meets phi in (180, 270) degrees (kept) ; at x = +0.5 it meets phi in (270, 360)
    // (cut away) and goes on to the far side, phi in (0, 90) (kept).
    const scene::Scene wedge = single(partial_sphere(1, -1, 1, 1.5f * kPi));
    const accel::EmbreeScene ew(wedge);
    ASSERT_TRUE(ew.intersect({{-0.5f, -5, 0}, {0, 1, 0}}, h));
    EXPECT_NEAR(h.p.y, -std::sqrt(0.75f), 1e-5);
    ASSERT_TRUE(ew.intersect({{0.5f, -5, 0}, {0, 1, 0}}, h));
    EXPECT_NEAR(h.p.y, std::sqrt(0.75f), 1e-5);
    EXPECT_LT(dot(h.ng, Vec3(0, -1, 0)), 0.0f);  // seen from inside
}

TEST(PartialSphere, UvIsPbrtsAndBoundsAreTight) {
    // u = phi / phimax, v = (theta - theta(zmin)) / (theta(zmax) - theta(zmin)).
    const float zmin = -0.5f, zmax = 0.8f, phimax = kPi;
    const scene::Scene sc = single(partial_sphere(1, zmin, zmax, phimax));
    const accel::EmbreeScene es(sc);
    accel::SurfaceHit h;
    const float tmin = std::acos(zmin), tmax = std::acos(zmax);
    for (float phi : {0.3f, 1.4f, 2.9f})
        for (float theta : {tmax + 0.01f, 1.2f, tmin - 0.01f}) {
            const Vec3 p{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
            ASSERT_TRUE(es.intersect({p * 3.0f, -p}, h));
            EXPECT_NEAR(h.uv.x, phi / phimax, 1e-5);
            EXPECT_NEAR(h.uv.y, (theta - tmin) / (tmax - tmin), 1e-5);
            // dp/du along increasing phi.
            EXPECT_GT(dot(h.dpdu, Vec3(-std::sin(phi), std::cos(phi), 0)), 0.999f);
        }
    const Bounds b = es.bounds();
    EXPECT_NEAR(b.lo.z, zmin, 1e-4);
    EXPECT_NEAR(b.hi.z, zmax, 1e-4);
    EXPECT_NEAR(b.lo.x, -1, 1e-4);
}

TEST(PartialSphere, TransformedAndInstancedHitsAreTheObjectSpaceOnes) {
    // A bowl scaled by 2 and moved, top-level and as an instance: the bottom sits at z = 3 - 2.
    Shape s = partial_sphere(1, -1, 0, 2 * kPi);
    s.to_world = Transform::translate({0, 0, 3}) * Transform::scale(Vec3(2.0f));
    scene::Scene sc = single(s);
    scene::Object obj;
    obj.shapes.push_back(partial_sphere(1, -1, 0, 2 * kPi));
    sc.objects.push_back(obj);
    sc.instances.push_back({0, Transform::translate({10, 0, 3}) * Transform::scale(Vec3(2.0f))});
    const accel::EmbreeScene es(sc);
    accel::SurfaceHit h;
    for (float x : {0.0f, 10.0f}) {
        ASSERT_TRUE(es.intersect({{x, 0, 20}, {0, 0, -1}}, h));
        EXPECT_NEAR(h.p.z, 1, 1e-5);
        EXPECT_NEAR(h.ng.z, -1, 1e-5);
    }
}

}  // namespace
}  // namespace phos::testing
