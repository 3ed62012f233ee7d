// pbrt-v4's textures through scene::eval_texture, against closed forms: constant, bilerp at its
// corners and centre, mix at amounts 0, 1/2, 1 and textured, directionmix along and across its
// direction, 2D and 3D checkerboard parity, polka dots inside and outside a dot, fbm, wrinkled
// and windy as their noise sums, marble's spline end points and range, and the uv overload.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "scene/perlin_noise.h"
#include "scene/procedural_textures.h"
#include "scene/texture_eval.h"

namespace phos::scene {
namespace {

int add(Scene& s, Texture t) {
    s.textures.push_back(std::move(t));
    return int(s.textures.size()) - 1;
}

int constant(Scene& s, Rgb v) {
    Texture t;
    t.value = v;
    return add(s, t);
}

TextureContext at(Vec3 p, Vec2 uv = {0, 0}, Vec3 n = {0, 0, 1}) {
    TextureContext c;
    c.p = p;
    c.uv = uv;
    c.n = n;
    return c;
}

void expect_rgb(Rgb got, Rgb want, float eps = 1e-5f) {
    EXPECT_NEAR(got.r, want.r, eps);
    EXPECT_NEAR(got.g, want.g, eps);
    EXPECT_NEAR(got.b, want.b, eps);
}

TEST(ProceduralTextures, BilerpCornersAndCentre) {
    Scene s;
    Texture t;
    t.kind = Texture::Kind::Bilerp;
    t.corners = {Rgb(1, 0, 0), Rgb(0, 1, 0), Rgb(0, 0, 1), Rgb(1, 1, 1)};  // v00 v01 v10 v11
    const int b = add(s, t);
    expect_rgb(eval_texture(s, b, at({}, {0, 0})), Rgb(1, 0, 0));
    expect_rgb(eval_texture(s, b, at({}, {0, 1})), Rgb(0, 1, 0));
    expect_rgb(eval_texture(s, b, at({}, {1, 0})), Rgb(0, 0, 1));
    expect_rgb(eval_texture(s, b, at({}, {1, 1})), Rgb(1, 1, 1));
    expect_rgb(eval_texture(s, b, at({}, {0.5f, 0.5f})), Rgb(0.5f, 0.5f, 0.5f));
    expect_rgb(eval_texture(s, b, at({}, {0.25f, 0})), Rgb(0.75f, 0, 0.25f));
    // The uv overload is the same lookup.
    expect_rgb(eval_texture(s, b, Vec2(0.25f, 0)), Rgb(0.75f, 0, 0.25f));
}

TEST(ProceduralTextures, MixAtAmountsZeroHalfOneAndTextured) {
    Scene s;
    const int a = constant(s, Rgb(1, 0, 0)), b = constant(s, Rgb(0, 0, 1));
    Texture t;
    t.kind = Texture::Kind::Mix;
    t.tex1 = a, t.tex2 = b;
    t.amount_value = 0;
    const int m0 = add(s, t);
    t.amount_value = 0.5f;
    const int mh = add(s, t);
    t.amount_value = 1;
    const int m1 = add(s, t);
    t.amount = constant(s, Rgb(0.25f));
    const int mt = add(s, t);
    expect_rgb(eval_texture(s, m0, at({})), Rgb(1, 0, 0));
    expect_rgb(eval_texture(s, mh, at({})), Rgb(0.5f, 0, 0.5f));
    expect_rgb(eval_texture(s, m1, at({})), Rgb(0, 0, 1));
    expect_rgb(eval_texture(s, mt, at({})), Rgb(0.75f, 0, 0.25f));
}

TEST(ProceduralTextures, DirectionMixAlongAndAcrossItsDirection) {
    Scene s;
    Texture t;
    t.kind = Texture::Kind::DirectionMix;
    t.tex1 = constant(s, Rgb(1, 0, 0));
    t.tex2 = constant(s, Rgb(0, 1, 0));
    t.direction = {0, 1, 0};
    const int d = add(s, t);
    expect_rgb(eval_texture(s, d, at({}, {}, {0, 1, 0})), Rgb(1, 0, 0));   // aligned: tex1
    expect_rgb(eval_texture(s, d, at({}, {}, {0, -1, 0})), Rgb(1, 0, 0));  // |cos|: either side
    expect_rgb(eval_texture(s, d, at({}, {}, {1, 0, 0})), Rgb(0, 1, 0));   // perpendicular: tex2
    const float c = std::cos(kPi / 3);                                     // 60 degrees: half each
    expect_rgb(eval_texture(s, d, at({}, {}, {std::sin(kPi / 3), c, 0})), Rgb(0.5f, 0.5f, 0));
}

TEST(ProceduralTextures, CheckerboardParityIn2DAnd3D) {
    Scene s;
    Texture t;
    t.kind = Texture::Kind::Checkerboard;
    t.tex1 = constant(s, Rgb(1.0f));
    t.tex2 = constant(s, Rgb(0.0f));
    const int c2 = add(s, t);
    expect_rgb(eval_texture(s, c2, at({}, {0.5f, 0.5f})), Rgb(1.0f));
    expect_rgb(eval_texture(s, c2, at({}, {1.5f, 0.5f})), Rgb(0.0f));
    expect_rgb(eval_texture(s, c2, at({}, {-0.5f, 0.5f})), Rgb(0.0f));
    expect_rgb(eval_texture(s, c2, at({}, {-0.5f, -0.5f})), Rgb(1.0f));
    t.dimension = 3;
    t.texture_from_world = Transform::scale({2, 2, 2}).inverse();  // cells of 2 world units
    const int c3 = add(s, t);
    expect_rgb(eval_texture(s, c3, at({1, 1, 1}, {1.5f, 0.5f})), Rgb(1.0f));  // uv is not used
    expect_rgb(eval_texture(s, c3, at({3, 1, 1})), Rgb(0.0f));
    expect_rgb(eval_texture(s, c3, at({3, 3, 1})), Rgb(1.0f));
    expect_rgb(eval_texture(s, c3, at({3, 3, 3})), Rgb(0.0f));
    expect_rgb(eval_texture(s, c3, at({-1, 1, 1})), Rgb(0.0f));
    expect_rgb(eval_texture(s, c3, at({-1, -1, -1})), Rgb(0.0f));
    expect_rgb(eval_texture(s, c3, at({-1, -1, 1})), Rgb(1.0f));
    EXPECT_FALSE(checker_odd(Vec3(3e9f, 5e9f, 0.5f)));  // huge floats are even integers
    EXPECT_FALSE(checker_odd(Vec2(NAN, 0.5f)));
}

TEST(ProceduralTextures, DotsInsideAndOutsideADot) {
    Scene s;
    Texture t;
    t.kind = Texture::Kind::Dots;
    t.tex1 = constant(s, Rgb(1.0f));  // inside a dot
    t.tex2 = constant(s, Rgb(0.0f));  // outside
    const int d = add(s, t);
    int with_dot = 0, without = 0;
    for (int cell = 0; cell < 40; ++cell) {
        const float sc = float(cell), tc = float(cell % 7);
        const float s_centre = sc + 0.15f * perlin_noise(sc + 1.5f, tc + 2.8f, 0.5f);
        const float t_centre = tc + 0.15f * perlin_noise(sc + 4.5f, tc + 9.8f, 0.5f);
        // The cell's far corner region is at least 0.3 sqrt(2) > 0.35 from any dot centre.
        expect_rgb(eval_texture(s, d, at({}, {sc + 0.45f, tc + 0.45f})), Rgb(0.0f));
        if (perlin_noise(sc + 0.5f, tc + 0.5f, 0.5f) > 0) {
            ++with_dot;
            expect_rgb(eval_texture(s, d, at({}, {s_centre, t_centre})), Rgb(1.0f));
            expect_rgb(eval_texture(s, d, at({}, {s_centre + 0.34f, t_centre})), Rgb(1.0f));
            const float away = t_centre >= tc ? -0.36f : 0.36f;  // staying in the cell
            EXPECT_FALSE(inside_polka_dot({s_centre, t_centre + away}));
        } else {
            ++without;
            expect_rgb(eval_texture(s, d, at({}, {s_centre, t_centre})), Rgb(0.0f));
        }
    }
    EXPECT_GT(with_dot, 5);  // both kinds of cell were checked
    EXPECT_GT(without, 5);
}

TEST(ProceduralTextures, NoiseTexturesAreTheirSumsInTextureSpace) {
    Scene s;
    Texture t;
    t.texture_from_world = Transform::translate({0.5f, 0, 0});
    t.octaves = 5;
    t.roughness = 0.7f;
    t.kind = Texture::Kind::FBm;
    const int f = add(s, t);
    t.kind = Texture::Kind::Wrinkled;
    const int w = add(s, t);
    t.kind = Texture::Kind::Windy;
    const int y = add(s, t);
    const Vec3 p(1.2f, -0.4f, 3.3f), q = p + Vec3(0.5f, 0, 0);
    expect_rgb(eval_texture(s, f, at(p)), Rgb(fbm(q, 0.7f, 5)));
    expect_rgb(eval_texture(s, w, at(p)), Rgb(turbulence(q, 0.7f, 5)));
    expect_rgb(eval_texture(s, y, at(p)), Rgb(std::fabs(fbm(q * 0.1f, 0.5f, 3)) * fbm(q, 0.5f, 6)));
    EXPECT_NE(eval_texture(s, f, at(p)).r, 0.0f);
    // At the texture-space origin every octave's noise is 0: fbm and windy vanish, and turbulence
    // is pbrt's 0.2 omega^octaves.
    expect_rgb(eval_texture(s, f, at({-0.5f, 0, 0})), Rgb(0.0f));
    expect_rgb(eval_texture(s, y, at({-0.5f, 0, 0})), Rgb(0.0f));
    expect_rgb(eval_texture(s, w, at({-0.5f, 0, 0})), Rgb(0.2f * std::pow(0.7f, 5.0f)));
}

TEST(ProceduralTextures, MarbleSplineEndsAndRange) {
    // Without variation, t = 1/2 + sin(y) / 2: y = -pi/2 and pi/2 are the spline's end points (the
    // first and last control points), y = 0 the start of segment 3 (the fourth control point).
    expect_rgb(marble({0, -kPi / 2, 0}, 1, 0, 0.5f, 8), Rgb(0.87f, 0.87f, 0.9f), 1e-4f);
    expect_rgb(marble({0, kPi / 2, 0}, 1, 0, 0.5f, 8), Rgb(0.87f, 0.87f, 0.9f), 1e-4f);
    expect_rgb(marble({5, 0, -2}, 1, 0, 0.5f, 8), Rgb(0.75f, 0.75f, 0.75f), 1e-4f);
    expect_rgb(marble({0, kPi / 4, 0}, 2, 0, 0.5f, 8), Rgb(0.87f, 0.87f, 0.9f), 1e-4f);  // scale 2
    Sampler rng(3);
    float lo = 1, hi = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 p(rng.next() * 20, rng.next() * 20, rng.next() * 20);
        const Rgb c = marble(p, 1.5f, 0.8f, 0.5f, 8);
        for (int k = 0; k < 3; ++k) {
            ASSERT_GE(c[k], 0.3f - 1e-6f);
            ASSERT_LE(c[k], 0.9f + 1e-6f);
            lo = std::min(lo, c[k]);
            hi = std::max(hi, c[k]);
        }
    }
    EXPECT_LT(lo, 0.45f);  // the dark vein (0.2, 0.2, 0.33) pulls the spline down
    EXPECT_GT(hi, 0.85f);
    // Through eval_texture, in texture space.
    Scene s;
    Texture t;
    t.kind = Texture::Kind::Marble;
    t.variation = 0;
    t.texture_from_world = Transform::translate({0, kPi / 2, 0});
    expect_rgb(eval_texture(s, add(s, t), at({0, 0, 0})), Rgb(0.87f, 0.87f, 0.9f), 1e-4f);
}

TEST(ProceduralTextures, ImageUsesItsMapping) {
    Scene s;
    Texture t;
    t.kind = Texture::Kind::Image;
    auto img = std::make_shared<TextureImage>();
    img->width = 2, img->height = 1;
    img->texels = {Rgb(1, 0, 0), Rgb(0, 0, 1)};
    t.image = img;
    t.wrap = Texture::Wrap::Clamp;
    t.mapping = Texture::Mapping::Planar;  // s = x
    const int i = add(s, t);
    expect_rgb(eval_texture(s, i, at({0.1f, 0, 0}, {0.9f, 0.5f})), Rgb(1, 0, 0));
    expect_rgb(eval_texture(s, i, at({0.9f, 0, 0}, {0.1f, 0.5f})), Rgb(0, 0, 1));
}

}  // namespace
}  // namespace phos::scene
