// Helpers shared by the light tests: running mean/variance with a k-sigma check (per wavelength for
// spectral estimates), and small scenes (rectangle, disk, sphere emitters) built by hand.
//
// Emission is spectral: a light's RGB colour is read as an illuminant (spectrum/rgb_spectrum.h),
// so even RGB white is D65-shaped; spectral::illuminant(L, lambda) is what a light of colour L emits
// at `lambda`, and the closed forms below are per unit radiance times that.
//
// Statistical bound: for N independent samples X_i with finite variance, the sample mean has
// standard deviation sigma / sqrt(N), and by the central limit theorem it is close to normal for the
// N used here (>= 1e4). Estimating sigma by the sample deviation s, |mean - E[X]| <= k s / sqrt(N)
// fails by chance with probability about 2 Phi(-k): 6e-5 for k = 4, 6e-7 for k = 5. Seeds are fixed,
// so a pass is reproducible; a broken estimator is off by many sigma.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "core/rng.h"
#include "core/vec.h"
#include "scene/scene.h"
#include "spectral_test_util.h"
#include "support/shapes.h"

namespace phos::shading::test {

inline constexpr double kSigmas = 5.0;

struct RunningStat {
    double sum = 0, sum2 = 0;
    long n = 0;
    void add(double x) {
        sum += x;
        sum2 += x * x;
        ++n;
    }
    double mean() const { return sum / double(n); }
    double std_error() const {
        const double m = mean();
        const double var = std::max(0.0, sum2 / double(n) - m * m) * double(n) / double(n - 1);
        return std::sqrt(var / double(n));
    }
};

// Expects the mean within kSigmas standard errors of `expected` (plus a relative 1e-5 for float
// rounding when the samples are (nearly) constant).
inline void expect_mean(const RunningStat& s, double expected, const char* what) {
    const double tol = kSigmas * s.std_error() + 1e-5 * std::fabs(expected) + 1e-12;
    EXPECT_NEAR(s.mean(), expected, tol) << what << " (N=" << s.n << ", stderr=" << s.std_error() << ")";
}

// One RunningStat per wavelength sample of a spectral estimate.
struct SpectralStat {
    RunningStat s[spectral::kSpectrumSamples];
    void add(const Spectrum& v) {
        for (int i = 0; i < spectral::kSpectrumSamples; ++i) s[i].add(double(v[i]));
    }
};

// expect_mean at every wavelength sample.
inline void expect_means(const SpectralStat& st, const Spectrum& expected, const char* what) {
    for (int i = 0; i < spectral::kSpectrumSamples; ++i) {
        SCOPED_TRACE(::testing::Message() << "wavelength sample " << i);
        expect_mean(st.s[i], double(expected[i]), what);
    }
}

inline double dot_d(Vec3 a, Vec3 b) { return double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z; }

// Two-triangle mesh of the rectangle [x0,x1] x [z0,z1] at height y, emitting towards -y.
inline scene::Shape rectangle_y(float x0, float x1, float z0, float z1, float y) {
    scene::Shape s;
    s.kind = scene::Shape::Kind::Mesh;
    s.mesh.positions = {{x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}};
    s.mesh.indices = {0, 1, 2, 0, 2, 3};
    return s;
}

using phos::testing::disk;
using phos::testing::sphere;

inline scene::Light area_light_record(Rgb L, bool two_sided = false) {
    scene::Light l;
    l.kind = scene::Light::Kind::Area;
    l.color = L;
    l.two_sided = two_sided;
    l.shape = 0;
    return l;
}

// Irradiance at x (unit normal n) from a polygon of uniform radiance L lying entirely above x's
// tangent plane (Lambert's formula): E = L/2 |sum_i Theta_i n . Gamma_i|, where Theta_i is the
// angle the edge (v_i, v_i+1) subtends at x and Gamma_i the unit normal of the plane through x and
// that edge. It is Stokes' theorem applied to the projected solid angle integral of cos over the
// polygon's spherical projection: the integrand n.w is the divergence-free part whose flux through
// the spherical polygon reduces to a sum over its great-circle edges.
inline double lambert_irradiance(const std::vector<Vec3>& poly, Vec3 x, Vec3 n, double L) {
    double sum = 0;
    for (size_t i = 0; i < poly.size(); ++i) {
        const Vec3 a = normalize(poly[i] - x), b = normalize(poly[(i + 1) % poly.size()] - x);
        const double theta = std::acos(std::clamp(dot_d(a, b), -1.0, 1.0));
        const Vec3 g = normalize(cross(a, b));
        sum += theta * dot_d(n, g);
    }
    return 0.5 * L * std::fabs(sum);
}

// An image texture of w x h texels (row 0 at the top).
inline scene::Texture image_texture(int w, int h, std::vector<Rgb> texels) {
    auto img = std::make_shared<scene::TextureImage>();
    img->width = w;
    img->height = h;
    img->texels = std::move(texels);
    scene::Texture t;
    t.kind = scene::Texture::Kind::Image;
    t.image = std::move(img);
    return t;
}

// An n x n map with a smooth gradient, black pixels and one bright spot (n >= 12).
inline std::vector<Rgb> varied_map(int n) {
    std::vector<Rgb> texels;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            float v = 0.1f + 0.05f * float((x * 5 + y * 3) % 7);
            if ((x + 2 * y) % 9 == 0) v = 0;
            texels.push_back(Rgb(v, 2 * v, 0.5f * v));
        }
    texels[size_t(4 * n + 11)] = Rgb(30, 20, 10);
    return texels;
}

}  // namespace phos::shading::test
