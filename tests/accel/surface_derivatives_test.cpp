// accel::surface_derivatives against the surface itself: for two nearby hits on every shape kind
// (triangles with and without uvs, bilinear patches with uvs, full and partial spheres, disks,
// cylinders, cones and their caps, curves, a transformed instance), p2 - p1 = dpdu du + dpdv dv to
// first order, so the derivatives match the uv each hit reports; with shading normals, pbrt-v4's
// shading pair is perpendicular to ns.
#include "accel/surface_derivatives.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "accel/embree_scene.h"
#include "accel/scene_builders.h"

namespace phos::testing {
namespace {

using scene::Shape;

struct Case {
    std::string name;
    scene::Scene scene;
    Vec3 origin, dir;  // a ray that hits the surface away from seams and edges
};

Shape patch_with_uvs() {
    Shape s;
    s.kind = Shape::Kind::Mesh;
    s.mesh.positions = {{-1, -1, 0.3f}, {1.2f, -0.8f, -0.5f}, {-0.9f, 1.1f, -0.4f}, {1, 1, 0.9f}};
    s.mesh.patches = {0, 1, 2, 3};
    s.mesh.uvs = {{0.1f, 0.2f}, {0.9f, 0.1f}, {0.2f, 0.8f}, {1.1f, 1.3f}};
    return s;
}

Shape textured_triangle(bool normals) {
    Shape s;
    s.kind = Shape::Kind::Mesh;
    s.mesh.positions = {{-2, -1, 0}, {2, -1.5f, 0.3f}, {0, 2, -0.2f}};
    s.mesh.indices = {0, 1, 2};
    s.mesh.uvs = {{0.1f, 0.1f}, {2.0f, 0.4f}, {0.7f, 1.5f}};
    if (normals)
        s.mesh.normals = {normalize(Vec3(0.2f, 0, 1)), normalize(Vec3(-0.1f, 0.3f, 1)), Vec3(0, 0, 1)};
    return s;
}

Shape curve() {
    Shape s;
    s.kind = Shape::Kind::Curves;
    s.curves.type = scene::CurveSet::Type::Cylinder;
    s.curves.points = {{-1, 0, 0}, {-0.3f, 0.2f, 0}, {0.3f, -0.2f, 0}, {1, 0.1f, 0}};
    s.curves.radii = {0.3f, 0.3f, 0.3f, 0.3f};
    s.curves.segments = {0};
    return s;
}

std::vector<Case> cases() {
    std::vector<Case> out;
    const auto add = [&](const std::string& name, Shape s, Vec3 o, Vec3 d) {
        scene::Scene sc;
        sc.shapes.push_back(std::move(s));
        out.push_back({name, std::move(sc), o, d});
    };
    add("triangle (barycentric uv)", quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}), {0.3f, -0.4f, 3},
        {0, 0, -1});
    add("triangle with uvs", textured_triangle(false), {0.1f, 0.2f, 3}, {0.05f, 0, -1});
    add("bilinear patch with uvs", patch_with_uvs(), {0.2f, 0.1f, 3}, {0, 0.05f, -1});
    Shape sph = sphere({0.5f, -0.2f, 0.1f}, 1.3f);
    sph.axis = normalize(Vec3(0.3f, 1, 0.2f));
    add("sphere", sph, {5, 0.3f, 0.4f}, {-1, 0, 0});
    Shape part = sphere({0, 0, 0}, 1);
    part.partial = true;
    part.axis = {0, 0, 1};
    part.z_min = -0.5f, part.z_max = 0.8f, part.phi_max = 4.5f;
    add("partial sphere", part, {3, 0.6f, 0.2f}, {-1, 0, 0});
    add("disk (annulus)", disk({0, 0, 0}, normalize(Vec3(0.2f, 0.1f, 1)), 2, 0.5f), {1.1f, 0.4f, 3},
        {0, 0, -1});
    add("cylinder", cylinder({0, 0, 0}, {0, 0, 1}, 1, 2, true), {3, 0.4f, 0.3f}, {-1, 0, 0});
    add("cylinder cap", cylinder({0, 0, 0}, {0, 0, 1}, 1, 2, true), {0.3f, 0.4f, 3}, {0, 0, -1});
    add("cone", cone({0, 0, 0}, {0, 0, 1}, 1, 2, false), {3, 0.3f, -0.2f}, {-1, 0, 0});
    add("curve", curve(), {0.1f, 0.05f, 3}, {0, 0, -1});
    Shape scaled = sphere({0, 0, 0}, 1);
    scaled.to_world = Transform::scale({2, 1, 0.5f});
    add("scaled sphere", scaled, {0.3f, 5, 0.1f}, {0, -1, 0});
    // An instanced sphere under a rotation and non-uniform scale.
    {
        scene::Scene sc;
        scene::Object obj;
        obj.shapes.push_back(sphere({0, 0, 0}, 1));
        sc.objects.push_back(obj);
        sc.instances.push_back(
            {0, Transform::translate({1, 0, 0}) * Transform::rotate(30, normalize(Vec3(1, 1, 0))) *
                    Transform::scale({1.5f, 0.7f, 1})});
        out.push_back({"instanced sphere", std::move(sc), {1.2f, 0.1f, 5}, {0, 0, -1}});
    }
    return out;
}

