// SurfaceHit contents: normals and orientation rules (reverse_orientation, mirroring, shading
// normals), uv and tangents of every shape kind, instance/shape ids, bounds, and input errors.
#include <gtest/gtest.h>

#include <thread>

#include "accel/embree_scene.h"
#include "accel/scene_builders.h"
#include "core/error.h"
#include "core/log.h"

namespace phos::testing {
namespace {

using scene::Shape;

scene::Scene single(Shape s) {
    scene::Scene sc;
    sc.shapes.push_back(std::move(s));
    return sc;
}

accel::SurfaceHit hit_of(const scene::Scene& sc, Ray ray) {
    const accel::EmbreeScene es(sc);
    accel::SurfaceHit h;
    EXPECT_TRUE(es.intersect(ray, h));
    return h;
}

void expect_vec(Vec3 a, Vec3 b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Surface, SphereHitFieldsAndLongitudeLatitudeUv) {
    Shape s = sphere({1, 2, 3}, 2, 4);
    s.area_light = 7;
    s.media = {1, 2};
    const scene::Scene sc = single(s);
    const accel::EmbreeScene es(sc);
    accel::SurfaceHit h;
    ASSERT_TRUE(es.intersect({{1, 2, 10}, {0, 0, -1}}, h));
    EXPECT_NEAR(h.t, 5, 1e-5);
    expect_vec(h.p, {1, 2, 5});
    expect_vec(h.ng, {0, 0, 1});
    expect_vec(h.ns, {0, 0, 1});
    EXPECT_EQ(h.shape, 0);
    EXPECT_EQ(h.instance, -1);
    EXPECT_EQ(h.primitive, 0);
    EXPECT_EQ(h.material, 4);
    EXPECT_EQ(h.area_light, 7);
    EXPECT_EQ(h.media.inside, 1);
    EXPECT_EQ(h.media.outside, 2);
    EXPECT_GT(h.error, 0);
    EXPECT_LT(h.error, 1e-4f);
    EXPECT_NEAR(length(h.dpdu), 1, 1e-5);
    EXPECT_NEAR(dot(h.dpdu, h.ng), 0, 1e-5);
    // Pole along the shape's axis (+y by default): v = theta / pi from the +axis pole, u = phi / 2pi
    // measured in the frame (s, t) = (+x, -z) around +y.
    EXPECT_NEAR(h.uv.x, 0.75f, 1e-5);
    EXPECT_NEAR(h.uv.y, 0.5f, 1e-5);
    ASSERT_TRUE(es.intersect({{1, 10, 3}, {0, -1, 0}}, h));
    EXPECT_NEAR(h.uv.y, 0, 1e-5);
    ASSERT_TRUE(es.intersect({{1, -10, 3}, {0, 1, 0}}, h));
    EXPECT_NEAR(h.uv.y, 1, 1e-5);
    ASSERT_TRUE(es.intersect({{10, 2, 3}, {-1, 0, 0}}, h));
    EXPECT_NEAR(h.uv.x, 0, 1e-5);
    EXPECT_NEAR(h.uv.y, 0.5f, 1e-5);
    expect_vec(h.dpdu, {0, 0, -1});  // increasing phi from +x goes towards t = -z
    // With a +z pole, u is pbrt's phi = atan2(y, x) / 2pi.
    Shape z = sphere({0, 0, 0}, 1);
    z.axis = {0, 0, 1};
    const accel::SurfaceHit hz = hit_of(single(z), {{0, 5, 0}, {0, -1, 0}});
    EXPECT_NEAR(hz.uv.x, 0.25f, 1e-5);
    EXPECT_NEAR(hz.uv.y, 0.5f, 1e-5);
}

TEST(Surface, RayIntervalIsRespected) {
    const scene::Scene sc = single(sphere({0, 0, 0}, 2));
    const accel::EmbreeScene es(sc);
    accel::SurfaceHit h;
    EXPECT_FALSE(es.intersect({{0, 0, 7}, {0, 0, -1}, 0, 4.9f}, h));
    EXPECT_FALSE(es.occluded({{0, 0, 7}, {0, 0, -1}, 0, 4.9f}));
    ASSERT_TRUE(es.intersect({{0, 0, 7}, {0, 0, -1}, 5.1f, kInf}, h));
    EXPECT_NEAR(h.t, 9, 1e-5);
    expect_vec(h.ng, {0, 0, -1});  // the far side, still outward
    // t is in units of |dir|.
    ASSERT_TRUE(es.intersect({{0, 0, 7}, {0, 0, -10}}, h));
    EXPECT_NEAR(h.t, 0.5f, 1e-6);
    EXPECT_FALSE(es.intersect({{0, 0, 7}, {0, 0, 0}}, h));  // degenerate direction: no hit
}

TEST(Orientation, ReverseOrientationAndMirroringFlipAnalyticNormals) {
    const Ray ray{{0, 0, 5}, {0, 0, -1}};
    Shape s = sphere({0, 0, 0}, 1);
    expect_vec(hit_of(single(s), ray).ng, {0, 0, 1});
    s.reverse_orientation = true;
    expect_vec(hit_of(single(s), ray).ng, {0, 0, -1});
    expect_vec(hit_of(single(s), ray).ns, {0, 0, -1});
    // A handedness-swapping transform flips as in pbrt; both together cancel.
    s.to_world = Transform::scale({-1, 1, 1});
    expect_vec(hit_of(single(s), ray).ng, {0, 0, 1});
    s.reverse_orientation = false;
    expect_vec(hit_of(single(s), ray).ng, {0, 0, -1});
}

TEST(Orientation, TriangleWindingReverseAndMirror) {
    // Counter-clockwise seen from +y: the front faces up.
    Shape q = quad({-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});
    const Ray down{{0.2f, 3, 0.1f}, {0, -1, 0}}, up{{0.2f, -3, 0.1f}, {0, 1, 0}};
    expect_vec(hit_of(single(q), down).ng, {0, 1, 0});
    expect_vec(hit_of(single(q), up).ng, {0, 1, 0});  // geometric: not turned towards the ray
    Shape r = q;
    r.reverse_orientation = true;
    expect_vec(hit_of(single(r), down).ng, {0, -1, 0});
    // pbrt: the world-space winding normal flips when the transform swaps handedness, i.e. the
    // normal is the object-space normal carried over by the normal transform.
    Shape m = q;
    m.to_world = Transform::scale({1, -1, 1});  // winding unchanged, object normal -> -y
    expect_vec(hit_of(single(m), down).ng, {0, -1, 0});
    m.to_world = Transform::scale({-1, 1, 1});  // winding reversed, object normal stays +y
    expect_vec(hit_of(single(m), down).ng, {0, 1, 0});
    // The box, a triangle mesh, stays outward under mirroring.
    Shape b = box({-1, -1, -1}, {1, 1, 1});
    b.to_world = Transform::scale({-2, 1, 1});
    expect_vec(hit_of(single(b), {{5, 0.1f, 0.2f}, {-1, 0, 0}}).ng, {1, 0, 0});
    expect_vec(hit_of(single(b), {{0.1f, 0.2f, -5}, {0, 0, 1}}).ng, {0, 0, -1});
}

TEST(Orientation, ShadingNormalsOrientTheGeometricNormal) {
    Shape q = quad({-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});
    q.mesh.normals.assign(4, Vec3(0, -1, 0));
    const Ray down{{0.2f, 3, 0.1f}, {0, -1, 0}};
    accel::SurfaceHit h = hit_of(single(q), down);
    expect_vec(h.ng, {0, -1, 0});
    expect_vec(h.ns, {0, -1, 0});
    // Varying normals are interpolated barycentrically and normalised.
    const Vec3 n0 = normalize(Vec3(0.5f, 1, 0)), n1 = normalize(Vec3(0, 1, 0.5f));
    const Vec3 n2 = normalize(Vec3(-0.5f, 1, 0)), n3 = normalize(Vec3(0, 1, -0.5f));
    q.mesh.normals = {n0, n1, n2, n3};
    // (0.5, 0, 0.75) lies on triangle 0 (v0 v1 v2): p = v0 + b1 (v1 - v0) + b2 (v2 - v0)
    // = (-1 + 2 b2, 0, -1 + 2 b1 + 2 b2), so b2 = 0.75 and b1 = 0.125.
    h = hit_of(single(q), {{0.5f, 3, 0.75f}, {0, -1, 0}});
    ASSERT_EQ(h.primitive, 0);
    const float b2 = 0.75f, b1 = (0.75f + 1) / 2 - b2, b0 = 1 - b1 - b2;
    expect_vec(h.ns, normalize(n0 * b0 + n1 * b1 + n2 * b2));
    EXPECT_NEAR(h.uv.x, b1, 1e-5);  // no mesh uvs: barycentrics
    EXPECT_NEAR(h.uv.y, b2, 1e-5);
    expect_vec(h.ng, {0, 1, 0});
    // The same under a rotation: normals follow the normal transform.
    q.to_world = Transform::rotate(90, {0, 0, 1});  // +y -> -x
    h = hit_of(single(q), {{-3, 0.5f, 0.75f}, {1, 0, 0}});
    expect_vec(h.ng, {-1, 0, 0});
    const Vec3 ns = normalize(n0 * b0 + n1 * b1 + n2 * b2);
    expect_vec(h.ns, {-ns.y, ns.x, ns.z});
}

TEST(Surface, MeshUvAndTangent) {
    Shape q = quad({-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});
    q.mesh.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};  // u along +x, v along +z
    const accel::SurfaceHit h = hit_of(single(q), {{0.5f, 3, -0.25f}, {0, -1, 0}});
    EXPECT_NEAR(h.uv.x, 0.75f, 1e-5);
    EXPECT_NEAR(h.uv.y, 0.375f, 1e-5);
    expect_vec(h.dpdu, {1, 0, 0});
    EXPECT_GE(h.primitive, 0);
    EXPECT_LT(h.primitive, 2);
}

// Hits on flat top-level triangles carry the BSDF's shading frame, kept per triangle: it must be
// the frame shading_frame() builds from the hit's own ng, ns and dpdu, to the bit (the BSDF uses
// it instead); meshes with normals, analytic shapes and instanced triangles carry none.
TEST(Surface, FlatTrianglesCarryTheirShadingFrame) {
    scene::Scene sc;
    Shape b = box({-1, -1, -1}, {1, 1, 1});
    b.to_world = Transform::rotate(30, {1, 2, 3}) * Transform::scale({-2, 1, 0.5f});
    b.reverse_orientation = true;
    sc.shapes.push_back(b);
    Shape q = quad({-3, -2, -3}, {-3, -2, 3}, {3, -2.5f, 3}, {3, -2, -3});
    q.mesh.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0.2f}};
    sc.shapes.push_back(q);
    sc.shapes.push_back(mesh_sphere({0, 2.5f, 0}, 0.7f, 12, 8, true));
    sc.shapes.push_back(sphere({2.5f, 0, 0}, 0.5f));
    scene::Object obj;
    obj.shapes.push_back(box({-0.3f, -0.3f, -0.3f}, {0.3f, 0.3f, 0.3f}));
    sc.objects.push_back(obj);
    sc.instances.push_back({0, Transform::translate({-2.5f, 0, 0})});
    const accel::EmbreeScene es(sc);
    Sampler rng(17);
    int with = 0, without = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 o = random_unit(rng) * 8.0f;
        const Vec3 to = random_in(rng, {-3, -3, -3}, {3, 3, 3});
        accel::SurfaceHit h;
        if (!es.intersect({o, to - o}, h)) continue;
        const bool flat_mesh = h.instance < 0 && h.shape <= 1;
        ASSERT_EQ(h.shading != nullptr, flat_mesh) << "shape " << h.shape << " instance " << h.instance;
        if (!h.shading) {
            ++without;
            continue;
        }
        ++with;
        const ShadingFrame f = shading_frame(h.ng, h.ns, h.dpdu);
        ASSERT_EQ(h.shading->ng, f.ng);
        ASSERT_EQ(h.shading->frame.s, f.frame.s);
        ASSERT_EQ(h.shading->frame.t, f.frame.t);
        ASSERT_EQ(h.shading->frame.n, f.frame.n);
    }
    EXPECT_GT(with, 2000);
    EXPECT_GT(without, 800);
}

