// pbrt's mix material resolved at points (scene/material_mix.h): the amount's extremes, the share
// of points that get the second material, the same answer for the same point, nested mixes and a
// textured amount.
#include "scene/material_mix.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"

namespace phos::scene {
namespace {

// Materials 0 and 1 plain, 2 a mix of them with `amount`.
Scene mix_scene(float amount) {
    Scene s;
    s.materials.resize(3);
    s.materials[2].mix_a = 0;
    s.materials[2].mix_b = 1;
    s.materials[2].mix_amount = amount;
    return s;
}

Vec3 random_point(Sampler& rng) { return {10 * rng.next() - 5, 10 * rng.next() - 5, 10 * rng.next() - 5}; }

TEST(MaterialMix, PlainMaterialsAndTheAmountsExtremes) {
    Scene s = mix_scene(0);
    EXPECT_FALSE(s.materials[0].is_mix());
    EXPECT_TRUE(has_mix_materials(s));
    Sampler rng(1);
    for (int i = 0; i < 100; ++i) {
        const Vec3 p = random_point(rng);
        EXPECT_EQ(resolve_material(s, 1, p, {}), 1);
        EXPECT_EQ(resolve_material(s, 2, p, {}), 0);
    }
    s.materials[2].mix_amount = 1;
    for (int i = 0; i < 100; ++i) EXPECT_EQ(resolve_material(s, 2, random_point(rng), {}), 1);
    s.materials[2].mix_a = -1;
    EXPECT_FALSE(has_mix_materials(s));
}

TEST(MaterialMix, TheSecondMaterialsShareIsTheAmountAndAPointKeepsItsChoice) {
    for (float amount : {0.1f, 0.3f, 0.75f}) {
        const Scene s = mix_scene(amount);
        Sampler rng(2);
        const int n = 20000;
        int second = 0;
        for (int i = 0; i < n; ++i) {
            const Vec3 p = random_point(rng);
            const int m = resolve_material(s, 2, p, {});
            ASSERT_TRUE(m == 0 || m == 1);
            second += m == 1;
            ASSERT_EQ(resolve_material(s, 2, p, {0.3f, 0.8f}), m);  // a point's material is fixed
        }
        // Binomial: within 5 standard deviations.
        EXPECT_NEAR(double(second) / n, amount, 5 * std::sqrt(amount * (1 - amount) / n)) << amount;
    }
}

TEST(MaterialMix, NestedMixesAndATexturedAmount) {
    Scene s = mix_scene(0.5f);
    // Material 3: a mix of material 2 (itself a mix) and 0, always the first.
    Material outer;
    outer.mix_a = 2;
    outer.mix_b = 0;
    outer.mix_amount = 0;
    s.materials.push_back(outer);
    Sampler rng(3);
    int ones = 0;
    for (int i = 0; i < 1000; ++i) {
        const int m = resolve_material(s, 3, random_point(rng), {});
        ASSERT_TRUE(m == 0 || m == 1);
        ones += m == 1;
    }
    EXPECT_GT(ones, 400);
    EXPECT_LT(ones, 600);
    // An amount texture of 0 or 1: the first or second material wherever it says so.
    Texture zero, one;
    zero.value = Rgb(0.0f);
    one.value = Rgb(1.0f);
    s.textures = {zero, one};
    s.materials[2].mix_amount = 1;
    s.materials[2].mix_amount_texture = 0;
    EXPECT_EQ(resolve_material(s, 2, {1, 2, 3}, {}), 0);
    s.materials[2].mix_amount_texture = 1;
    EXPECT_EQ(resolve_material(s, 2, {1, 2, 3}, {}), 1);
}

}  // namespace
}  // namespace phos::scene
