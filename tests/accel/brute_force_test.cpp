// Embree against the brute-force reference intersector on a random scene holding every shape kind,
// transformed (rotation, non-uniform scale, mirroring) and instanced: hit/miss, shape, t, normal,
// point, and occlusion queries must agree ray by ray.
#include "accel/brute_force.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <string>

#include "accel/embree_scene.h"
#include "accel/scene_builders.h"

namespace phos::testing {
namespace {

using scene::Shape;

// Soup of random triangles inside a unit-ish cube around `c`.
Shape triangle_soup(Sampler& rng, Vec3 c, int n) {
    Shape s;
    s.kind = Shape::Kind::Mesh;
    for (int i = 0; i < 3 * n; ++i) {
        s.mesh.positions.push_back(c + random_in(rng, Vec3(-1.5f), Vec3(1.5f)));
        s.mesh.indices.push_back(uint32_t(i));
    }
    return s;
}

struct RandomScene {
    scene::Scene scene;
    std::vector<Vec3> targets;  // world-space points near geometry, to aim rays at
};

RandomScene make_random_scene(uint64_t seed) {
    Sampler rng(seed);
    RandomScene rs;
    scene::Scene& sc = rs.scene;
    auto pos = [&] { return random_in(rng, Vec3(-8.0f), Vec3(8.0f)); };
    auto add = [&](Shape s, Vec3 target) {
        s.material = int(sc.shapes.size());
        sc.shapes.push_back(std::move(s));
        rs.targets.push_back(target);
    };
    for (int i = 0; i < 4; ++i) {
        const Vec3 c = pos();
        add(sphere(c, 0.3f + rng.next()), c);
    }
    for (int i = 0; i < 3; ++i) {  // ellipsoids: rotated, non-uniformly scaled; one mirrored
        const Vec3 c = pos();
        Shape s = sphere(Vec3(0.2f, -0.1f, 0.3f), 0.5f + rng.next());
        s.to_world = random_transform(rng, c, true);
        if (i == 2) s.to_world = s.to_world * Transform::scale({-1, 1, 1});
        add(s, s.to_world.point(s.center));
    }
    for (int i = 0; i < 3; ++i) {
        const Vec3 c = pos();
        Shape s = disk(c, random_unit(rng), 0.5f + rng.next(), i == 0 ? 0.3f : 0.0f);
        if (i == 2) {
            s.center = Vec3(0.0f);
            s.to_world = random_transform(rng, c, true);
        }
        add(s, c);
    }
    for (int i = 0; i < 4; ++i) {
        const Vec3 c = pos();
        Shape s = cylinder(c, random_unit(rng), 0.3f + 0.7f * rng.next(), 0.5f + 2 * rng.next(), i % 2 == 0);
        if (i == 3) {
            s.center = Vec3(0.0f);
            s.to_world = random_transform(rng, c, true);
            s.reverse_orientation = true;
        }
        add(s, c);
    }
    for (int i = 0; i < 4; ++i) {
        const Vec3 c = pos();
        Shape s = cone(c, random_unit(rng), 0.3f + 0.7f * rng.next(), 0.5f + 2 * rng.next(), i != 1);
        if (i == 3) {
            s.center = Vec3(0.0f);
            s.to_world = random_transform(rng, c, true);
        }
        add(s, c);
    }
    for (int i = 0; i < 3; ++i) {
        const Vec3 c = pos();
        Shape s = box(Vec3(-0.5f, -0.3f, -0.8f), Vec3(0.6f, 0.4f, 0.2f));
        s.to_world = i == 0 ? Transform::translate(c) : random_transform(rng, c, true);
        if (i == 2) s.to_world = s.to_world * Transform::scale({1, -1, 1});
        add(s, c);
    }
    {
        const Vec3 c = pos();
        Shape s = mesh_sphere(Vec3(0.0f), 1.2f, 24, 12, true);
        s.to_world = random_transform(rng, c, true);
        add(s, c);
        Shape r = mesh_sphere(Vec3(0.0f), 0.8f, 16, 8, false);
        r.reverse_orientation = true;
        r.to_world = Transform::translate(pos());
        add(r, r.to_world.point(Vec3(0.0f)));
        Shape soup = triangle_soup(rng, Vec3(0.0f), 30);
        const Vec3 c2 = pos();
        soup.to_world = random_transform(rng, c2, true);
        add(soup, c2);
        add(quad({-12, -9, -12}, {-12, -9, 12}, {12, -9, 12}, {12, -9, -12}), {0, -9, 0});
    }
    // An object of mixed shapes, placed three times (one placement mirrored and squashed).
    scene::Object obj;
    obj.name = "cluster";
    obj.shapes.push_back(sphere({0.5f, 0, 0}, 0.5f));
    obj.shapes.push_back(box({-1, -0.2f, -0.5f}, {0, 0.4f, 0.5f}));
    obj.shapes.push_back(cone({0, 0.8f, 0}, {0, 1, 0}, 0.4f, 0.8f));
    obj.shapes.push_back(cylinder({0, -0.6f, 0.6f}, {1, 0, 0}, 0.2f, 1.2f, true));
    obj.shapes.push_back(triangle_soup(rng, Vec3(0.0f), 8));
    obj.shapes.back().to_world = Transform::scale({0.5f, 0.5f, 0.5f});
    sc.objects.push_back(obj);
    for (int i = 0; i < 3; ++i) {
        scene::Instance inst;
        const Vec3 c = pos();
        inst.to_world = random_transform(rng, c, i > 0);
        if (i == 2) inst.to_world = inst.to_world * Transform::scale({1, 1, -1});
        sc.instances.push_back(inst);
        rs.targets.push_back(c);
    }
    return rs;
}

TEST(BruteForce, EmbreeAgreesWithReferenceOnRandomRays) {
    const RandomScene rs = make_random_scene(7);
    const accel::EmbreeScene es(rs.scene);
    Sampler rng(11);
    const int kRays = 6000;
    int hits = 0, failures = 0, analytic_hits = 0, instance_hits = 0;
    for (int k = 0; k < kRays; ++k) {
        Ray ray;
        const int mode = k % 5;
        const Vec3 target =
            rs.targets[rng.next_index(uint32_t(rs.targets.size()))] + random_in(rng, Vec3(-1.0f), Vec3(1.0f));
        if (mode == 0) {  // anywhere, any direction
            ray.origin = random_in(rng, Vec3(-12.0f), Vec3(12.0f));
            ray.dir = random_unit(rng);
        } else if (mode == 1 || mode == 2) {  // aimed at geometry, unnormalised direction
            ray.origin = random_in(rng, Vec3(-12.0f), Vec3(12.0f));
            ray.dir = (target - ray.origin) * (0.01f + 3 * rng.next());
        } else if (mode == 3) {  // from far away
            ray.origin = target + random_unit(rng) * 5000.0f;
            ray.dir = normalize(target - ray.origin);
        } else {  // restricted interval
            ray.origin = random_in(rng, Vec3(-12.0f), Vec3(12.0f));
            ray.dir = normalize(target - ray.origin);
            ray.tmin = 8 * rng.next();
            ray.tmax = ray.tmin + 10 * rng.next();
        }
        const Dv o(ray.origin), d(ray.dir);
        const auto ref = ref_intersect(rs.scene, o, d, ray.tmin, ray.tmax);
        accel::SurfaceHit hit;
        const bool got = es.intersect(ray, hit);
        bool ok = got == ref.has_value() && es.occluded(ray) == got;
        if (ok && got) {
            ++hits;
            const double tol = 1e-5 * std::max(1.0, ref->t);
            const bool same = hit.shape == ref->shape && hit.instance == ref->instance;
            if (!same) {
                // Only a genuine tie (two surfaces at the same distance) may differ.
                ok = std::fabs(hit.t - ref->t) < tol;
            } else {
                ok = std::fabs(hit.t - ref->t) < tol && dotd(Dv(hit.ng), ref->n) > 0.999;
                if (hit.instance >= 0) ++instance_hits;
                const Shape& s = hit.instance >= 0 ? rs.scene.objects[0].shapes[size_t(hit.shape)]
                                                   : rs.scene.shapes[size_t(hit.shape)];
                if (s.kind != Shape::Kind::Mesh && s.kind != Shape::Kind::Box) ++analytic_hits;
            }
            const Dv pr = o + d * ref->t;
            const Dv dp = Dv(hit.p) - pr;
            // A float ray is itself only known to a few ulps of |origin| + t |dir|.
            const double scale = std::sqrt(dotd(o, o)) + ref->t * std::sqrt(dotd(d, d));
            ok = ok && std::sqrt(dotd(dp, dp)) < 1e-5 * (std::sqrt(dotd(pr, pr)) + 1) + 1e-6 * scale;
            ok = ok && std::fabs(length(hit.ng) - 1) < 1e-5 && std::fabs(length(hit.ns) - 1) < 1e-5;
            // Nothing lies in front of the closest hit; the hit itself blocks a slightly longer ray.
            Ray shorter = ray, longer = ray;
            shorter.tmax = float(ref->t * (1 - 1e-4));
            longer.tmax = float(ref->t * (1 + 1e-4));
            ok = ok && (shorter.tmax <= shorter.tmin || !es.occluded(shorter)) && es.occluded(longer);
        }
        if (!ok) {
            if (++failures <= 40) {
                const Dv pr = ref ? o + d * ref->t : Dv();
                const Dv dp = Dv(hit.p) - pr;
                std::printf(
                    "ray %d mode %d: embree %s shape %d inst %d t %.9g | ref %s shape %d inst %d t %.9g "
                    "dn %.6f dp %.3g occ %d\n",
                    k, mode, got ? "hit" : "miss", hit.shape, hit.instance, hit.t, ref ? "hit" : "miss",
                    ref ? ref->shape : -1, ref ? ref->instance : -1, ref ? ref->t : 0.0,
                    ref ? dotd(Dv(hit.ng), ref->n) : 0.0, std::sqrt(dotd(dp, dp)), int(es.occluded(ray)));
            }
        }
    }
    std::printf("hits %d analytic %d instance %d of %d\n", hits, analytic_hits, instance_hits, kRays);
    EXPECT_EQ(failures, 0);
    // The comparison is only meaningful if many rays hit, analytic shapes and instances included.
    EXPECT_GT(hits, kRays / 3);
    EXPECT_GT(analytic_hits, kRays / 10);
    EXPECT_GT(instance_hits, kRays / 100);
}

// The packet query (intersect16, for the photon tracer's wavefront) must give exactly the hits of
// single-ray queries, field by field and bit for bit, on the same random scene of every shape kind
// and instances, with partly filled packets and unusable rays among them (a zero direction, an empty
// interval, a NaN origin, an infinite direction, coordinates beyond Embree's range, a NaN end of the
// interval: Embree asserted on the last two, and Debian's Embree keeps its assertions); with the
// kernels Embree picks for this CPU and with those of CPUs without AVX-512 (whose packets of 16 run
// as two halves of 8: lanes left out once held garbage there, and Debian's Embree aborted on its
// assertion that every ray of a half is finite).
class PacketKernels : public ::testing::TestWithParam<const char*> {};

TEST_P(PacketKernels, PacketHitsEqualSingleRayHits) {
    const RandomScene rs = make_random_scene(7);
    const accel::EmbreeScene es(rs.scene, GetParam());
    Sampler rng(12);
    int hits = 0, analytic_hits = 0, mismatches = 0;
    for (int round = 0; round < 600; ++round) {
        const int n = 1 + int(rng.next_index(16));
        Ray rays[16];
        for (int k = 0; k < n; ++k) {
            const Vec3 target = rs.targets[rng.next_index(uint32_t(rs.targets.size()))] +
                                random_in(rng, Vec3(-1.0f), Vec3(1.0f));
            rays[k].origin = random_in(rng, Vec3(-12.0f), Vec3(12.0f));
            rays[k].dir =
                rng.next() < 0.5f ? random_unit(rng) : (target - rays[k].origin) * (0.1f + rng.next());
            if (k == 3 && round % 7 == 0) rays[k].dir = Vec3(0.0f);
            if (k == 4 && round % 5 == 0) rays[k].tmax = 0.0f;
            if (k == 5 && round % 11 == 0) rays[k].origin.y = std::numeric_limits<float>::quiet_NaN();
            if (k == 6 && round % 13 == 0) rays[k].dir.z = std::numeric_limits<float>::infinity();
            // Finite but beyond what Embree traces (it asserts), and a NaN end of the interval.
            if (k == 7 && round % 17 == 0) rays[k].origin.x = 1e20f;
            if (k == 8 && round % 19 == 0) rays[k].dir.y = -2e18f;
            if (k == 9 && round % 23 == 0) rays[k].tmax = std::numeric_limits<float>::quiet_NaN();
            if (k == 10 && round % 29 == 0) rays[k].tmin = std::numeric_limits<float>::quiet_NaN();
        }
        accel::SurfaceHit packet[16];
        bool found[16];
        es.intersect16(rays, n, packet, found);
        for (int k = 0; k < n; ++k) {
            accel::SurfaceHit single;
            const bool got = es.intersect(rays[k], single);
            bool same = got == found[k];
            if (same && got) {
                ++hits;
                const accel::SurfaceHit& h = packet[k];
                same = h.t == single.t && h.p == single.p && h.ng == single.ng && h.ns == single.ns &&
                       h.uv == single.uv && h.dpdu == single.dpdu && h.shape == single.shape &&
                       h.instance == single.instance && h.primitive == single.primitive &&
                       h.material == single.material && h.error == single.error;
                const Shape& s = h.instance >= 0 ? rs.scene.objects[0].shapes[size_t(h.shape)]
                                                 : rs.scene.shapes[size_t(h.shape)];
                if (s.kind != Shape::Kind::Mesh && s.kind != Shape::Kind::Box) ++analytic_hits;
            }
            mismatches += !same;
        }
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(hits, 1500);
    EXPECT_GT(analytic_hits, 300);
}

// Rays beyond Embree's range hit nothing, in every query, though the scene lies on their path
// (the process says so once: Cli.CameraBeyondEmbreesRangeRendersAndSaysSo).
TEST(BruteForce, RaysBeyondEmbreesRangeMiss) {
    const RandomScene rs = make_random_scene(8);
    const accel::EmbreeScene es(rs.scene);
    accel::SurfaceHit hit;
    const Ray reach{Vec3(0, 0, 1e18f), Vec3(0, 0, -1)}, far{Vec3(0, 0, 1e20f), Vec3(0, 0, -1)};
    int reached = 0;
    for (const Vec3& t : rs.targets) {
        const Ray r{reach.origin, t - reach.origin};
        reached += es.intersect(r, hit);
    }
    ASSERT_GT(reached, 0);  // within range, the scene is hit from that far
    for (const Vec3& t : rs.targets) {
        const Ray r{far.origin, t - far.origin};
        EXPECT_FALSE(es.intersect(r, hit));
        EXPECT_FALSE(es.occluded(r));
        Ray packet[2] = {r, reach};
        accel::SurfaceHit hits[2];
        bool found[2];
        es.intersect16(packet, 2, hits, found);
        EXPECT_FALSE(found[0]);
    }
}

std::string kernels_name(const ::testing::TestParamInfo<const char*>& info) {
    return info.param ? std::string(info.param + 4) == "avx2" ? "Avx2" : "Sse42" : "Best";
}
INSTANTIATE_TEST_SUITE_P(BruteForce, PacketKernels, ::testing::Values(nullptr, "isa=avx2", "isa=sse4.2"),
                         kernels_name);

}  // namespace
}  // namespace phos::testing
