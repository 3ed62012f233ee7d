// The MIP map of image textures (scene/mip_map.h) against its definitions: each level the exact
// 2x2 box average of the one below (and of the image, for the top); non-power-of-two images
// resampled up keeping a constant; trilinear lookups linear in the continuous level between two
// levels' bilinear lookups; EWA of a constant image is that constant, of a fine checkerboard seen
// from far away its mean, and an over-long footprint clamped to max_anisotropy; zero footprints
// are the finest level's lookups; the mapping derivatives (texture_mapping.h) and the filtered
// image texture in eval_texture.
#include "scene/mip_map.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "scene/scene.h"
#include "scene/texture_eval.h"
#include "scene/texture_mapping.h"

namespace phos::scene {
namespace {

TextureImage random_image(int w, int h, uint64_t seed) {
    TextureImage im;
    im.width = w;
    im.height = h;
    Sampler s(seed, 0);
    for (int i = 0; i < w * h; ++i) im.texels.push_back(Rgb(s.next(), s.next(), s.next()));
    return im;
}

// A checkerboard of `cell`-texel squares, 0 and 1.
TextureImage checker(int n, int cell) {
    TextureImage im;
    im.width = im.height = n;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) im.texels.push_back(Rgb(float((x / cell + y / cell) % 2)));
    return im;
}

void expect_rgb_near(Rgb a, Rgb b, float tol) {
    EXPECT_NEAR(a.r, b.r, tol);
    EXPECT_NEAR(a.g, b.g, tol);
    EXPECT_NEAR(a.b, b.b, tol);
}

TEST(MipMap, LevelsAreExactBoxAverages) {
    const TextureImage im = random_image(8, 4, 3);
    const MipMap mip(im, Texture::Wrap::Repeat);
    ASSERT_EQ(mip.levels(), 4);  // 8x4, 4x2, 2x1, 1x1
    const int sizes[4][2] = {{8, 4}, {4, 2}, {2, 1}, {1, 1}};
    for (int l = 0; l < 4; ++l) {
        EXPECT_EQ(mip.level(l).width, sizes[l][0]);
        EXPECT_EQ(mip.level(l).height, sizes[l][1]);
    }
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) EXPECT_EQ(mip.level(0).at(x, y).r, im.at(x, y).r);
    for (int l = 1; l < 3; ++l) {
        const TextureImage &a = mip.level(l - 1), &b = mip.level(l);
        for (int y = 0; y < b.height; ++y)
            for (int x = 0; x < b.width; ++x) {
                const Rgb want = (a.at(2 * x, 2 * y) + a.at(2 * x + 1, 2 * y) + a.at(2 * x, 2 * y + 1) +
                                  a.at(2 * x + 1, 2 * y + 1)) /
                                 4.0f;
                EXPECT_EQ(b.at(x, y).r, want.r);
                EXPECT_EQ(b.at(x, y).g, want.g);
                EXPECT_EQ(b.at(x, y).b, want.b);
            }
    }
    // 2x1 -> 1x1: the single row counts twice, so the top is the mean of the two texels.
    const Rgb top = (mip.level(2).at(0, 0) + mip.level(2).at(1, 0)) * 0.5f;
    expect_rgb_near(mip.level(3).at(0, 0), top, 1e-7f);
    // And the top is the mean of the whole image (box filters compose).
    Rgb mean(0.0f);
    for (const Rgb& c : im.texels) mean += c / 32.0f;
    expect_rgb_near(mip.level(3).at(0, 0), mean, 1e-6f);
}

TEST(MipMap, NonPowerOfTwoImagesAreResampledUpKeepingConstants) {
    TextureImage im;
    im.width = 3;
    im.height = 5;
    im.texels.assign(15, Rgb(0.25f, 0.5f, 2.0f));
    for (const Texture::Wrap wrap : {Texture::Wrap::Repeat, Texture::Wrap::Clamp}) {
        const MipMap mip(im, wrap);
        ASSERT_EQ(mip.levels(), 4);  // 4x8, 2x4, 1x2, 1x1
        EXPECT_EQ(mip.level(0).width, 4);
        EXPECT_EQ(mip.level(0).height, 8);
        for (int l = 0; l < mip.levels(); ++l)
            for (const Rgb& c : mip.level(l).texels) expect_rgb_near(c, Rgb(0.25f, 0.5f, 2.0f), 1e-5f);
    }
    // The windowed sinc interpolates: resampling to the same size keeps the image.
    const TextureImage r = random_image(6, 6, 9);
    const TextureImage same = resample_up(r, 6, 6, Texture::Wrap::Repeat);
    for (size_t i = 0; i < r.texels.size(); ++i) expect_rgb_near(same.texels[i], r.texels[i], 1e-6f);
}

