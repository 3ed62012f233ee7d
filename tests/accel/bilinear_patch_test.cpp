// Exact bilinear patches: hit distances against a fine tessellation (brute force), the saddle
// z = h u v hit where it is, (u, v), uv and normals as pbrt-v4 defines them, orientation flags,
// instances, and occlusion.
#include <gtest/gtest.h>

#include <cmath>

#include "accel/embree_scene.h"
#include "accel/scene_builders.h"

namespace phos::testing {
namespace {

using scene::Shape;

// One patch with corners p00 p10 p01 p11 (pbrt's order) as a mesh's exact patch.
Shape patch_shape(Vec3 p00, Vec3 p10, Vec3 p01, Vec3 p11) {
    Shape s;
    s.kind = Shape::Kind::Mesh;
    s.mesh.positions = {p00, p10, p01, p11};
    s.mesh.patches = {0, 1, 2, 3};
    return s;
}

// The same patch as an n x n grid of triangles (counter-clockwise around dp/du x dp/dv).
Shape tessellated(Vec3 p00, Vec3 p10, Vec3 p01, Vec3 p11, int n) {
    Shape s;
    s.kind = Shape::Kind::Mesh;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const float u = float(i) / float(n), v = float(j) / float(n);
            s.mesh.positions.push_back((p00 * (1 - u) + p10 * u) * (1 - v) + (p01 * (1 - u) + p11 * u) * v);
        }
    const auto at = [n](int i, int j) { return uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            s.mesh.indices.insert(s.mesh.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j),
                                                         at(i + 1, j + 1), at(i, j + 1)});
    return s;
}

scene::Scene single(Shape s) {
    scene::Scene sc;
    sc.shapes.push_back(std::move(s));
    return sc;
}

TEST(BilinearPatch, HitDistancesMatchAFineTessellation) {
    const Vec3 p00{-1, -1, 0.3f}, p10{1.2f, -0.8f, -0.5f}, p01{-0.9f, 1.1f, -0.4f}, p11{1, 1, 0.9f};
    const scene::Scene exact = single(patch_shape(p00, p10, p01, p11));
    const scene::Scene fine = single(tessellated(p00, p10, p01, p11, 250));
    const accel::EmbreeScene ee(exact), ef(fine);
    Sampler rng(5);
    int compared = 0, mismatched = 0;
    for (int i = 0; i < 4000; ++i) {
        const Vec3 o = random_in(rng, Vec3(-3.0f), Vec3(3.0f));
        const Vec3 d = normalize(random_in(rng, Vec3(-1.2f), Vec3(1.2f)) - o);
        accel::SurfaceHit he, hf;
        const bool a = ee.intersect({o, d}, he), b = ef.intersect({o, d}, hf);
        if (a != b) {
            // Only rays that graze the patch, or pass within the tessellation's error of it.
            ++mismatched;
            continue;
        }
        if (!a) continue;
        ++compared;
        // The tessellation lies within ~|twist| / (8 n^2) of the patch; grazing rays amplify that.
        const float slack = 2e-5f / std::max(0.05f, std::fabs(dot(hf.ng, d)));
        EXPECT_NEAR(he.t, hf.t, slack) << i;
        EXPECT_GT(std::fabs(dot(he.ng, hf.ng)), 0.999f) << i;
        // The hit is on the patch: p(u, v) at the reported (u, v) (no uvs given) is the hit point.
        const Vec3 q = (p00 * (1 - he.uv.x) + p10 * he.uv.x) * (1 - he.uv.y) +
                       (p01 * (1 - he.uv.x) + p11 * he.uv.x) * he.uv.y;
        EXPECT_LT(length(q - he.p), 1e-5f) << i;
        // Onwards from the hit the curved patch may be met again, but never at t ~ 0 (spawning).
        if (std::fabs(dot(he.ng, d)) > 0.1f) {
            accel::SurfaceHit again;
            const Vec3 n = dot(he.ng, d) < 0 ? -he.ng : he.ng;
            if (ee.intersect({he.p + n * (4 * he.error), d}, again)) {
                EXPECT_GT(again.t, 1e-4f) << i;
            }
        }
    }
    EXPECT_GT(compared, 1000);
    EXPECT_LT(mismatched, 8);
}