TEST(SurfaceDerivatives, MatchNearbyHitsOnEveryShapeKind) {
    for (const Case& c : cases()) {
        const accel::EmbreeScene es(c.scene);
        accel::SurfaceHit h0;
        ASSERT_TRUE(es.intersect({c.origin, c.dir}, h0)) << c.name;
        const accel::SurfaceDerivatives d = accel::surface_derivatives(c.scene, h0);
        // dpdu x dpdv is along the geometric normal (either way round).
        const Vec3 n = cross(d.dpdu, d.dpdv);
        ASSERT_GT(length(n), 0) << c.name;
        EXPECT_GT(std::fabs(dot(normalize(n), h0.ng)), 0.999f) << c.name;
        // The unit tangent the hit reports is dpdu's direction (curves: the tangent of the curve).
        EXPECT_GT(dot(normalize(d.dpdu), h0.dpdu), 0.999f) << c.name;
        const Frame side(normalize(c.dir));
        for (Vec3 offset : {side.s, side.t, side.s + side.t * 0.5f}) {
            const float eps = 1e-3f;
            accel::SurfaceHit h1;
            ASSERT_TRUE(es.intersect({c.origin + offset * eps, c.dir}, h1)) << c.name;
            const Vec3 dp = h1.p - h0.p;
            const Vec2 duv = h1.uv - h0.uv;
            const Vec3 predicted = d.dpdu * duv.x + d.dpdv * duv.y;
            // First order: the residual is O(eps^2) against |dp| = O(eps).
            EXPECT_LT(length(dp - predicted), 0.02f * length(dp) + 1e-6f)
                << c.name << ": dp " << dp.x << " " << dp.y << " " << dp.z << " predicted " << predicted.x
                << " " << predicted.y << " " << predicted.z;
        }
    }
}

TEST(SurfaceDerivatives, ShadingNormalsGivePbrtsPerpendicularPair) {
    scene::Scene sc;
    sc.shapes.push_back(textured_triangle(true));
    const accel::EmbreeScene es(sc);
    accel::SurfaceHit h;
    ASSERT_TRUE(es.intersect({{0.1f, 0.2f, 3}, {0, 0, -1}}, h));
    const accel::SurfaceDerivatives d = accel::surface_derivatives(sc, h);
    EXPECT_NEAR(dot(d.dpdu, h.ns), 0, 1e-5f * length(d.dpdu));
    EXPECT_NEAR(dot(d.dpdv, h.ns), 0, 1e-5f * length(d.dpdv));
    // dpdv = ns x dpdu, so dpdu x dpdv is along ns.
    EXPECT_GT(dot(normalize(cross(d.dpdu, d.dpdv)), h.ns), 0.9999f);
    // The geometric dpdu, made perpendicular to ns: same length to first order in the tilt.
    scene::Scene flat;
    flat.shapes.push_back(textured_triangle(false));
    const accel::EmbreeScene ef(flat);
    accel::SurfaceHit g;
    ASSERT_TRUE(ef.intersect({{0.1f, 0.2f, 3}, {0, 0, -1}}, g));
    const accel::SurfaceDerivatives dg = accel::surface_derivatives(flat, g);
    EXPECT_NEAR(length(d.dpdu), length(dg.dpdu - h.ns * dot(h.ns, dg.dpdu)), 1e-4f * length(dg.dpdu));
}

}  // namespace
}  // namespace phos::testing
