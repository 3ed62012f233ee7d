// Clarberg's equal-area octahedral mapping (Clarberg 2008, sec. 3; the radius r = 1 - |d| of the
// signed distance d to the diamond's edge, z = 1 - r^2, and phi linear along the diamond's side).
#include "core/equal_area.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace phos {

Vec3 equal_area_square_to_sphere(Vec2 p) {
    const float u = 2 * p.x - 1, v = 2 * p.y - 1;
    const float up = std::fabs(u), vp = std::fabs(v);
    // Signed distance from the diamond |u| + |v| = 1: positive inside (upper hemisphere).
    const float signed_distance = 1 - (up + vp);
    const float r = 1 - std::fabs(signed_distance);
    // phi in [0, pi/2] within the quadrant, linear along the diamond's side.
    const float phi = (r == 0 ? 1 : (vp - up) / r + 1) * (kPi / 4);
    const float z = std::copysign(1 - r * r, signed_distance);
    const float cos_phi = std::copysign(std::cos(phi), u), sin_phi = std::copysign(std::sin(phi), v);
    const float s = r * std::sqrt(std::max(0.0f, 2 - r * r));
    return {cos_phi * s, sin_phi * s, z};
}

Vec2 equal_area_sphere_to_square(Vec3 d) {
    const float x = std::fabs(d.x), y = std::fabs(d.y), z = std::fabs(d.z);
    const float r = std::sqrt(std::max(0.0f, 1 - z));
    const float a = std::max(x, y);
    const float b = a == 0 ? 0 : std::min(x, y) / a;
    // phi / (pi/2) in the quadrant, measured from the larger of |x|, |y|.
    float phi = std::atan(b) * (2 / kPi);
    if (x < y) phi = 1 - phi;
    float v = phi * r;
    float u = r - v;
    if (d.z < 0) {
        // Lower hemisphere: fold the triangle out over the diamond's edge.
        std::swap(u, v);
        u = 1 - u;
        v = 1 - v;
    }
    u = std::copysign(u, d.x);
    v = std::copysign(v, d.y);
    return {std::clamp(0.5f * (u + 1), 0.0f, 1.0f), std::clamp(0.5f * (v + 1), 0.0f, 1.0f)};
}

void wrap_octahedral(int& x, int& y, int n) {
    if (x < 0) {
        x = -1 - x;
        y = n - 1 - y;
    } else if (x >= n) {
        x = 2 * n - 1 - x;
        y = n - 1 - y;
    }
    if (y < 0) {
        x = n - 1 - x;
        y = -1 - y;
    } else if (y >= n) {
        x = n - 1 - x;
        y = 2 * n - 1 - y;
    }
    x = std::clamp(x, 0, n - 1);
    y = std::clamp(y, 0, n - 1);
}

}  // namespace phos
