// pbrt shapes end to end, from scene text to ray hits and lights: partial spheres (clamped as
// pbrt-v4, hit only on the part, area lights over the part), loopsubdiv (subdivided to the limit
// surface, located errors for bad meshes), bilinearmesh (planar patches as triangles, the others exact).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "accel/embree_scene.h"
#include "core/log.h"
#include "io/pbrt/pbrt_loader.h"
#include "shading/area_light.h"
#include "test_util.h"

namespace phos::testing {
namespace {

scene::Scene load_text(const std::string& text) {
    log::set_quiet(true);
    TempDir dir;
    scene::Scene s = io::load_pbrt(dir.write("scene.pbrt", text));
    log::set_quiet(false);
    return s;
}

const std::string kHead = "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";

TEST(PbrtPartialSphere, ClampedAsPbrtAndHitOnlyOnThePart) {
    // zmin beyond the radius clamps to -r; phimax 400 clamps to 360: only zmax = 0.5 cuts.
    const scene::Scene s =
        load_text(kHead +
                  "Translate 0 0 -1\nShape \"sphere\" \"float radius\" 2 \"float zmin\" -5 "
                  "\"float zmax\" 0.5 \"float phimax\" 400\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    const scene::Shape& sh = s.shapes[0];
    EXPECT_TRUE(sh.partial);
    EXPECT_FLOAT_EQ(sh.z_min, -2);
    EXPECT_FLOAT_EQ(sh.z_max, 0.5f);
    EXPECT_FLOAT_EQ(sh.phi_max, 2 * kPi);
    const accel::EmbreeScene es(s);
    accel::SurfaceHit h;
    // Down the axis from above: the cap above z = 0.5 (object space) is gone, so the ray meets the
    // bottom of the bowl from inside, at object z = -2, world z = -3.
    ASSERT_TRUE(es.intersect({{0, 0, 10}, {0, 0, -1}}, h));
    EXPECT_NEAR(h.p.z, -3, 1e-5);
    EXPECT_NEAR(h.ng.z, -1, 1e-5);  // the outward normal, facing away from the viewer
    // A full sphere in the same place is hit on top.
    const scene::Scene full = load_text(kHead + "Translate 0 0 -1\nShape \"sphere\" \"float radius\" 2\n");
    EXPECT_FALSE(full.shapes[0].partial);
    const accel::EmbreeScene ef(full);
    ASSERT_TRUE(ef.intersect({{0, 0, 10}, {0, 0, -1}}, h));
    EXPECT_NEAR(h.p.z, 1, 1e-5);
    // A zero-area part is skipped with a warning.
    EXPECT_TRUE(load_text(kHead + "Shape \"sphere\" \"float zmin\" 0.3 \"float zmax\" 0.3\n").shapes.empty());
}

TEST(PbrtFullSphere, UvAndTangentAreThoseOfPbrtV4) {
    // pbrt-v4: u = phi / 2pi with phi = atan2(y, x) from +x in object space, v = 1 - theta / pi with
    // theta from +z (v = 0 at the -z pole); dpdu along increasing phi. Rotated so that object +z
    // is world +y: the top of the sphere has v near 1.
    const scene::Scene s = load_text(kHead + "Rotate -90 1 0 0\nShape \"sphere\" \"float radius\" 1\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_TRUE(s.shapes[0].pbrt_uv);
    const accel::EmbreeScene es(s);
    accel::SurfaceHit h;
    for (const Vec3 o :
         {Vec3(0.3f, 0.5f, 5), Vec3(-0.4f, -0.2f, 5), Vec3(0.05f, 0.9f, 5), Vec3(-0.6f, 0.1f, 5)}) {
        ASSERT_TRUE(es.intersect({o, {0, 0, -1}}, h));
        // Object space: world (x, y, z) is object (x, -z, y) under Rotate -90 about x.
        const Vec3 q(h.p.x, -h.p.z, h.p.y);
        float phi = std::atan2(q.y, q.x);
        if (phi < 0) phi += 2 * kPi;
        const float theta = std::acos(std::clamp(q.z, -1.0f, 1.0f));
        EXPECT_NEAR(h.uv.x, phi / (2 * kPi), 1e-4f);
        EXPECT_NEAR(h.uv.y, 1 - theta / kPi, 1e-4f);
        // dpdu along increasing phi: object (-sin phi, cos phi, 0), world (-sin phi, 0, -cos phi).
        EXPECT_NEAR(h.dpdu.x, -std::sin(phi), 1e-4f);
        EXPECT_NEAR(h.dpdu.z, -std::cos(phi), 1e-4f);
    }
}

TEST(PbrtPartialSphere, AreaLightPowerAndSamplesUseThePart) {
    // A hemisphere (phimax 180) between z = 0 and z = 1 of a unit sphere: area pi * 1 * 1.
    const scene::Scene s = load_text(kHead +
                                     "AreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"float power\" 10\n"
                                     "Shape \"sphere\" \"float zmin\" 0 \"float phimax\" 180\n");
    ASSERT_EQ(s.lights.size(), 1u);
    const shading::AreaLight light(s.lights[0], s.shapes[0]);
    EXPECT_NEAR(light.sampler().area(), kPi, 1e-5);
    // pbrt-v4's power: L scaled so that pi * area * L = power.
    EXPECT_NEAR(light.power().g, 10, 1e-3);
    Sampler rng(7);
    for (int i = 0; i < 1000; ++i) {
        const shading::ShapeSample p = light.sampler().sample_area(rng.next2());
        ASSERT_GE(p.p.z, -1e-6f);
        ASSERT_GE(p.p.y, -1e-6f);  // phi in [0, pi]
    }
}

TEST(PbrtLoopSubdiv, TetrahedronBecomesItsSmoothLimitSurface) {
    const std::string tet =
        "\"point3 P\" [1 1 1  1 -1 -1  -1 1 -1  -1 -1 1] \"integer indices\" [0 1 2 0 2 3 0 3 1 1 3 2]";
    const scene::Scene s = load_text(kHead + "Shape \"loopsubdiv\" \"integer levels\" 3 " + tet + "\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    const scene::TriangleMesh& m = s.shapes[0].mesh;
    EXPECT_EQ(m.triangle_count(), 4u * 64u);
    EXPECT_EQ(m.normals.size(), m.positions.size());
    const accel::EmbreeScene es(s);
    accel::SurfaceHit h;
    // Towards a corner: the limit surface passes through corner / 5 (Loop's masks, closed form).
    const Vec3 corner = normalize(Vec3(1, 1, 1));
    ASSERT_TRUE(es.intersect({corner * 10.0f, -corner}, h));
    EXPECT_NEAR(length(h.p), std::sqrt(3.0f) / 5, 1e-4);
    // The smooth surface's normal there is the axis; pbrt-v4's masks point it against the winding
    // (inwards here), and the surface faces it.
    EXPECT_LT(dot(h.ns, corner), -0.999f);
    EXPECT_LT(dot(h.ng, corner), 0.0f);
    // Towards a face centre: a third of the corner's distance on the tetrahedron; the smooth limit
    // surface is much rounder (0.73 of it).
    ASSERT_TRUE(es.intersect({corner * -10.0f, corner}, h));
    EXPECT_LT(length(h.p), 1 / std::sqrt(3.0f));
    EXPECT_GT(length(h.p), 0.6f * std::sqrt(3.0f) / 5);
    EXPECT_LT(dot(h.ns, -corner), -0.999f);
    // The default is 3 levels; pbrt-v3's "nlevels" is read as "levels".
    EXPECT_EQ(load_text(kHead + "Shape \"loopsubdiv\" " + tet + "\n").shapes[0].mesh.triangle_count(), 256u);
    EXPECT_EQ(load_text("WorldBegin\nShape \"loopsubdiv\" \"integer nlevels\" 1 " + tet + "\n")
                  .shapes[0]
                  .mesh.triangle_count(),
              16u);
}

TEST(PbrtLoopSubdiv, BadMeshesAreLocatedErrors) {
    log::set_quiet(true);
    TempDir dir;
    // Three triangles on the edge 0-1.
    const std::string bad =
        dir.write("bad.pbrt",
                  "WorldBegin\nShape \"loopsubdiv\" \"point3 P\" [0 0 0 1 0 0 0 1 0 0 0 1 1 1 1]\n"
                  "  \"integer indices\" [0 1 2 1 0 3 1 0 4]\n");
    expect_parse_error_from([&] { io::load_pbrt(bad); }, "", 3, 3, "two triangles that run it the same way");
    const std::string range =
        dir.write("range.pbrt",
                  "WorldBegin\nShape \"loopsubdiv\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer "
                  "indices\" [0 1 5]\n");
    expect_parse_error_from([&] { io::load_pbrt(range); }, "", 2, 51, "out of range");
    const std::string levels = dir.write(
        "levels.pbrt",
        "WorldBegin\nShape \"loopsubdiv\" \"integer levels\" -1 \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer "
        "indices\" [0 1 2]\n");
    expect_parse_error_from([&] { io::load_pbrt(levels); }, "", 2, 20, "levels");
    log::set_quiet(false);
}

TEST(PbrtBilinearMesh, PlanarPatchesAreTrianglesOthersAreExact) {
    // Two patches: a flat unit square, and the saddle z = h u v over [2, 3] x [0, 1] (h = 0.8).
    const scene::Scene s = load_text(
        kHead +
        "AreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"float power\" 5\n"
        "Shape \"bilinearmesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0  1 1 0  2 0 0  3 0 0  2 1 0  3 1 0.8]\n"
        "  \"integer indices\" [0 1 2 3  4 5 6 7]\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    const scene::TriangleMesh& m = s.shapes[0].mesh;
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 3, 0, 3, 2}));
    EXPECT_EQ(m.patches, (std::vector<uint32_t>{4, 5, 6, 7}));
    const accel::EmbreeScene es(s);
    accel::SurfaceHit h;
    ASSERT_TRUE(es.intersect({{0.3f, 0.6f, 5}, {0, 0, -1}}, h));
    EXPECT_NEAR(h.t, 5, 1e-6);
    EXPECT_EQ(h.primitive, 1);  // the second triangle (p00 p11 p01)
    ASSERT_TRUE(es.intersect({{2.5f, 0.75f, 5}, {0, 0, -1}}, h));
    EXPECT_NEAR(h.p.z, 0.8f * 0.5f * 0.75f, 1e-6);
    EXPECT_NEAR(h.uv.x, 0.5f, 1e-6);
    EXPECT_NEAR(h.uv.y, 0.75f, 1e-6);
    EXPECT_GT(h.ng.z, 0);
    // Two triangles would put the saddle's point on the diagonal's plane instead.
    EXPECT_GT(std::fabs(h.p.z - 0.8f * std::min(0.5f, 0.75f)), 0.05f);
    // The light's power is spread over both patches' true area.
    const shading::AreaLight light(s.lights[0], s.shapes[0]);
    double fine = 0;
    for (int i = 0; i < 400; ++i)
        for (int j = 0; j < 400; ++j) {
            const double u = (i + 0.5) / 400, v = (j + 0.5) / 400;
            fine += std::sqrt(1 + 0.64 * (u * u + v * v)) / (400.0 * 400.0);
        }
    EXPECT_NEAR(light.sampler().area(), 1 + fine, 1e-4);
    EXPECT_NEAR(light.power().g, 5, 1e-3);
}

}  // namespace
}  // namespace phos::testing
