// Infinite lights: a constant environment (pdf integrates over the sphere, irradiance pi L) and a
// small synthetic lat-long map (lookup convention, directions distributed in proportion to
// luminance x solid angle, pdf_Li consistency, emission power). Radiance is spectral: the RGB
// colour (a texel's, times the scale) read as an illuminant, checked at every wavelength sample.
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/transform.h"
#include "light_test_util.h"
#include "shading/infinite_light.h"

namespace phos::shading {
namespace {

using test::expect_mean;
using test::expect_means;
using test::RunningStat;
using test::SpectralStat;

const SceneSphere kSphere{{1, 2, 3}, 2.5f};
const Wavelengths& kLambda = spectral::fixed_lambda();

// A map texel's radiance at `lambda`: per-hit colours take the table fit.
Spectrum texel_spectrum(Rgb c, const Wavelengths& lambda) {
    return spectrum::RgbSpectrum(c, spectrum::RgbSpectrum::Use::Illuminant, spectrum::RgbSpectrum::Fit::Table)
        .sample(lambda);
}

TEST(InfiniteLight, ConstantEnvironment) {
    scene::Light rec;
    rec.kind = scene::Light::Kind::Infinite;
    rec.color = Rgb(1, 2, 3);
    const InfiniteLight light(rec, {}, kSphere);
    EXPECT_TRUE(light.is_infinite());
    // The constant radiance: (1, 2, 3) read as an illuminant (a scene constant: the exact fit).
    const Spectrum L = spectral::illuminant(Rgb(1, 2, 3), kLambda);
    EXPECT_TRUE(spectral::spectra_near(light.Le({}, {0.3f, -0.2f, 0.9f}, kLambda), L, 1e-6));
    EXPECT_EQ(light.Le_rgb({0.3f, -0.2f, 0.9f}), Rgb(1, 2, 3));
    const double R = 2.5;
    EXPECT_NEAR(light.power().g, 4 * kPi * kPi * R * R * 2, 1e-3);
    Sampler rng(4);
    RunningStat inv_pdf;
    SpectralStat irr;
    const Vec3 n = normalize(Vec3(1, 1, 0));
    for (int i = 0; i < 40000; ++i) {
        const LightLiSample s = light.sample_Li({0, 0, 0}, rng.next2(), kLambda);
        ASSERT_GT(s.pdf, 0);
        EXPECT_NEAR(light.pdf_Li({0, 0, 0}, s.wi, s.p_light, s.n_light), s.pdf, 1e-6f);
        EXPECT_EQ(s.distance, kInf);
        inv_pdf.add(1 / s.pdf);
        irr.add(s.L * (std::max(0.0f, dot(s.wi, n)) / s.pdf));
    }
    expect_mean(inv_pdf, 4 * kPi, "E[1/pdf]");
    expect_means(irr, L * kPi, "irradiance pi L");
    SpectralStat weight;
    RunningStat colour[3];  // the weight through the film, each sample at its own wavelengths
    const int N = 20000;
    for (int i = 0; i < N; ++i) {
        const Vec2 u_pos = rng.next2(), u_dir = rng.next2();
        const LightLeSample s = light.sample_Le(u_pos, u_dir, kLambda);
        const Vec3 rel = s.ray.origin - kSphere.center;
        ASSERT_NEAR(dot(rel, s.ray.dir), -2.5f, 1e-4f);  // starts on a disk outside the scene
        ASSERT_LE(length(rel - s.ray.dir * dot(rel, s.ray.dir)), 2.5f + 1e-4f);
        weight.add(s.weight);
        const Wavelengths li = spectral::stratified_lambda(i, N);
        const Rgb c = spectrum::to_srgb(light.sample_Le(u_pos, u_dir, li).weight, li);
        for (int k = 0; k < 3; ++k) colour[k].add(c[k]);
    }
    // pi R^2 times the integral 4 pi L, at every wavelength.
    expect_means(weight, L * float(4 * kPi * kPi * R * R), "constant env weight");
    // Through the film: power() (the exact fit's RGB is within 1e-5 of (1, 2, 3); 2e-3 relative
    // covers the CIE tables' interpolation against the fit's 1 nm sums).
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(colour[k].mean(), light.power()[k],
                    test::kSigmas * colour[k].std_error() + 2e-3 * light.power()[k])
            << "channel " << k;
    }
}

// An 8 x 4 map with a few dark texels and a bright spot, oriented by a rotation.
struct EnvFixture {
    static constexpr int W = 8, H = 4;
    std::vector<scene::Texture> textures;
    scene::Light rec;
    Transform rot = Transform::rotate(30, {1, 0, 0}) * Transform::rotate(50, {0, 0, 1});
    EnvFixture() {
        auto img = std::make_shared<scene::TextureImage>();
        img->width = W;
        img->height = H;
        for (int j = 0; j < H; ++j)
            for (int i = 0; i < W; ++i) {
                float v = 0.2f + 0.1f * float((i * 7 + j * 3) % 5);
                if ((i + j) % 6 == 0) v = 0;  // dark texels: never sampled
                img->texels.push_back(Rgb(v, 0.5f * v, 2 * v));
            }
        img->texels[size_t(1 * W + 5)] = Rgb(20, 15, 10);  // the "sun"
        scene::Texture t;
        t.kind = scene::Texture::Kind::Image;
        t.image = img;
        t.value = Rgb(1.5f);
        textures.push_back(t);
        rec.kind = scene::Light::Kind::Infinite;
        rec.color = Rgb(2, 1, 1);
        rec.texture = 0;
        rec.to_world = rot;
    }
    Rgb texel(int i, int j) const { return textures[0].image->at(i, j) * Rgb(3, 1.5f, 1.5f); }
    double omega(int j) const { return 2 * kPi / W * (std::cos(kPi * j / H) - std::cos(kPi * (j + 1) / H)); }
    // Texel of a world direction, computed independently of the light.
    void cell(Vec3 w, int& i, int& j) const {
        const Vec3 l = normalize(rot.inverse().vector(w));
        double phi = std::atan2(l.y, l.x);
        if (phi < 0) phi += 2 * kPi;
        i = std::min(int(phi / (2 * kPi) * W), W - 1);
        j = std::min(int(std::acos(std::clamp(double(l.z), -1.0, 1.0)) / kPi * H), H - 1);
    }
};

TEST(InfiniteLight, LatLongLookupConvention) {
    const EnvFixture f;
    const InfiniteLight light(f.rec, f.textures, kSphere);
    for (int j = 0; j < f.H; ++j)
        for (int i = 0; i < f.W; ++i) {
            const float theta = kPi * (j + 0.5f) / f.H, phi = 2 * kPi * (i + 0.5f) / f.W;
            const Vec3 local{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                             std::cos(theta)};
            EXPECT_EQ(light.Le_rgb(f.rot.vector(local)), f.texel(i, j)) << i << "," << j;
            EXPECT_EQ(light.Le({}, f.rot.vector(local), kLambda), texel_spectrum(f.texel(i, j), kLambda))
                << i << "," << j;
        }
}

TEST(InfiniteLight, EnvMapSamplingFollowsLuminance) {
    const EnvFixture f;
    const InfiniteLight light(f.rec, f.textures, kSphere);
    double total_lum = 0, lit_omega = 0;
    Rgb integral(0.0f);
    Spectrum integral_s(0.0f);  // at kLambda
    for (int j = 0; j < f.H; ++j)
        for (int i = 0; i < f.W; ++i) {
            total_lum += f.texel(i, j).luminance() * f.omega(j);
            if (f.texel(i, j).luminance() > 0) lit_omega += f.omega(j);
            integral += f.texel(i, j) * float(f.omega(j));
            integral_s += texel_spectrum(f.texel(i, j), kLambda) * float(f.omega(j));
        }
    EXPECT_NEAR(light.integral().r, integral.r, 1e-4 * integral.r);
    EXPECT_NEAR(light.power().g, kPi * 2.5 * 2.5 * integral.g, 1e-4 * kPi * 6.25 * integral.g);

    const int N = 200000;
    std::vector<int> count(f.W * f.H, 0);
    Sampler rng(12);
    RunningStat inv_pdf;
    SpectralStat radiance;
    for (int n = 0; n < N; ++n) {
        const LightLiSample s = light.sample_Li({0, 0, 0}, rng.next2(), kLambda);
        ASSERT_GT(s.pdf, 0);
        int i, j;
        f.cell(s.wi, i, j);
        ++count[size_t(j * f.W + i)];
        EXPECT_NEAR(light.pdf_Li({}, s.wi, {}, {}), s.pdf, 1e-5f * s.pdf);
        // The radiance is the texel's colour as a spectrum (texels near a cell edge may round
        // into the neighbour, as the map's own lookup decides: compare with the light's colour
        // there, which LatLongLookupConvention ties to the texels).
        const Rgb c = light.Le_rgb(s.wi);
        EXPECT_EQ(s.L, texel_spectrum(c, kLambda));
        // pdf proportional to luminance: pdf = lum(L) / integral of lum.
        EXPECT_NEAR(s.pdf, c.luminance() / total_lum, 1e-3 * s.pdf);
        inv_pdf.add(1 / s.pdf);
        radiance.add(s.L / s.pdf);
    }
    expect_mean(inv_pdf, lit_omega, "E[1/pdf] = lit solid angle");
    expect_means(radiance, integral_s, "E[L/pdf] = integral of L");
    // Chi-square over the texels with non-zero expectation; dark texels must never be hit.
    double chi2 = 0;
    int dof = -1;
    for (int j = 0; j < f.H; ++j)
        for (int i = 0; i < f.W; ++i) {
            const double expected = N * f.texel(i, j).luminance() * f.omega(j) / total_lum;
            const int got = count[size_t(j * f.W + i)];
            if (expected == 0) {
                EXPECT_EQ(got, 0) << i << "," << j;
                continue;
            }
            chi2 += (got - expected) * (got - expected) / expected;
            ++dof;
        }
    // Mean dof, standard deviation sqrt(2 dof): 5 sigma above the mean.
    EXPECT_LT(chi2, dof + 5 * std::sqrt(2.0 * dof)) << "dof " << dof;

    SpectralStat weight;
    for (int n = 0; n < 40000; ++n) weight.add(light.sample_Le(rng.next2(), rng.next2(), kLambda).weight);
    expect_means(weight, integral_s * float(kPi * 2.5 * 2.5), "env map emission");
}

TEST(InfiniteLight, BadTextureIsAnInputError) {
    scene::Light rec;
    rec.kind = scene::Light::Kind::Infinite;
    rec.texture = 3;
    EXPECT_THROW(InfiniteLight(rec, {}, kSphere), InputError);
    std::vector<scene::Texture> tex(1);
    tex[0].kind = scene::Texture::Kind::Image;  // no pixels
    rec.texture = 0;
    EXPECT_THROW(InfiniteLight(rec, tex, kSphere), InputError);
}

}  // namespace
}  // namespace phos::shading