TEST(BilinearPatch, SaddleUvNormalAndOrientation) {
    // p(u, v) = (u, v, h u v) over the unit square: a hyperbolic paraboloid.
    const float h = 0.8f;
    Shape s = patch_shape({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, h});
    const scene::Scene sc_es = single(s);
    const accel::EmbreeScene es(sc_es);
    accel::SurfaceHit hit;
    for (const Vec2 uv : {Vec2(0.25f, 0.5f), Vec2(0.9f, 0.1f), Vec2(0.6f, 0.7f)}) {
        ASSERT_TRUE(es.intersect({{uv.x, uv.y, 5}, {0, 0, -1}}, hit));
        EXPECT_NEAR(hit.p.z, h * uv.x * uv.y, 1e-6f);
        EXPECT_NEAR(hit.t, 5 - h * uv.x * uv.y, 1e-5f);
        EXPECT_NEAR(hit.uv.x, uv.x, 1e-6f);
        EXPECT_NEAR(hit.uv.y, uv.y, 1e-6f);
        // dp/du x dp/dv = (1, 0, h v) x (0, 1, h u) = (-h v, -h u, 1).
        const Vec3 n = normalize(Vec3(-h * uv.y, -h * uv.x, 1));
        EXPECT_GT(dot(hit.ng, n), 0.99999f);
        EXPECT_GT(dot(hit.ns, n), 0.99999f);
        EXPECT_NEAR(dot(hit.dpdu, normalize(Vec3(1, 0, h * uv.y))), 1, 1e-5f);
        EXPECT_EQ(hit.primitive, 0);
    }
    // Flipped patches and reverse_orientation each turn the normal; both together restore it.
    for (int flags = 1; flags < 4; ++flags) {
        Shape f = s;
        f.mesh.patches_flipped = flags & 1;
        f.reverse_orientation = flags & 2;
        const scene::Scene sc_ef = single(f);
        const accel::EmbreeScene ef(sc_ef);
        ASSERT_TRUE(ef.intersect({{0.5f, 0.5f, 5}, {0, 0, -1}}, hit));
        EXPECT_EQ(hit.ng.z > 0, flags == 3) << flags;
    }
    // Per-corner uvs are interpolated bilinearly; the tangent follows the texture's u.
    Shape t = s;
    t.mesh.uvs = {{0, 0}, {0, 2}, {3, 0}, {3, 2}};  // s = 3 v, t = 2 u: texture u runs along v
    const scene::Scene sc_et = single(t);
    const accel::EmbreeScene et(sc_et);
    ASSERT_TRUE(et.intersect({{0.5f, 0.25f, 5}, {0, 0, -1}}, hit));
    EXPECT_NEAR(hit.uv.x, 0.75f, 1e-5f);
    EXPECT_NEAR(hit.uv.y, 1.0f, 1e-5f);
    EXPECT_NEAR(dot(hit.dpdu, normalize(Vec3(0, 1, h * 0.5f))), 1, 1e-5f);
    // Per-corner normals are interpolated, and the geometric normal turns to their side.
    Shape n = s;
    n.mesh.normals = {{0, 0, -1}, {0, 0, -1}, {0, 0, -1}, {0, 0, -1}};
    const scene::Scene sc_en = single(n);
    const accel::EmbreeScene en(sc_en);
    ASSERT_TRUE(en.intersect({{0.5f, 0.5f, 5}, {0, 0, -1}}, hit));
    EXPECT_NEAR(hit.ns.z, -1, 1e-6f);
    EXPECT_LT(hit.ng.z, 0);
}

TEST(BilinearPatch, OcclusionInstancesAndTrianglesBeside) {
    // A mesh with one triangle and one exact patch; also as an instance moved by +10 in x.
    Shape s = patch_shape({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0.5f});
    s.mesh.positions.push_back({3, 0, 0});
    s.mesh.positions.push_back({4, 0, 0});
    s.mesh.positions.push_back({3, 1, 0});
    s.mesh.indices = {4, 5, 6};
    scene::Scene sc = single(s);
    scene::Object obj;
    obj.shapes.push_back(s);
    sc.objects.push_back(obj);
    sc.instances.push_back({0, Transform::translate({10, 0, 0})});
    const accel::EmbreeScene es(sc);
    accel::SurfaceHit hit;
    for (float dx : {0.0f, 10.0f}) {
        ASSERT_TRUE(es.intersect({{dx + 0.5f, 0.5f, 5}, {0, 0, -1}}, hit));
        EXPECT_NEAR(hit.p.z, 0.125f, 1e-6f);
        EXPECT_EQ(hit.primitive, 0);
        EXPECT_TRUE(es.occluded({{dx + 0.5f, 0.5f, 5}, {0, 0, -1}}));
        EXPECT_FALSE(es.occluded({{dx + 0.5f, 0.5f, 5}, {0, 0, -1}, 0.0f, 4.8f}));
        ASSERT_TRUE(es.intersect({{dx + 3.2f, 0.2f, 5}, {0, 0, -1}}, hit));
        EXPECT_NEAR(hit.t, 5, 1e-6f);
    }
    EXPECT_FALSE(es.intersect({{1.5f, 0.5f, 5}, {0, 0, -1}}, hit));
}

}  // namespace
}  // namespace phos::testing
