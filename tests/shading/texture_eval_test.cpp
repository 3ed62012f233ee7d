// Tests of texture evaluation (shading/texture_eval.h): bilinear image lookup, wrap modes, uv
// mapping, checkerboard and scale textures, and their use by the Bsdf (diffuse albedo, diffuse
// transmittance, a coated material's slab albedo).
#include "shading/texture_eval.h"

#include <gtest/gtest.h>

#include "shading/bsdf.h"
#include "spectral_test_util.h"

namespace phos::shading {
namespace {

using scene::Texture;

// 2 x 2 image, row 0 at the top: top-left red, top-right green, bottom-left blue, bottom-right white.
std::shared_ptr<scene::TextureImage> quad_image() {
    auto img = std::make_shared<scene::TextureImage>();
    img->width = 2;
    img->height = 2;
    img->texels = {Rgb(1, 0, 0), Rgb(0, 1, 0), Rgb(0, 0, 1), Rgb(1, 1, 1)};
    return img;
}

scene::Scene scene_with(Texture t) {
    scene::Scene s;
    s.textures.push_back(std::move(t));
    return s;
}

Texture image_texture(Texture::Wrap wrap) {
    Texture t;
    t.kind = Texture::Kind::Image;
    t.image = quad_image();
    t.wrap = wrap;
    return t;
}

void expect_rgb(Rgb a, Rgb b, float tol = 1e-5f) {
    EXPECT_NEAR(a.r, b.r, tol);
    EXPECT_NEAR(a.g, b.g, tol);
    EXPECT_NEAR(a.b, b.b, tol);
}

TEST(TextureEval, ConstantAndNoTexture) {
    Texture t;
    t.value = Rgb(0.2f, 0.3f, 0.4f);
    const auto s = scene_with(t);
    expect_rgb(eval_texture(s, 0, Vec2(0.3f, 0.9f)), t.value);
    expect_rgb(eval_texture(s, -1, Vec2(0.3f, 0.9f)), Rgb(1.0f));
    expect_rgb(eval_texture(s, 7, Vec2(0.3f, 0.9f)), Rgb(1.0f));  // bad index: no crash
}

TEST(TextureEval, BilinearAtTexelCentresAndBetween) {
    const auto s = scene_with(image_texture(Texture::Wrap::Clamp));
    // v grows upwards: v = 0.75 is the top row.
    expect_rgb(eval_texture(s, 0, Vec2(0.25f, 0.75f)), Rgb(1, 0, 0));
    expect_rgb(eval_texture(s, 0, Vec2(0.75f, 0.75f)), Rgb(0, 1, 0));
    expect_rgb(eval_texture(s, 0, Vec2(0.25f, 0.25f)), Rgb(0, 0, 1));
    expect_rgb(eval_texture(s, 0, Vec2(0.75f, 0.25f)), Rgb(1, 1, 1));
    // Centre: the mean of all four; halfway along the top row: mean of red and green.
    expect_rgb(eval_texture(s, 0, Vec2(0.5f, 0.5f)), Rgb(0.5f, 0.5f, 0.5f));
    expect_rgb(eval_texture(s, 0, Vec2(0.5f, 0.75f)), Rgb(0.5f, 0.5f, 0));
    // A quarter of the way from red to green texel centre.
    expect_rgb(eval_texture(s, 0, Vec2(0.375f, 0.75f)), Rgb(0.75f, 0.25f, 0));
}

TEST(TextureEval, WrapModes) {
    const auto rep = scene_with(image_texture(Texture::Wrap::Repeat));
    const auto clamp = scene_with(image_texture(Texture::Wrap::Clamp));
    const auto black = scene_with(image_texture(Texture::Wrap::Black));
    // Repeat: periodic in both directions, and the edge between tiles blends across them.
    for (Vec2 uv : {Vec2(0.3f, 0.6f), Vec2(0.8f, 0.1f)}) {
        expect_rgb(eval_texture(rep, 0, uv + Vec2(1, 0)), eval_texture(rep, 0, uv));
        expect_rgb(eval_texture(rep, 0, uv + Vec2(-3, 2)), eval_texture(rep, 0, uv), 1e-4f);
    }
    // At u = 0 on the top row: halfway between red (left) and green (wrapped from the right).
    expect_rgb(eval_texture(rep, 0, Vec2(0.0f, 0.75f)), Rgb(0.5f, 0.5f, 0));
    // Clamp: the edge texel extends outwards.
    expect_rgb(eval_texture(clamp, 0, Vec2(0.0f, 0.75f)), Rgb(1, 0, 0));
    expect_rgb(eval_texture(clamp, 0, Vec2(-5.0f, 0.75f)), Rgb(1, 0, 0));
    expect_rgb(eval_texture(clamp, 0, Vec2(0.75f, 7.0f)), Rgb(0, 1, 0));
    // Black: outside texels are black, so the edge fades to half and beyond is black.
    expect_rgb(eval_texture(black, 0, Vec2(0.0f, 0.75f)), Rgb(0.5f, 0, 0));
    expect_rgb(eval_texture(black, 0, Vec2(-0.5f, 0.75f)), Rgb(0.0f));
    // The low-level lookup agrees (texel coordinates, row 0 at the top).
    expect_rgb(lookup_bilinear(*quad_image(), 0.5f, 0.5f, Texture::Wrap::Clamp), Rgb(1, 0, 0));
    expect_rgb(lookup_bilinear(*quad_image(), 1.0f, 1.5f, Texture::Wrap::Clamp), Rgb(0.5f, 0.5f, 1));
}

TEST(TextureEval, UvMappingAndInvertV) {
    Texture t = image_texture(Texture::Wrap::Clamp);
    t.u_scale = 0.5f;
    t.u_offset = 0.5f;  // u = 0.5 -> 0.75 (right column)
    t.v_scale = 2.0f;
    t.v_offset = -0.25f;  // v = 0.5 -> 0.75 (top row)
    t.value = Rgb(2.0f);  // image multiplier
    expect_rgb(eval_texture(scene_with(t), 0, Vec2(0.5f, 0.5f)), Rgb(0, 2, 0));
    Texture inv = image_texture(Texture::Wrap::Clamp);
    inv.invert_v = true;  // v = 0.25 is now the top row
    expect_rgb(eval_texture(scene_with(inv), 0, Vec2(0.25f, 0.25f)), Rgb(1, 0, 0));
}

TEST(TextureEval, CheckerboardAndScale) {
    scene::Scene s;
    Texture a;
    a.value = Rgb(0.2f);
    Texture b;
    b.value = Rgb(0.9f);
    s.textures = {a, b};
    Texture check;
    check.kind = Texture::Kind::Checkerboard;
    check.tex1 = 0;
    check.tex2 = 1;
    check.u_scale = check.v_scale = 4;  // 4 x 4 squares over the unit square
    s.textures.push_back(check);
    expect_rgb(eval_texture(s, 2, Vec2(0.1f, 0.1f)), Rgb(0.2f));
    expect_rgb(eval_texture(s, 2, Vec2(0.3f, 0.1f)), Rgb(0.9f));
    expect_rgb(eval_texture(s, 2, Vec2(0.3f, 0.3f)), Rgb(0.2f));
    expect_rgb(eval_texture(s, 2, Vec2(-0.1f, 0.1f)), Rgb(0.9f));  // negative coordinates alternate too
    Texture plain = check;                                         // values instead of textures
    plain.tex1 = plain.tex2 = -1;
    plain.value = Rgb(1, 0, 0);
    plain.value2 = Rgb(0, 0, 1);
    s.textures.push_back(plain);
    expect_rgb(eval_texture(s, 3, Vec2(0.3f, 0.1f)), Rgb(0, 0, 1));
    Texture scale;
    scale.kind = Texture::Kind::Scale;
    scale.tex1 = 2;
    scale.value = Rgb(0.5f);
    s.textures.push_back(scale);
    expect_rgb(eval_texture(s, 4, Vec2(0.3f, 0.1f)), Rgb(0.45f));
    Texture cyc;  // a malformed self-reference must not recurse forever
    cyc.kind = Texture::Kind::Scale;
    cyc.tex1 = 5;
    s.textures.push_back(cyc);
    EXPECT_TRUE(eval_texture(s, 5, Vec2(0.3f, 0.1f)).is_finite());
}

// The texture multiplies the diffuse colour, and the BSDF's spectral values are that colour's
// spectrum (the table fit, as textures are upsampled per hit): at every wavelength, and through
// the film. A grey (white) texel keeps the value flat.
TEST(TextureEval, BsdfDiffuseAlbedoIsTextured) {
    auto s = scene_with(image_texture(Texture::Wrap::Repeat));
    scene::Material m;
    m.diffuse = Rgb(0.5f);
    m.diffuse_texture = 0;
    accel::SurfaceHit h;
    h.ng = h.ns = Vec3(0, 0, 1);
    h.uv = Vec2(0.25f, 0.25f);  // blue texel
    const Bsdf b(m, h, s);
    const Vec3 up(0, 0, 1);
    expect_rgb(b.diffuse_colour(), Rgb(0, 0, 0.5f));
    const spectrum::RgbSpectrum blue(Rgb(0, 0, 0.5f), spectrum::RgbSpectrum::Use::Albedo,
                                     spectrum::RgbSpectrum::Fit::Table);
    for (int k = 0; k < 16; ++k) {
        const Wavelengths lambda = spectral::stratified_lambda(k, 16);
        EXPECT_EQ(b.diffuse_albedo(lambda), blue.sample(lambda));
        EXPECT_TRUE(spectral::spectra_near(b.eval(up, up, lambda), blue.sample(lambda) * kInvPi, 1e-6));
    }
    // Lit by RGB white, through the film: (0, 0, 0.5) / pi, within the table fit's 3e-3 of the
    // RGB (and ~1e-4 of Monte Carlo over 4096 x 4 stratified wavelengths).
    const Rgb colour = spectral::film_colour(
        [&](const Wavelengths& l) { return b.eval(up, up, l) * spectral::illuminant(Rgb(1.0f), l); });
    expect_rgb(colour, Rgb(0, 0, 0.5f * kInvPi), 4e-3f * kInvPi);

    h.uv = Vec2(0.75f, 0.25f);  // white texel: kd stays grey 0.5
    const Bsdf w(m, h, s);
    expect_rgb(w.diffuse_colour(), Rgb(0.5f));
    EXPECT_TRUE(spectral::flat_near(w.eval(up, up, spectral::fixed_lambda()), 0.5f * kInvPi, 1e-7));
}

// pbrt-v4's diffusetransmission with a textured transmittance: the Lambertian transmission lobe
// is scale x texel at each hit (f = T / pi for wi on the far side), clamped to [0, 1] as pbrt-v4
// clamps it; the reflection lobe keeps its own value.
TEST(TextureEval, BsdfDiffuseTransmittanceIsTextured) {
    auto s = scene_with(image_texture(Texture::Wrap::Repeat));
    scene::Material m;
    m.diffuse = Rgb(0.25f);
    m.diffuse_transmission = Rgb(1.5f);  // the material's scale; texels above 1/1.5 clamp to 1
    m.diffuse_transmission_texture = 0;
    accel::SurfaceHit h;
    h.ng = h.ns = Vec3(0, 0, 1);
    const Vec3 up(0, 0, 1), down(0, 0, -1);
    const Wavelengths lambda = spectral::fixed_lambda();
    h.uv = Vec2(0.25f, 0.25f);  // blue texel: T = (0, 0, 1)
    const Bsdf blue(m, h, s);
    const spectrum::RgbSpectrum t_blue(Rgb(0, 0, 1), spectrum::RgbSpectrum::Use::Albedo,
                                       spectrum::RgbSpectrum::Fit::Table);
    EXPECT_TRUE(spectral::spectra_near(blue.eval(up, down, lambda), t_blue.sample(lambda) * kInvPi, 1e-6));
    EXPECT_TRUE(spectral::flat_near(blue.eval(up, up, lambda), 0.25f * kInvPi, 1e-6));
    h.uv = Vec2(0.75f, 0.25f);  // white texel: T = 1 (1.5 clamped)
    const Bsdf white(m, h, s);
    EXPECT_TRUE(spectral::flat_near(white.eval(up, down, lambda), kInvPi, 1e-6));
}

// A coated diffuse material whose slab albedo is a texture: the slab scatters where the texel is
// white and not where it is black, so the layered BSDF's value differs between the two texels
// (the slab's medium is thick here: 1 mean free path), and an untextured material with the
// texel's albedo gives the same value to the bit (the walk is deterministic per (wo, wi)).
TEST(TextureEval, CoatedSlabAlbedoIsTextured) {
    auto img = std::make_shared<scene::TextureImage>();
    img->width = 2;
    img->height = 1;
    img->texels = {Rgb(0.0f), Rgb(1.0f)};
    Texture t;
    t.kind = Texture::Kind::Image;
    t.image = img;
    auto s = scene_with(t);
    scene::Material m;
    m.layered = true;
    m.diffuse = Rgb(0.3f);
    m.layer_thickness = 1.0f;
    m.layer_albedo = Rgb(0.9f);
    m.layer_albedo_texture = 0;
    accel::SurfaceHit h;
    h.ng = h.ns = Vec3(0, 0, 1);
    h.dpdu = Vec3(1, 0, 0);
    const Vec3 wo = normalize(Vec3(0.3f, 0.1f, 1)), wi = normalize(Vec3(-0.4f, 0.2f, 1));
    const Wavelengths lambda = spectral::fixed_lambda();
    h.uv = Vec2(0.25f, 0.5f);  // black texel: no medium
    const Spectrum f_black = Bsdf(m, h, s).eval(wo, wi, lambda);
    h.uv = Vec2(0.75f, 0.5f);  // white texel: albedo 0.9
    const Spectrum f_white = Bsdf(m, h, s).eval(wo, wi, lambda);
    scene::Material plain = m;
    plain.layer_albedo_texture = -1;
    EXPECT_EQ(f_white, Bsdf(plain, h, s).eval(wo, wi, lambda));
    plain.layer_albedo = Rgb(0.0f);
    EXPECT_EQ(f_black, Bsdf(plain, h, s).eval(wo, wi, lambda));
    EXPECT_GT(std::fabs(f_white[0] - f_black[0]), 0.01f * f_black[0]);
}

}  // namespace
}  // namespace phos::shading