// The accelerator keeps per-triangle constants for the scene's first 2^20 triangles only; a mesh
// beyond them computes the same constants at each hit, so its hits must equal those of the same
// mesh kept (every field but the shading frame, which only kept triangles carry).
TEST(Surface, TrianglesBeyondTheKeptOnesGiveTheSameHits) {
    Shape filler;  // 2^20 - 1 triangles, far away from the rays below
    filler.kind = Shape::Kind::Mesh;
    const uint32_t n = (1u << 20) - 1;
    for (uint32_t i = 0; i < n; ++i) {
        const float x = 100 + float(i % 1024) * 0.01f, z = float(i / 1024) * 0.01f;
        filler.mesh.positions.insert(filler.mesh.positions.end(),
                                     {{x, 0, z}, {x + 0.01f, 0, z}, {x, 0, z + 0.01f}});
        filler.mesh.indices.insert(filler.mesh.indices.end(), {3 * i, 3 * i + 2, 3 * i + 1});
    }
    Shape target = mesh_sphere({0, 0, 0}, 1, 16, 12, false);
    target.mesh.uvs.clear();
    Shape target_uv = quad({-3, -2, -3}, {-3, -2, 3}, {3, -2.5f, 3}, {3, -2, -3});
    target_uv.mesh.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0.2f}};
    scene::Scene beyond, kept;
    beyond.shapes = {filler, target, target_uv};
    kept.shapes = {Shape(), target, target_uv};  // the same shape indices, without the filler
    kept.shapes[0] = sphere({100, 100, 100}, 0.1f);
    const accel::EmbreeScene a(beyond), b(kept);
    Sampler rng(23);
    int hits = 0;
    for (int i = 0; i < 5000; ++i) {
        const Vec3 o = random_unit(rng) * 6.0f;
        const Vec3 to = random_in(rng, {-2, -2.5f, -2}, {2, 1, 2});
        accel::SurfaceHit ha, hb;
        const bool fa = a.intersect({o, to - o}, ha), fb = b.intersect({o, to - o}, hb);
        ASSERT_EQ(fa, fb);
        if (!fa || ha.shape == 0) continue;
        ++hits;
        EXPECT_EQ(ha.shading, nullptr);
        ASSERT_NE(hb.shading, nullptr);
        ASSERT_EQ(ha.p, hb.p);
        ASSERT_EQ(ha.ng, hb.ng);
        ASSERT_EQ(ha.ns, hb.ns);
        ASSERT_EQ(ha.dpdu, hb.dpdu);
        ASSERT_EQ(ha.uv, hb.uv);
        ASSERT_EQ(ha.t, hb.t);
        ASSERT_EQ(ha.error, hb.error);
        ASSERT_EQ(ha.primitive, hb.primitive);
        ASSERT_EQ(ha.shape, hb.shape);
    }
    EXPECT_GT(hits, 3000);
}

