// pbrt `plymesh` with `displacement` and `edgelength`, as pbrt-v4 builds it: the mesh refined
// until every world-space edge is shorter than edgelength, moved along its normals by the float
// texture (or constant), with normals recomputed; errors located at the parameter.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pbrt_test_util.h"
#include "scene/scene.h"
#include "support/mesh_writers.h"

namespace phos::io::test {
namespace {

struct Loaded {
    scene::Scene scene;
    int warnings = 0;
};

// A scene with the unit square (uv = xy) as "quad.ply", then `world`.
Loaded load_with_quad(PbrtTempDir& dir, const std::string& world) {
    scene::TriangleMesh quad = phos::testing::unit_quad();
    quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    phos::testing::write_ply(dir.file("quad.ply"), quad, false);
    QuietLog quiet;
    const int before = log::warning_count();
    Loaded l{load_pbrt(dir.write("scene.pbrt", "WorldBegin\n" + world)), 0};
    l.warnings = log::warning_count() - before;
    return l;
}

float max_edge(const scene::TriangleMesh& m) {
    float e = 0;
    for (size_t i = 0; i < m.indices.size(); i += 3)
        for (int k = 0; k < 3; ++k)
            e = std::max(e, length(m.positions[m.indices[i + size_t(k)]] -
                                   m.positions[m.indices[i + size_t((k + 1) % 3)]]));
    return e;
}

TEST(PbrtDisplacement, ConstantDisplacementMovesThePlaneAlongItsNormal) {
    PbrtTempDir dir;
    // Scaled by 2: edges are measured in world space (length 2 per unit), the displacement is in
    // object space and scaled with the mesh.
    const Loaded l = load_with_quad(dir,
                                    "Scale 2 2 2\nShape \"plymesh\" \"string filename\" \"quad.ply\" "
                                    "\"float displacement\" 0.25 \"float edgelength\" 0.5\n");
    EXPECT_EQ(l.warnings, 0);
    ASSERT_EQ(l.scene.shapes.size(), 1u);
    const scene::TriangleMesh& m = l.scene.shapes[0].mesh;
    EXPECT_GT(m.triangle_count(), 16u);
    EXPECT_LT(max_edge(m), 0.5f);
    for (const Vec3& p : m.positions) EXPECT_FLOAT_EQ(p.z, 0.5f);
    ASSERT_EQ(m.normals.size(), m.positions.size());
    for (const Vec3& n : m.normals) EXPECT_NEAR(n.z, 1, 1e-6);
}

TEST(PbrtDisplacement, OptionDisplacementEdgeScaleScalesEdgeLength) {
    PbrtTempDir dir;
    scene::TriangleMesh quad = phos::testing::unit_quad();
    quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    phos::testing::write_ply(dir.file("quad.ply"), quad, false);
    QuietLog quiet;
    const std::string shape =
        "WorldBegin\nShape \"plymesh\" \"string filename\" \"quad.ply\" \"float displacement\" 0.1 "
        "\"float edgelength\" 0.5\n";
    const scene::Scene plain = load_pbrt(dir.write("a.pbrt", shape));
    const scene::Scene finer =
        load_pbrt(dir.write("b.pbrt", "Option \"float displacementedgescale\" 0.25\n" + shape));
    EXPECT_LT(max_edge(plain.shapes.at(0).mesh), 0.5f);
    EXPECT_GE(max_edge(plain.shapes.at(0).mesh), 0.125f);
    EXPECT_LT(max_edge(finer.shapes.at(0).mesh), 0.125f);  // 0.5 x 0.25
    expect_pbrt_error(dir.write("c.pbrt", "Option \"float displacementedgescale\" 0\n" + shape), 1, 8,
                      "takes one positive float");
}

TEST(PbrtDisplacement, CheckerboardTextureGivesTwoHeights) {
    PbrtTempDir dir;
    const Loaded l = load_with_quad(
        dir,
        "Texture \"bumps\" \"float\" \"checkerboard\" \"float uscale\" 2 \"float vscale\" 2 "
        "\"float tex1\" 0.1 \"float tex2\" 0\n"
        "Shape \"plymesh\" \"string filename\" \"quad.ply\" \"texture displacement\" \"bumps\" "
        "\"float edgelength\" 0.05\n");
    EXPECT_EQ(l.warnings, 0);
    const scene::TriangleMesh& m = l.scene.shapes[0].mesh;
    EXPECT_LT(max_edge(m), 0.05f + 0.1f);  // steps between squares are stretched by the displacement
    int high = 0, low = 0;
    for (size_t i = 0; i < m.positions.size(); ++i) {
        const float z = m.positions[i].z;
        EXPECT_TRUE(z == 0.0f || std::fabs(z - 0.1f) < 1e-6f) << z;
        const Vec2 uv = m.uvs[i];
        const bool even = (int(std::floor(2 * uv.x)) + int(std::floor(2 * uv.y))) % 2 == 0;
        EXPECT_EQ(z > 0.05f, even) << uv.x << " " << uv.y;
        (z > 0.05f ? high : low)++;
    }
    EXPECT_GT(high, 100);
    EXPECT_GT(low, 100);
}

TEST(PbrtDisplacement, DefaultEdgeLengthIsOne) {
    PbrtTempDir dir;
    const Loaded l = load_with_quad(dir,
                                    "Shape \"plymesh\" \"string filename\" \"quad.ply\" "
                                    "\"float displacement\" 0\n");
    const scene::TriangleMesh& m = l.scene.shapes[0].mesh;
    EXPECT_LT(max_edge(m), 1.0f);
    EXPECT_GT(m.triangle_count(), 2u);  // the square's diagonal (1.41) and sides (1) were split
}

TEST(PbrtDisplacement, BadParametersAreLocatedErrors) {
    PbrtTempDir dir;
    QuietLog quiet;
    phos::testing::write_ply(dir.file("quad.ply"), phos::testing::unit_quad(), false);
    const std::string shape = "Shape \"plymesh\" \"string filename\" \"quad.ply\" ";
    expect_pbrt_error(dir.write("a.pbrt", "WorldBegin\n" + shape + "\"texture displacement\" \"nope\"\n"), 2,
                      46, "unknown float texture \"nope\"");
    expect_pbrt_error(
        dir.write("b.pbrt", "WorldBegin\n" + shape + "\"float displacement\" 1 \"float edgelength\" 0\n"), 2,
        69, "\"edgelength\" must be a positive length");
    expect_pbrt_error(
        dir.write("c.pbrt", "WorldBegin\n" + shape + "\"float displacement\" 1 \"float edgelength\" 1e-6\n"),
        2, 46, "too many triangles");
}

}  // namespace
}  // namespace phos::io::test
