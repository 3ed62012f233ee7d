// Ray spawning robustness: rays leaving a surface never re-hit it at t ~ 0 (acne), rays refracted
// into a closed shape find its far side, and shadow rays do not leak through touching geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "accel/brute_force.h"
#include "accel/embree_scene.h"
#include "accel/scene_builders.h"

namespace phos::testing {
namespace {

using scene::Shape;

// A ray from outside the bounds aimed at a random point inside them.
Ray ray_at(Sampler& rng, const Bounds& b) {
    const Vec3 c = b.center();
    const float r = length(b.extent());
    const Vec3 target = random_in(rng, c - b.extent() * 0.4f, c + b.extent() * 0.4f);
    Ray ray;
    ray.origin = c + random_unit(rng) * (2 * r);
    ray.dir = target - ray.origin;
    return ray;
}

// For a scene holding one closed convex shape: rays spawned from hits outwards must escape and
// rays spawned inwards must reach the far side at the distance the reference intersector finds.
void check_convex_self_intersection(const scene::Scene& sc, int trials, uint64_t seed) {
    const accel::EmbreeScene es(sc);
    Sampler rng(seed);
    int hits = 0, inward = 0, bad = 0;
    for (int k = 0; k < trials; ++k) {
        accel::SurfaceHit h;
        if (!es.intersect(ray_at(rng, es.bounds()), h)) continue;
        ++hits;
        Vec3 dir = random_unit(rng);
        if (std::fabs(dot(dir, h.ng)) < 1e-3f) continue;  // skip true grazing
        const Ray r = accel::spawn_ray(h, dir);
        accel::SurfaceHit h2;
        const bool got = es.intersect(r, h2);
        if (dot(dir, h.ng) > 0) {
            if (got || es.occluded(r)) {
                if (++bad < 5) std::printf("outward ray re-hit at t=%g (error %g)\n", h2.t, h.error);
            }
            continue;
        }
        ++inward;
        const auto ref = ref_intersect(sc, Dv(r.origin), Dv(r.dir), 0, 1e30);
        if (!ref || !got || std::fabs(h2.t - ref->t) > 1e-3 * ref->t + 1e-5) {
            if (++bad < 5)
                std::printf("inward ray: got %d t=%g, ref t=%g (error %g)\n", int(got), got ? h2.t : -1.0f,
                            ref ? ref->t : -1.0, h.error);
        }
    }
    EXPECT_EQ(bad, 0);
    EXPECT_GT(hits, trials / 2);
    EXPECT_GT(inward, trials / 5);
}

scene::Scene single(Shape s) {
    scene::Scene sc;
    sc.shapes.push_back(std::move(s));
    return sc;
}

TEST(SelfIntersection, SphereAtOrigin) {
    check_convex_self_intersection(single(sphere({0, 0, 0}, 1)), 2000, 1);
}

TEST(SelfIntersection, SphereFarFromOrigin) {
    check_convex_self_intersection(single(sphere({1000, -500, 300}, 2)), 2000, 2);
}

TEST(SelfIntersection, TinySphere) {
    check_convex_self_intersection(single(sphere({5, 5, 5}, 0.01f)), 2000, 3);
}

TEST(SelfIntersection, Ellipsoid) {
    Sampler rng(4);
    Shape s = sphere({0, 0, 0}, 1);
    s.to_world = random_transform(rng, {3, -2, 10}, true);
    check_convex_self_intersection(single(s), 2000, 4);
}

TEST(SelfIntersection, CappedCylinderAndCone) {
    Sampler rng(5);
    Shape c = cylinder({1, 2, 3}, normalize(Vec3(1, 2, -1)), 0.7f, 2.0f, true);
    check_convex_self_intersection(single(c), 2000, 5);
    Shape k = cone({0, 0, 0}, {0, 1, 0}, 1.0f, 1.5f, true);
    k.to_world = random_transform(rng, {-20, 5, 0}, true);
    check_convex_self_intersection(single(k), 2000, 6);
}

TEST(SelfIntersection, TriangleMeshSphereAndBox) {
    Shape m = mesh_sphere({10, 0, -3}, 1.5f, 32, 16, false);
    check_convex_self_intersection(single(m), 2000, 7);
    Shape b = box({-1, -2, -0.5f}, {3, 1, 0.5f});
    Sampler rng(8);
    b.to_world = random_transform(rng, {100, 50, -70}, true);
    check_convex_self_intersection(single(b), 2000, 9);
}

TEST(SelfIntersection, InstancedSphere) {
    scene::Scene sc;
    scene::Object obj;
    obj.shapes.push_back(sphere({0.5f, 0, 0}, 1));
    sc.objects.push_back(obj);
    Sampler rng(10);
    sc.instances.push_back({0, random_transform(rng, {40, -30, 20}, true)});
    check_convex_self_intersection(sc, 2000, 10);
}

TEST(SelfIntersection, PlanarSurfacesNeverRehitThemselves) {
    Sampler rng(12);
    Shape q = quad({-5, 0.3f, -5}, {-5, 0.3f, 5}, {5, 0.3f, 5}, {5, 0.3f, -5});
    q.to_world = Transform::translate({200, 100, 0}) * Transform::rotate(33, {1, 2, 3});
    Shape d = disk({-3, 7, 2}, normalize(Vec3(0.3f, 1, 0.2f)), 4, 1);
    for (const Shape& s : {q, d}) {
        const scene::Scene sc = single(s);  // EmbreeScene keeps a reference to its scene
        const accel::EmbreeScene es(sc);
        int hits = 0;
        for (int k = 0; k < 2000; ++k) {
            accel::SurfaceHit h;
            if (!es.intersect(ray_at(rng, es.bounds()), h)) continue;
            ++hits;
            const Vec3 dir = random_unit(rng);
            EXPECT_FALSE(es.occluded(accel::spawn_ray(h, dir))) << "dir.ng = " << dot(dir, h.ng);
        }
        EXPECT_GT(hits, 500);
    }
}

// Floor quad at y = 0 plus a unit sphere resting on it at the origin.
void check_sphere_on_floor(const Shape& ball, int floor_index, scene::Scene sc) {
    const accel::EmbreeScene es(sc);
    Sampler rng(13);
    int tested = 0;
    for (int k = 0; k < 3000; ++k) {
        // A point on the floor 1e-6 .. 1e-1 away from the contact point, reached from below.
        const float rho = std::pow(10.0f, -6 + 5 * rng.next()), phi = 2 * kPi * rng.next();
        Ray probe{{rho * std::cos(phi), -1, rho * std::sin(phi)}, {0, 1, 0}};
        accel::SurfaceHit h;
        ASSERT_TRUE(es.intersect(probe, h));
        if (h.shape != floor_index) continue;  // the ball is (numerically) first at the contact
        ++tested;
        const Vec3 light = Vec3(0, 3, 0) + random_in(rng, Vec3(-0.3f, 0, -0.3f), Vec3(0.3f, 0, 0.3f));
        EXPECT_TRUE(es.occluded(accel::spawn_ray_to(h, light))) << "leak at rho " << rho;
    }
    EXPECT_GT(tested, 1000);
    // Far from the ball the same shadow rays reach the light.
    for (int k = 0; k < 500; ++k) {
        const float rho = 3 + 5 * rng.next(), phi = 2 * kPi * rng.next();
        accel::SurfaceHit h;
        ASSERT_TRUE(es.intersect({{rho * std::cos(phi), 1, rho * std::sin(phi)}, {0, -1, 0}}, h));
        EXPECT_FALSE(es.occluded(accel::spawn_ray_to(h, {0, 3, 0})));
    }
    (void)ball;
}

TEST(NoLeak, SphereRestingOnPlane) {
    scene::Scene sc;
    sc.shapes.push_back(quad({-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}));
    sc.shapes.push_back(sphere({0, 1, 0}, 1));
    check_sphere_on_floor(sc.shapes[1], 0, sc);
    // The same with a box slab as the floor and a tessellated ball.
    scene::Scene sc2;
    sc2.shapes.push_back(box({-10, -1, -10}, {10, 0, 10}));
    sc2.shapes.push_back(mesh_sphere({0, 1, 0}, 1, 64, 32, true));
    check_sphere_on_floor(sc2.shapes[1], 0, sc2);
}

TEST(NoLeak, WallsMeetingAtACorner) {
    scene::Scene sc;
    sc.shapes.push_back(quad({-5, 0, -5}, {-5, 0, 5}, {1, 0, 5}, {1, 0, -5}));  // floor, up
    sc.shapes.push_back(quad({1, 0, -5}, {1, 0, 5}, {1, 5, 5}, {1, 5, -5}));    // wall at x = 1
    const accel::EmbreeScene es(sc);
    Sampler rng(14);
    for (int k = 0; k < 3000; ++k) {
        const float gap = std::pow(10.0f, -6 + 4 * rng.next());
        accel::SurfaceHit h;
        ASSERT_TRUE(es.intersect({{1 - gap, 2, 4 * (2 * rng.next() - 1)}, {0, -1, 0}}, h));
        ASSERT_EQ(h.shape, 0);
        const Vec3 light(3, 0.05f + 2 * rng.next(), 4 * (2 * rng.next() - 1));
        EXPECT_TRUE(es.occluded(accel::spawn_ray_to(h, light))) << "leak at gap " << gap;
    }
}

// Random walks inside a closed shape (`inside` gives local interior points, `edge` local points on
// its edges or rims): every ray must hit the shape again, none may escape through an edge.
template <class Inside, class Edge>
void check_closed(const Shape& s, Inside inside, Edge edge, Sampler& rng) {
    const scene::Scene sc = single(s);  // EmbreeScene keeps a reference to its scene
    const accel::EmbreeScene es(sc);
    int bounces = 0, escapes = 0;
    for (int path = 0; path < 300; ++path) {
        // Start inside, aiming straight at an edge or corner every other path.
        const Vec3 lo = inside(), lt = path % 2 ? edge() : inside();
        Ray ray{s.to_world.point(lo), s.to_world.point(lt) - s.to_world.point(lo)};
        EXPECT_TRUE(es.occluded(ray));
        for (int bounce = 0; bounce < 20; ++bounce) {
            accel::SurfaceHit h;
            if (!es.intersect(ray, h)) {
                ++escapes;
                break;
            }
            ++bounces;
            // Inside is opposite to the outward normal.
            Vec3 dir = random_unit(rng);
            if (dot(dir, h.ng) > 0) dir = -dir;
            ray = accel::spawn_ray(h, dir);
        }
    }
    EXPECT_EQ(escapes, 0);
    EXPECT_EQ(bounces, 300 * 20);
}

TEST(NoLeak, InsideClosedShapesNothingEscapes) {
    Sampler rng(15);
    auto sign = [&] { return rng.next() < 0.5f ? -1.0f : 1.0f; };
    for (int variant = 0; variant < 2; ++variant) {
        const Transform tf = variant ? random_transform(rng, {30, -10, 5}, true) : Transform();
        Shape b = box({-1, -1, -1}, {1, 1, 1});
        b.to_world = tf;
        check_closed(
            b, [&] { return random_in(rng, Vec3(-0.9f), Vec3(0.9f)); },
            [&] {  // on an edge, sometimes a corner
                Vec3 p = random_in(rng, Vec3(-1.0f), Vec3(1.0f));
                p.x = sign(), p.y = sign();
                if (rng.next() < 0.3f) p.z = sign();
                return p;
            },
            rng);
        Shape c = cylinder({0, 0, 0}, {0, 1, 0}, 1, 2, true);
        c.to_world = tf;
        Shape k = cone({0, 0, 0}, {0, 1, 0}, 1, 2, true);
        k.to_world = tf;
        for (const Shape& s : {c, k}) {
            const bool is_cone = s.kind == Shape::Kind::Cone;
            check_closed(
                s,
                [&] {
                    const float y = 1.8f * rng.next() - 0.9f,
                                r = 0.9f * std::sqrt(rng.next()) * (is_cone ? (1 - y) / 2 : 1);
                    const float ph = 2 * kPi * rng.next();
                    return Vec3(r * std::cos(ph), y, r * std::sin(ph));
                },
                [&] {  // on the rim of a cap
                    const float ph = 2 * kPi * rng.next(), y = is_cone ? -1.0f : sign();
                    return Vec3(std::cos(ph), y, std::sin(ph));
                },
                rng);
        }
    }
}

TEST(Spawn, ShadowRaysStopShortOfTheirTarget) {
    scene::Scene sc;
    sc.shapes.push_back(quad({-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}));  // floor
    sc.shapes.push_back(quad({-1, 4, -1}, {1, 4, -1}, {1, 4, 1}, {-1, 4, 1}));  // light, down
    const accel::EmbreeScene es(sc);
    Sampler rng(16);
    for (int k = 0; k < 1000; ++k) {
        accel::SurfaceHit floor_hit, light_hit;
        ASSERT_TRUE(es.intersect({{8 * rng.next() - 4, 1, 8 * rng.next() - 4}, {0, -1, 0}}, floor_hit));
        ASSERT_TRUE(
            es.intersect({{1.8f * rng.next() - 0.9f, 3, 1.8f * rng.next() - 0.9f}, {0, 1, 0}}, light_hit));
        ASSERT_EQ(light_hit.shape, 1);
        const Ray to = accel::spawn_ray_to(floor_hit, light_hit.p);
        EXPECT_LT(to.tmax, 1.0f);
        EXPECT_FALSE(es.occluded(to));
        EXPECT_FALSE(es.occluded(accel::spawn_ray_between(floor_hit, light_hit)));
        EXPECT_FALSE(es.occluded(accel::spawn_ray_between(light_hit, floor_hit)));
    }
    // With a blocker in between, the same queries are occluded.
    sc.shapes.push_back(sphere({0, 2, 0}, 0.5f));
    const accel::EmbreeScene blocked(sc);
    accel::SurfaceHit f, l;
    ASSERT_TRUE(blocked.intersect({{0, 1, 0.01f}, {0, -1, 0}}, f));
    ASSERT_TRUE(blocked.intersect({{0, 4.5f, 0}, {0, -1, 0}}, l));
    EXPECT_EQ(l.shape, 1);
    EXPECT_TRUE(blocked.occluded(accel::spawn_ray_to(f, l.p)));
    EXPECT_TRUE(blocked.occluded(accel::spawn_ray_between(f, l)));
}

// offset_origin (SSE selects) against its one-coordinate-at-a-time reference, to the bit: random
// hits and directions, and the values where next_float's cases part (zeros of both signs, the
// ends +-kInf and beyond, denormals, NaN, axis-aligned normals, no error bound).
TEST(OffsetOrigin, LanesGiveTheReferenceBits) {
    Sampler rng(91);
    const float special[] = {0.0f,
                             -0.0f,
                             kInf,
                             -kInf,
                             2e30f,
                             -3e30f,
                             1e-40f,
                             -1e-40f,
                             1.0f,
                             -1.0f,
                             1e-7f,
                             std::numeric_limits<float>::quiet_NaN(),
                             std::numeric_limits<float>::infinity()};
    const auto pick = [&](float scale) {
        const float u = rng.next();
        if (u < 0.3f) return special[size_t(rng.next() * 12.999f)];
        return (rng.next() * 2 - 1) * scale;
    };
    int differ = 0, nudged = 0;
    for (int k = 0; k < 400000; ++k) {
        accel::SurfaceHit h;
        const float scale = std::ldexp(1.0f, int(rng.next() * 80) - 40);
        h.p = Vec3(pick(scale), pick(scale), pick(scale));
        if (rng.next() < 0.3f) {
            const int axis = int(rng.next() * 2.999f);
            h.ng = Vec3(0.0f);
            h.ng[axis] = rng.next() < 0.5f ? 1.0f : -1.0f;
            if (rng.next() < 0.3f) h.ng[(axis + 1) % 3] = -0.0f;
        } else {
            h.ng = random_unit(rng);
        }
        h.error = rng.next() < 0.1f ? 0.0f : rng.next() * 1e-3f * scale;
        const Vec3 dir = rng.next() < 0.05f ? Vec3(pick(1.0f), pick(1.0f), pick(1.0f)) : random_unit(rng);
        if (rng.next() < 0.1f) {
            // A coordinate that the offset takes exactly to zero (next_float's zero case).
            const float d = h.error * (std::fabs(h.ng.x) + std::fabs(h.ng.y) + std::fabs(h.ng.z));
            const int i = int(rng.next() * 2.999f);
            const float o = h.ng[i] * d;
            h.p[i] = dot(dir, h.ng) < 0 ? o : -o;
        }
        const Vec3 a = accel::offset_origin(h, dir), b = accel::offset_origin_reference(h, dir);
        differ += std::memcmp(&a, &b, sizeof a) != 0;
        nudged += std::memcmp(&b, &h.p, sizeof b) != 0;
    }
    EXPECT_EQ(differ, 0);
    EXPECT_GT(nudged, 200000);  // the cases above do move most points
}

}  // namespace
}  // namespace phos::testing