TEST(Surface, DiskCylinderConeParameters) {
    // Annulus: the hole is empty, v runs from the outer edge (0) to the inner edge (1).
    const scene::Scene dsc = single(disk({0, 0, 0}, {0, 0, 1}, 2, 1));
    const accel::EmbreeScene des(dsc);
    accel::SurfaceHit h;
    EXPECT_FALSE(des.intersect({{0.5f, 0.2f, 3}, {0, 0, -1}}, h));
    ASSERT_TRUE(des.intersect({{1.5f, 0, 3}, {0, 0, -1}}, h));
    expect_vec(h.ng, {0, 0, 1});
    EXPECT_NEAR(h.uv.y, 0.5f, 1e-5);
    EXPECT_NEAR(h.uv.x, 0, 1e-5);

    // Cylinder along +y of height 2: v = (y + h/2) / h on the side; caps only when capped.
    Shape c = cylinder({0, 0, 0}, {0, 1, 0}, 1, 2, false);
    h = hit_of(single(c), {{5, 0.5f, 0}, {-1, 0, 0}});
    expect_vec(h.ng, {1, 0, 0});
    EXPECT_NEAR(h.uv.y, 0.75f, 1e-5);
    const Ray along{{0.2f, 5, 0}, {0, -1, 0}};
    {
        const scene::Scene open = single(c);
        EXPECT_FALSE(accel::EmbreeScene(open).occluded(along));
    }
    c.capped = true;
    h = hit_of(single(c), along);
    expect_vec(h.ng, {0, 1, 0});
    EXPECT_NEAR(h.t, 4, 1e-5);

    // Cone: apex at centre + axis h/2, base (capped) at centre - axis h/2.
    Shape k = cone({1, 1, 1}, {0, 0, 1}, 1, 2);
    h = hit_of(single(k), {{1, 1, 5}, {0, 0, -1}});
    expect_vec(h.p, {1, 1, 2}, 1e-4f);
    h = hit_of(single(k), {{1.2f, 1, -5}, {0, 0, 1}});
    expect_vec(h.p, {1.2f, 1, 0});
    expect_vec(h.ng, {0, 0, -1});
    h = hit_of(single(k), {{5, 1, 1}, {-1, 0, 0}});  // side at mid-height: radius 1/2
    expect_vec(h.p, {1.5f, 1, 1});
    expect_vec(h.ng, normalize(Vec3(1, 0, 0.5f)));
    EXPECT_NEAR(h.uv.y, 0.5f, 1e-5);
    k.capped = false;  // from below, the ray now reaches the inside of the apex
    h = hit_of(single(k), {{1, 1, -5}, {0, 0, 1}});
    expect_vec(h.p, {1, 1, 2}, 1e-4f);
}

