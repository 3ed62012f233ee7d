// Sampling warps: map uniform points of [0,1)^2 to distributions used by lights, BSDFs and photon
// emission, each with its density. Tests check every pdf integrates to 1 and matches its histogram.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/vec.h"

namespace phos::warp {

// Uniform on the unit disk (Shirley-Chiu concentric map, low distortion). pdf = 1/pi.
inline Vec2 concentric_disk(Vec2 u) {
    const float ox = 2 * u.x - 1, oy = 2 * u.y - 1;
    if (ox == 0 && oy == 0) return {0, 0};
    float r, theta;
    if (std::fabs(ox) > std::fabs(oy)) {
        r = ox;
        theta = (kPi / 4) * (oy / ox);
    } else {
        r = oy;
        theta = (kPi / 2) - (kPi / 4) * (ox / oy);
    }
    return {r * std::cos(theta), r * std::sin(theta)};
}
inline float concentric_disk_pdf() { return kInvPi; }

// Cosine-weighted hemisphere around +z. pdf = cos(theta)/pi.
inline Vec3 cosine_hemisphere(Vec2 u) {
    const Vec2 d = concentric_disk(u);
    const float z = std::sqrt(std::max(0.0f, 1 - d.x * d.x - d.y * d.y));
    return {d.x, d.y, z};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0 ? cos_theta * kInvPi : 0; }

// Uniform on the unit sphere. pdf = 1/(4 pi).
inline Vec3 uniform_sphere(Vec2 u) {
    const float z = 1 - 2 * u.x;
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    const float phi = 2 * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float uniform_sphere_pdf() { return 0.25f * kInvPi; }

// The density of directions uniform over the cone within angle acos(cos_max) of +z.
inline float uniform_cone_pdf(float cos_max) { return 1 / (2 * kPi * (1 - cos_max)); }

// Directions around +z distributed as (n+1)/(2 pi) cos^n(theta) (the Phong lobe). pdf below.
inline Vec3 power_cosine(Vec2 u, float n) {
    const float z = std::pow(u.x, 1 / (n + 1));
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    const float phi = 2 * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float power_cosine_pdf(float cos_theta, float n) {
    return cos_theta > 0 ? (n + 1) * (0.5f * kInvPi) * std::pow(cos_theta, n) : 0;
}

// Spot-light style directions around +z distributed as (n+1)/(2 pi (1-c^(n+1))) cos^n, truncated to
// the cone cos(theta) >= cos_max: the exact emission distribution of a cos^dropoff spot light.
inline Vec3 truncated_power_cosine(Vec2 u, float n, float cos_max) {
    const float cmax_n1 = std::pow(std::max(cos_max, 0.0f), n + 1);
    const float z = std::pow(1 - u.x * (1 - cmax_n1), 1 / (n + 1));
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    const float phi = 2 * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float truncated_power_cosine_pdf(float cos_theta, float n, float cos_max) {
    if (cos_theta < cos_max || cos_theta <= 0) return 0;
    const float cmax_n1 = std::pow(std::max(cos_max, 0.0f), n + 1);
    return (n + 1) * std::pow(cos_theta, n) / (2 * kPi * (1 - cmax_n1));
}

// Uniform barycentric coordinates (b0, b1) on a triangle; b2 = 1 - b0 - b1. pdf = 1/area.
inline Vec2 uniform_triangle(Vec2 u) {
    const float su = std::sqrt(u.x);
    return {1 - su, u.y * su};
}

// Balance-free power heuristic (beta = 2) for multiple importance sampling.
inline float power_heuristic(float pdf_a, float pdf_b) {
    const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a + b > 0 ? a / (a + b) : 0;
}

}  // namespace phos::warp
