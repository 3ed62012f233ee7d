// pbrt-v4's procedural texture functions (see procedural_textures.h).
#include "scene/procedural_textures.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "scene/perlin_noise.h"

namespace phos::scene {
namespace {

// 1 if floor(x) is odd, else 0 (0 for non-finite x).
int floor_parity(float x) { return std::fabs(std::fmod(std::floor(x), 2.0f)) == 1.0f ? 1 : 0; }

}  // namespace

bool checker_odd(Vec2 st) { return (floor_parity(st.x) + floor_parity(st.y)) % 2 == 1; }

bool checker_odd(Vec3 p) { return (floor_parity(p.x) + floor_parity(p.y) + floor_parity(p.z)) % 2 == 1; }

bool inside_polka_dot(Vec2 st) {
    const float s_cell = std::floor(st.x + 0.5f), t_cell = std::floor(st.y + 0.5f);
    if (!(perlin_noise(s_cell + 0.5f, t_cell + 0.5f, 0.5f) > 0)) return false;
    constexpr float kRadius = 0.35f, kMaxShift = 0.5f - kRadius;
    const float s_centre = s_cell + kMaxShift * perlin_noise(s_cell + 1.5f, t_cell + 2.8f, 0.5f);
    const float t_centre = t_cell + kMaxShift * perlin_noise(s_cell + 4.5f, t_cell + 9.8f, 0.5f);
    const float ds = st.x - s_centre, dt = st.y - t_centre;
    return ds * ds + dt * dt < kRadius * kRadius;
}

float windy(Vec3 p) {
    const float wind_strength = fbm(p * 0.1f, 0.5f, 3);
    const float wave_height = fbm(p, 0.5f, 6);
    return std::fabs(wind_strength) * wave_height;
}

Rgb marble(Vec3 p, float scale, float variation, float omega, int octaves) {
    const Vec3 q = p * scale;
    const float m = q.y + variation * fbm(q, omega, octaves);
    float t = 0.5f + 0.5f * std::sin(m);
    if (!std::isfinite(t)) t = 0.5f;
    // pbrt's nine control points: six cubic Bezier segments, segment i using points i..i+3.
    static constexpr std::array<Rgb, 9> kColours = {
        Rgb(.58f, .58f, .6f), Rgb(.58f, .58f, .6f), Rgb(.58f, .58f, .6f),
        Rgb(.5f, .5f, .5f),   Rgb(.6f, .59f, .58f), Rgb(.58f, .58f, .6f),
        Rgb(.58f, .58f, .6f), Rgb(.2f, .2f, .33f),  Rgb(.58f, .58f, .6f),
    };
    constexpr int kSegments = int(kColours.size()) - 3;
    const int first = std::clamp(int(std::floor(t * float(kSegments))), 0, kSegments - 1);
    const float u = t * float(kSegments) - float(first), v = 1 - u;
    const Rgb* c = &kColours[size_t(first)];
    // Cubic Bezier in Bernstein form.
    const Rgb bezier =
        c[0] * (v * v * v) + c[1] * (3 * v * v * u) + c[2] * (3 * v * u * u) + c[3] * (u * u * u);
    return bezier * 1.5f;
}

}  // namespace phos::scene