TEST(Instances, HitsReportInstanceAndObjectShape) {
    scene::Scene sc;
    scene::Object obj;
    obj.shapes.push_back(box({-1, -1, -1}, {1, 1, 1}));
    obj.shapes.push_back(sphere({0, 3, 0}, 1, 5));
    sc.objects.push_back(obj);
    sc.shapes.push_back(sphere({0, 0, -50}, 1));
    sc.instances.push_back({0, Transform::translate({10, 0, 0})});
    sc.instances.push_back({0, Transform::translate({-10, 0, 0}) * Transform::scale({-2, 2, 2})});
    const accel::EmbreeScene es(sc);
    accel::SurfaceHit h;
    ASSERT_TRUE(es.intersect({{10, 3, 10}, {0, 0, -1}}, h));
    EXPECT_EQ(h.instance, 0);
    EXPECT_EQ(h.shape, 1);
    EXPECT_EQ(h.material, 5);
    EXPECT_NEAR(h.t, 9, 1e-5);
    expect_vec(h.ng, {0, 0, 1});
    ASSERT_TRUE(es.intersect({{-10, 6, 10}, {0, 0, -1}}, h));
    EXPECT_EQ(h.instance, 1);
    EXPECT_EQ(h.shape, 1);
    EXPECT_NEAR(h.t, 8, 1e-5);
    // An instance transform carries normals over without the pbrt handedness flip.
    expect_vec(h.ng, {0, 0, 1});
    ASSERT_TRUE(es.intersect({{-20, 0.5f, 0.5f}, {1, 0, 0}}, h));
    EXPECT_EQ(h.instance, 1);
    EXPECT_EQ(h.shape, 0);
    expect_vec(h.ng, {-1, 0, 0});
    expect_vec(h.p, {-12, 0.5f, 0.5f});
    ASSERT_TRUE(es.intersect({{0, 0, 0}, {0, 0, -1}}, h));
    EXPECT_EQ(h.instance, -1);
    EXPECT_EQ(h.shape, 0);
}

