// Tests of shading::SurfaceWalk: the walk to the next scattering surface steps through medium
// interfaces, sums the distance travelled over every segment, counts its queries and gives up on
// a path that crosses too many interfaces.
#include "shading/surface_walk.h"

#include <gtest/gtest.h>

#include "support/shapes.h"

namespace phos::shading {
namespace {

// Quads of half-size 1 facing -z at the given depths; material 0 is an interface, 1 scatters.
scene::Scene layers(const std::vector<float>& interfaces, float wall) {
    scene::Scene s;
    scene::Material interface;
    interface.interface_only = true;
    scene::Material diffuse;
    diffuse.diffuse = Rgb(0.5f);
    s.materials = {interface, diffuse};
    const auto quad_at = [](float z, int material) {
        scene::Shape q = testing::quad({-1, -1, z}, {-1, 1, z}, {1, 1, z}, {1, -1, z});
        q.material = material;
        return q;
    };
    for (float z : interfaces) s.shapes.push_back(quad_at(z, 0));
    s.shapes.push_back(quad_at(wall, 1));
    return s;
}

Ray ray_along_z(Vec3 origin, float speed) {
    Ray r;
    r.origin = origin;
    r.dir = Vec3(0, 0, speed);
    return r;
}

TEST(SurfaceWalk, StepsThroughInterfacesToTheScatteringSurface) {
    const scene::Scene s = layers({1.0f, 2.0f}, 3.0f);
    const accel::EmbreeScene accel(s);
    SurfaceWalk walk(accel);
    Ray ray = ray_along_z({0.25f, -0.5f, 0}, 2.0f);  // |dir| = 2: t is half the distance
    accel::SurfaceHit hit;
    ASSERT_EQ(walk.next(ray, hit), SurfaceWalk::Event::Surface);
    EXPECT_EQ(hit.material, 1);
    EXPECT_NEAR(hit.p.z, 3.0f, 1e-4f);
    EXPECT_NEAR(walk.distance(), 3.0f, 1e-4f);
    EXPECT_EQ(walk.crossings(), 2);
    EXPECT_EQ(walk.rays(), 3u);
    // The returned ray is the last segment's: it starts at the second interface, same direction.
    EXPECT_NEAR(ray.origin.z, 2.0f, 1e-3f);
    EXPECT_EQ(ray.dir.z, 2.0f);
    EXPECT_NEAR(hit.t * length(ray.dir), 1.0f, 1e-3f);
}

TEST(SurfaceWalk, EscapesAndKeepsCountingOverTheWholePath) {
    const scene::Scene s = layers({1.0f}, 3.0f);
    const accel::EmbreeScene accel(s);
    SurfaceWalk walk(accel);
    Ray ray = ray_along_z({0, 0, 0}, 1.0f);
    accel::SurfaceHit hit;
    ASSERT_EQ(walk.next(ray, hit), SurfaceWalk::Event::Surface);
    // Back towards -z from the wall: through the interface again, then out of the scene.
    ray = accel::spawn_ray(hit, Vec3(0, 0, -1));
    EXPECT_EQ(walk.next(ray, hit), SurfaceWalk::Event::Escaped);
    EXPECT_EQ(walk.crossings(), 2);
    EXPECT_EQ(walk.rays(), 4u);                 // interface, wall, interface, miss
    EXPECT_NEAR(walk.distance(), 5.0f, 1e-3f);  // 3 there, 2 back to the interface (not the escape)
    EXPECT_EQ(ray.dir.z, -1.0f);
}

TEST(SurfaceWalk, GivesUpAfterTooManyCrossings) {
    std::vector<float> many;
    for (int i = 0; i <= SurfaceWalk::kMaxCrossings; ++i) many.push_back(1.0f + 0.01f * float(i));
    const scene::Scene s = layers(many, 10.0f);
    const accel::EmbreeScene accel(s);
    SurfaceWalk walk(accel);
    Ray ray = ray_along_z({0, 0, 0}, 1.0f);
    accel::SurfaceHit hit;
    EXPECT_EQ(walk.next(ray, hit), SurfaceWalk::Event::Lost);
    EXPECT_EQ(walk.crossings(), SurfaceWalk::kMaxCrossings + 1);

    // One interface fewer and the wall is reached.
    many.pop_back();
    const scene::Scene s2 = layers(many, 10.0f);
    const accel::EmbreeScene accel2(s2);
    SurfaceWalk walk2(accel2);
    ray = ray_along_z({0, 0, 0}, 1.0f);
    EXPECT_EQ(walk2.next(ray, hit), SurfaceWalk::Event::Surface);
    EXPECT_EQ(hit.material, 1);
}

}  // namespace
}  // namespace phos::shading
