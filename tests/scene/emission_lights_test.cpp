// Glowing shapes become area lights (two-sided as the .scn loader asks, or one-sided) and lose their
// glow (no double counting).
#include "scene/emission_lights.h"

#include <gtest/gtest.h>

namespace phos::scene {
namespace {

TEST(EmissionLights, GlowingShapesBecomeAreaLights) {
    Scene s;
    Material plain, glow;
    plain.diffuse = Rgb(0.5f);
    glow.diffuse = Rgb(0.2f);
    glow.emission = Rgb(3, 2, 1);
    s.materials = {plain, glow};
    for (int m : {0, 1, 1}) {
        Shape sh;
        sh.kind = Shape::Kind::Sphere;
        sh.material = m;
        s.shapes.push_back(sh);
    }
    EXPECT_EQ(emissive_shapes_to_lights(s, /*two_sided=*/true), 2);
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.shapes[0].area_light, -1);
    for (int i : {1, 2}) {
        const Shape& sh = s.shapes[size_t(i)];
        ASSERT_GE(sh.area_light, 0);
        const Light& l = s.lights[size_t(sh.area_light)];
        EXPECT_EQ(l.kind, Light::Kind::Area);
        EXPECT_EQ(l.shape, i);
        EXPECT_EQ(l.color, Rgb(3, 2, 1));
        EXPECT_TRUE(l.two_sided);
        // The glow moved into the light: the shape's material keeps its albedo but not its emission.
        EXPECT_TRUE(s.materials[size_t(sh.material)].emission.is_black());
        EXPECT_EQ(s.materials[size_t(sh.material)].diffuse, Rgb(0.2f));
    }
    EXPECT_EQ(s.shapes[1].material, s.shapes[2].material);  // one copy per material
    EXPECT_EQ(emissive_shapes_to_lights(s, true), 0);       // idempotent
}

TEST(EmissionLights, OneSidedOnRequest) {
    Scene s;
    Material glow;
    glow.emission = Rgb(1.0f);
    s.materials = {glow};
    Shape sh;
    sh.kind = Shape::Kind::Sphere;
    sh.material = 0;
    s.shapes.push_back(sh);
    EXPECT_EQ(emissive_shapes_to_lights(s, /*two_sided=*/false), 1);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_FALSE(s.lights[0].two_sided);
}

}  // namespace
}  // namespace phos::scene