TEST(Bounds, TightAroundAllGeometry) {
    {
        const scene::Scene empty;
        const accel::EmbreeScene es(empty);
        EXPECT_TRUE(es.bounds().empty());
        accel::SurfaceHit h;
        EXPECT_FALSE(es.intersect({{0, 0, 0}, {1, 0, 0}}, h));
    }
    scene::Scene sc;
    sc.shapes.push_back(sphere({1, 2, 3}, 2));
    sc.shapes.push_back(box({-5, 0, 0}, {-4, 1, 1}));
    // A disk of radius 1 tilted 45 degrees about z: x extent cos 45, y extent sin 45, z extent 1.
    sc.shapes.push_back(disk({10, 0, 0}, normalize(Vec3(1, 1, 0)), 1));
    scene::Object obj;
    obj.shapes.push_back(sphere({0, 0, 0}, 1));
    sc.objects.push_back(obj);
    sc.instances.push_back({0, Transform::translate({0, -10, 0}) * Transform::scale({1, 3, 1})});
    const Bounds b = accel::EmbreeScene(sc).bounds();
    const float s = std::sqrt(0.5f);
    expect_vec(b.lo, {-5, -13, -1}, 1e-3f);
    expect_vec(b.hi, {10 + s, 4, 5}, 1e-3f);
    const scene::Scene tilted = single(disk({10, 0, 0}, normalize(Vec3(1, 1, 0)), 1));
    const Bounds d = accel::EmbreeScene(tilted).bounds();
    expect_vec(d.lo, {10 - s, -s, -1}, 1e-4f);
    expect_vec(d.hi, {10 + s, s, 1}, 1e-4f);
    Shape c = cylinder({0, 0, 0}, {0, 1, 0}, 1, 4, true);
    c.to_world = Transform::rotate(90, {0, 0, 1});
    const scene::Scene lying = single(c);
    const Bounds cb = accel::EmbreeScene(lying).bounds();
    expect_vec(cb.lo, {-2, -1, -1}, 1e-4f);
    expect_vec(cb.hi, {2, 1, 1}, 1e-4f);
}

