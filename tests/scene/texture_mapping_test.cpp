// pbrt-v4's 2D texture mappings and the 3D point mapping (scene/texture_mapping.h), each against its
// formula: uv scale and offset; spherical (theta / pi, phi / 2pi) on the axes; cylindrical on the
// axes and along z; planar dot products with v1, v2; all in the texture space of the stored
// world-to-texture transform.
#include "scene/texture_mapping.h"

#include <gtest/gtest.h>

namespace phos::scene {
namespace {

TextureContext at(Vec3 p, Vec2 uv = {0, 0}) {
    TextureContext c;
    c.p = p;
    c.uv = uv;
    return c;
}

void expect_st(Vec2 got, Vec2 want) {
    EXPECT_NEAR(got.x, want.x, 1e-5f);
    EXPECT_NEAR(got.y, want.y, 1e-5f);
}

TEST(TextureMapping, UvScalesThenOffsets) {
    Texture t;
    t.u_scale = 2, t.v_scale = 3, t.u_offset = 0.5f, t.v_offset = -1;
    expect_st(map_2d(t, at({9, 9, 9}, {0.25f, 0.5f})), {1.0f, 0.5f});
}

TEST(TextureMapping, SphericalOnTheAxes) {
    Texture t;
    t.mapping = Texture::Mapping::Spherical;
    expect_st(map_2d(t, at({1, 0, 0})), {0.5f, 0.0f});   // theta = pi/2, phi = 0
    expect_st(map_2d(t, at({0, 3, 0})), {0.5f, 0.25f});  // phi = pi/2; the distance does not matter
    expect_st(map_2d(t, at({-1, 0, 0})), {0.5f, 0.5f});
    expect_st(map_2d(t, at({0, -2, 0})), {0.5f, 0.75f});
    expect_st(map_2d(t, at({0, 0, 5})), {0.0f, 0.0f});  // theta = 0
    EXPECT_NEAR(map_2d(t, at({0, 0, -5})).x, 1.0f, 1e-5f);
    expect_st(map_2d(t, at({1, 0, 1})), {0.25f, 0.0f});  // theta = pi/4
    expect_st(map_2d(t, at({0, 0, 0})), {0.0f, 0.0f});   // the centre itself: defined, finite
    // In texture space: the CTM at the Texture directive translated the sphere's centre to (1, 2, 3).
    t.texture_from_world = Transform::translate({1, 2, 3}).inverse();
    expect_st(map_2d(t, at({2, 2, 3})), {0.5f, 0.0f});
    expect_st(map_2d(t, at({1, 3, 3})), {0.5f, 0.25f});
}

TEST(TextureMapping, CylindricalAroundZ) {
    Texture t;
    t.mapping = Texture::Mapping::Cylindrical;
    expect_st(map_2d(t, at({1, 0, 0.25f})), {0.5f, 0.25f});  // (pi + 0) / 2pi, z
    expect_st(map_2d(t, at({0, 2, -3})), {0.75f, -3.0f});
    expect_st(map_2d(t, at({0, -2, 1})), {0.25f, 1.0f});
    EXPECT_NEAR(map_2d(t, at({-1, 1e-7f, 0})).x, 1.0f, 1e-5f);
    t.texture_from_world = Transform::scale({1, 1, 0.5f});
    expect_st(map_2d(t, at({1, 0, 4})), {0.5f, 2.0f});
}

TEST(TextureMapping, PlanarProjectsOnV1AndV2) {
    Texture t;
    t.mapping = Texture::Mapping::Planar;
    t.planar_s = {1, 1, 0};
    t.planar_t = {0, 0, 2};
    t.u_offset = 0.5f, t.v_offset = -1;
    t.u_scale = 7;  // uv's parameters do not apply
    expect_st(map_2d(t, at({1, 2, 3}, {0.9f, 0.9f})), {3.5f, 5.0f});
    t.texture_from_world = Transform::translate({-1, 0, 0});
    expect_st(map_2d(t, at({1, 2, 3})), {2.5f, 5.0f});
}

TEST(TextureMapping, PointMappingIsTheTextureSpacePoint) {
    Texture t;
    t.texture_from_world = Transform::scale({2, 2, 2}).inverse();
    const Vec3 q = map_3d(t, at({1, -4, 6}));
    EXPECT_NEAR(q.x, 0.5f, 1e-6f);
    EXPECT_NEAR(q.y, -2.0f, 1e-6f);
    EXPECT_NEAR(q.z, 3.0f, 1e-6f);
}

}  // namespace
}  // namespace phos::scene
