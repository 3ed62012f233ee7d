// Area lights on alpha-masked shapes (pbrt-v4's DiffuseAreaLight::AlphaMasked): sample_Li and
// sample_Le give no sample where the shape's alpha is 0 (a texture's cut-out half, or a constant 0)
// and, for a constant alpha in (0, 1), keep that fraction of distinct points; unmasked lights are
// unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "light_test_util.h"
#include "shading/area_light.h"

namespace phos::shading {
namespace {

const Wavelengths& kLambda = spectral::fixed_lambda();

// The rectangle x in [0, 2], z in [0, 1] at y = 1 (facing -y: lights the floor), uv = (x / 2, z).
scene::Shape masked_rectangle() {
    scene::Shape s = test::rectangle_y(0, 2, 0, 1, 1);
    s.mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    return s;
}

// A clamped 4 x 1 image texture: alpha 0 for u <= 3/8, 1 for u >= 5/8, linear between (mean 1/2).
std::vector<scene::Texture> half_mask() {
    auto img = std::make_shared<scene::TextureImage>();
    img->width = 4;
    img->height = 1;
    img->texels = {Rgb(0.0f), Rgb(0.0f), Rgb(1.0f), Rgb(1.0f)};
    scene::Texture t;
    t.kind = scene::Texture::Kind::Image;
    t.image = img;
    t.wrap = scene::Texture::Wrap::Clamp;
    return {t};
}

struct Counts {
    int li = 0, le = 0, n = 0;
    bool masked_half_lit = false;  // a sample at x < 0.74 (u < 0.37: alpha exactly 0 there)
};

Counts count(const AreaLight& light, int n) {
    Sampler rng(9);
    Counts c;
    c.n = n;
    for (int i = 0; i < n; ++i) {
        const LightLiSample s = light.sample_Li({1, -1, 0.5f}, rng.next2(), kLambda);
        if (s.pdf > 0 && s.L.max() > 0) {
            ++c.li;
            c.masked_half_lit |= s.p_light.x < 0.74f;
        }
        const LightLeSample e = light.sample_Le(rng.next2(), rng.next2(), kLambda);
        if (e.weight.max() > 0) {
            ++c.le;
            c.masked_half_lit |= e.ray.origin.x < 0.74f;
        }
    }
    return c;
}

TEST(AreaLightAlpha, TextureCutOutEmitsOnlyWhereAlphaIsOne) {
    const std::vector<scene::Texture> textures = half_mask();
    scene::Shape s = masked_rectangle();
    s.alpha_texture = 0;
    const AreaLight light(test::area_light_record(Rgb(1.0f)), s, &textures);
    const Counts c = count(light, 4000);
    EXPECT_FALSE(c.masked_half_lit);
    // Uniform by area: half the points, within 4 binomial sigmas (sample_Li samples by area too).
    const double sigma = std::sqrt(0.25 / c.n);
    EXPECT_NEAR(double(c.le) / c.n, 0.5, 4 * sigma);
    EXPECT_NEAR(double(c.li) / c.n, 0.5, 4 * sigma);
}

TEST(AreaLightAlpha, ConstantAlphaKeepsThatFractionOfPoints) {
    for (float alpha : {0.0f, 0.3f, 1.0f}) {
        scene::Shape s = masked_rectangle();
        s.alpha = alpha;
        const AreaLight light(test::area_light_record(Rgb(1.0f)), s);
        const Counts c = count(light, 4000);
        const double sigma = std::sqrt(alpha * (1 - alpha) / c.n);
        EXPECT_NEAR(double(c.le) / c.n, alpha, 4 * sigma + 1e-12) << alpha;
        EXPECT_NEAR(double(c.li) / c.n, alpha, 4 * sigma + 1e-12) << alpha;
    }
}

}  // namespace
}  // namespace phos::shading