TEST(MipMap, ZeroFootprintIsTheFinestLevel) {
    const TextureImage im = random_image(16, 16, 5);
    const MipMap mip(im, Texture::Wrap::Repeat);
    const Vec2 st(0.37f, 0.81f);
    const Rgb bilinear = lookup_bilinear(im, st.x * 16, st.y * 16, Texture::Wrap::Repeat);
    for (const Texture::Filter f :
         {Texture::Filter::Bilinear, Texture::Filter::Trilinear, Texture::Filter::Ewa}) {
        const Rgb got = mip.filter(f, st, {0, 0}, {0, 0}, 8);
        EXPECT_EQ(got.r, bilinear.r);
        EXPECT_EQ(got.g, bilinear.g);
        EXPECT_EQ(got.b, bilinear.b);
    }
    // Point: the nearest texel, (0.37 * 16 - 0.5, 0.81 * 16 - 0.5) = (5.42, 12.46) -> (5, 12).
    const Rgb p = mip.filter(Texture::Filter::Point, st, {0, 0}, {0, 0}, 8);
    EXPECT_EQ(p.r, im.at(5, 12).r);
}

TEST(MipMap, TrilinearIsLinearInTheLevel) {
    const TextureImage im = random_image(16, 16, 7);
    const MipMap mip(im, Texture::Wrap::Repeat);  // 5 levels
    const Vec2 st(0.3f, 0.6f);
    const Rgb l1 = mip.bilerp(1, st), l2 = mip.bilerp(2, st);
    ASSERT_GT(std::fabs(l1.g - l2.g), 1e-3f);
    for (const float level : {1.0f, 1.25f, 1.5f, 1.9f}) {
        // width = 2 max|dst| = 2^(level - 4)
        const float width = std::exp2(level - 4);
        const Rgb got = mip.filter(Texture::Filter::Trilinear, st, {0.5f * width, 0}, {0, 0.1f * width}, 8);
        const float d = level - 1;
        expect_rgb_near(got, l1 * (1 - d) + l2 * d, 2e-6f);
        // Bilinear at the same footprint stays on the lower level.
        expect_rgb_near(mip.filter(Texture::Filter::Bilinear, st, {0.5f * width, 0}, {0, 0.1f * width}, 8),
                        l1, 1e-7f);
    }
    // A footprint wider than the image: the top texel.
    const Rgb top = mip.filter(Texture::Filter::Trilinear, st, {2, 0}, {0, 2}, 8);
    EXPECT_EQ(top.r, mip.level(4).at(0, 0).r);
}

TEST(MipMap, EwaOfAConstantIsTheConstant) {
    TextureImage im;
    im.width = 32;
    im.height = 16;
    im.texels.assign(512, Rgb(0.3f, 0.7f, 1.5f));
    const MipMap mip(im, Texture::Wrap::Repeat);
    const Vec2 footprints[][2] = {{{0.001f, 0.0f}, {0.0f, 0.001f}},
                                  {{0.05f, 0.02f}, {-0.01f, 0.03f}},
                                  {{0.3f, 0.0f}, {0.0f, 0.001f}},
                                  {{0.02f, 0.02f}, {0.02f, -0.0199f}}};
    for (const auto& f : footprints)
        for (const Vec2 st : {Vec2(0.1f, 0.2f), Vec2(0.97f, 0.5f), Vec2(-3.3f, 7.1f)})
            expect_rgb_near(mip.filter(Texture::Filter::Ewa, st, f[0], f[1], 8), Rgb(0.3f, 0.7f, 1.5f),
                            2e-6f);
}

TEST(MipMap, EwaOfAFineCheckerboardFromFarAwayIsItsMean) {
    const TextureImage im = checker(64, 1);
    const MipMap mip(im, Texture::Wrap::Repeat);
    Sampler s(11, 0);
    for (int i = 0; i < 50; ++i) {
        const Vec2 st(s.next(), s.next());
        // Strong minification, isotropic and anisotropic (up to 4:1): axes of 0.8 to 10 texels.
        const float a = 0.05f + 0.1f * s.next(), b = a * (0.25f + 0.75f * s.next());
        const float phi = 2 * kPi * s.next();
        const Vec2 d0(a * std::cos(phi), a * std::sin(phi)), d1(-b * std::sin(phi), b * std::cos(phi));
        const Rgb v = mip.filter(Texture::Filter::Ewa, st, d0, d1, 8);
        EXPECT_NEAR(v.r, 0.5f, 0.02f) << "st " << st.x << " " << st.y;
        const Rgb t = mip.filter(Texture::Filter::Trilinear, st, d0, d1, 8);
        EXPECT_NEAR(t.r, 0.5f, 0.02f);
    }
    // A footprint of a texel's size sees the checkerboard: EWA at a texel centre leans to its value.
    const float texel = 1.0f / 64;
    const Vec2 centre(10.5f * texel, 20.5f * texel);  // texel (10, 20): (10 + 20) even -> 0
    EXPECT_LT(mip.filter(Texture::Filter::Ewa, centre, {0.25f * texel, 0}, {0, 0.25f * texel}, 8).r, 0.4f);
}