TEST(Errors, BadInputThrowsOrIsSkipped) {
    Shape bad = quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
    bad.mesh.indices[4] = 9;
    const scene::Scene out_of_range = single(bad);
    EXPECT_THROW(accel::EmbreeScene{out_of_range}, InputError);
    bad.mesh.indices = {0, 1};
    const scene::Scene incomplete = single(bad);
    EXPECT_THROW(accel::EmbreeScene{incomplete}, InputError);
    scene::Scene sc;
    sc.instances.push_back({3, Transform()});
    EXPECT_THROW(accel::EmbreeScene{sc}, InputError);
    // Degenerate analytic shapes are skipped with a warning, not fatal.
    log::set_quiet(true);
    const int warnings = log::warning_count();
    const scene::Scene zero = single(sphere({0, 0, 0}, 0));
    const accel::EmbreeScene es(zero);
    EXPECT_GT(log::warning_count(), warnings);
    EXPECT_FALSE(es.occluded({{0, 0, 5}, {0, 0, -1}}));
    log::set_quiet(false);
}

TEST(Threads, ConcurrentQueriesMatchSerialOnes) {
    scene::Scene sc;
    sc.shapes.push_back(mesh_sphere({0, 0, 0}, 2, 64, 32, true));
    sc.shapes.push_back(cone({3, 0, 0}, {0, 1, 0}, 1, 2));
    const accel::EmbreeScene es(sc);
    const int n = 4000;
    std::vector<Ray> rays(n);
    Sampler rng(3);
    for (auto& r : rays) r = {random_in(rng, Vec3(-6.0f), Vec3(6.0f)), random_unit(rng)};
    std::vector<float> serial(n), parallel(n, -1);
    for (int i = 0; i < n; ++i) {
        accel::SurfaceHit h;
        serial[size_t(i)] = es.intersect(rays[size_t(i)], h) ? h.t : -2;
    }
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            for (int i = t; i < n; i += 4) {
                accel::SurfaceHit h;
                parallel[size_t(i)] = es.intersect(rays[size_t(i)], h) ? h.t : -2;
            }
        });
    for (auto& th : threads) th.join();
    EXPECT_EQ(serial, parallel);
}

}  // namespace
}  // namespace phos::testing