TEST(MipMap, EwaClampsTheAnisotropy) {
    const TextureImage im = random_image(64, 64, 13);
    const MipMap mip(im, Texture::Wrap::Repeat);
    const Vec2 st(0.4f, 0.55f);
    // 100:1 with max_anisotropy 8 is the ellipse of axes 0.2 and 0.2 / 8.
    const Rgb clamped = mip.filter(Texture::Filter::Ewa, st, {0.2f, 0}, {0, 0.002f}, 8);
    const Rgb want = mip.filter(Texture::Filter::Ewa, st, {0.2f, 0}, {0, 0.025f}, 8);
    expect_rgb_near(clamped, want, 1e-5f);
    // Without the clamp (a large max_anisotropy) the thin ellipse reads a finer level: different.
    const Rgb thin = mip.filter(Texture::Filter::Ewa, st, {0.2f, 0}, {0, 0.002f}, 1000);
    EXPECT_GT(std::fabs(thin.r - clamped.r) + std::fabs(thin.g - clamped.g) + std::fabs(thin.b - clamped.b),
              1e-3f);
    // The axes' order and signs do not matter.
    expect_rgb_near(mip.filter(Texture::Filter::Ewa, st, {0, -0.002f}, {-0.2f, 0}, 8), clamped, 1e-6f);
}

TEST(MipMap, MappingDerivativesFollowTheMapping) {
    Texture t;
    t.u_scale = 2;
    t.v_scale = -3;
    TextureContext c;
    c.dudx = 0.1f, c.dudy = 0.2f, c.dvdx = 0.3f, c.dvdy = 0.4f;
    St2Derivatives d = map_2d_derivatives(t, c);
    EXPECT_FLOAT_EQ(d.dsdx, 0.2f);
    EXPECT_FLOAT_EQ(d.dsdy, 0.4f);
    EXPECT_FLOAT_EQ(d.dtdx, -0.9f);
    EXPECT_FLOAT_EQ(d.dtdy, -1.2f);
    // Planar: s = p . v1, t = p . v2.
    t.mapping = Texture::Mapping::Planar;
    t.planar_s = Vec3(1, 1, 0);
    t.planar_t = Vec3(0, 0, 2);
    c.dpdx = Vec3(0.1f, 0.2f, 0.3f);
    c.dpdy = Vec3(-0.1f, 0, 1);
    d = map_2d_derivatives(t, c);
    EXPECT_FLOAT_EQ(d.dsdx, 0.3f);
    EXPECT_FLOAT_EQ(d.dtdx, 0.6f);
    EXPECT_FLOAT_EQ(d.dsdy, -0.1f);
    EXPECT_FLOAT_EQ(d.dtdy, 2.0f);
    // Spherical and cylindrical against finite differences of map_2d.
    for (const Texture::Mapping m : {Texture::Mapping::Spherical, Texture::Mapping::Cylindrical}) {
        t.mapping = m;
        c.p = Vec3(0.6f, 0.3f, 0.5f);
        c.dpdx = Vec3(1e-3f, -2e-3f, 0.5e-3f);
        c.dpdy = Vec3(0.5e-3f, 1e-3f, -1e-3f);
        d = map_2d_derivatives(t, c);
        TextureContext cx = c, cy = c;
        cx.p = c.p + c.dpdx;
        cy.p = c.p + c.dpdy;
        const Vec2 s0 = map_2d(t, c), sx = map_2d(t, cx), sy = map_2d(t, cy);
        EXPECT_NEAR(d.dsdx, sx.x - s0.x, 2e-5f);
        EXPECT_NEAR(d.dtdx, sx.y - s0.y, 2e-5f);
        EXPECT_NEAR(d.dsdy, sy.x - s0.x, 2e-5f);
        EXPECT_NEAR(d.dtdy, sy.y - s0.y, 2e-5f);
    }
}

TEST(MipMap, FilteredImageTextureReadsTheFootprint) {
    Scene scene;
    Texture t;
    t.kind = Texture::Kind::Image;
    auto im = std::make_shared<TextureImage>(checker(64, 1));
    t.image = im;
    t.filter = Texture::Filter::Ewa;
    t.mip_map = std::make_shared<const MipMap>(*im, t.wrap);
    scene.textures.push_back(t);
    t.filter = Texture::Filter::Bilinear;
    scene.textures.push_back(t);
    EXPECT_TRUE(reads_footprint(scene));
    TextureContext c;
    c.uv = Vec2(10.5f / 64, 1 - 20.5f / 64);  // texel (10, 20), value 0
    EXPECT_EQ(eval_texture(scene, 0, c).r, 0.0f);
    EXPECT_EQ(eval_texture(scene, 1, c).r, 0.0f);
    c.dudx = 0.1f, c.dvdy = 0.05f;  // minified: the EWA texture averages, the bilinear one does not
    EXPECT_NEAR(eval_texture(scene, 0, c).r, 0.5f, 0.02f);
    EXPECT_EQ(eval_texture(scene, 1, c).r, 0.0f);
    scene.textures.pop_back();
    scene.textures[0].filter = Texture::Filter::Bilinear;
    EXPECT_FALSE(reads_footprint(scene));
}

}  // namespace
}  // namespace phos::scene
