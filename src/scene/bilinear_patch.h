// A bilinear patch (pbrt's `bilinearmesh`): p(u, v) = lerp(v, lerp(u, p00, p10), lerp(u, p01, p11))
// over [0, 1]^2, its partial derivatives, its area element |dp/du x dp/dv| and its area, shared by the
// loader (power of an emitting mesh), the accelerator and the area-light sampler.
#pragma once

#include <array>

#include "core/vec.h"

namespace phos::scene {

// The corners in pbrt's order p00, p10, p01, p11.
using PatchCorners = std::array<Vec3, 4>;

// True when the four corners lie in one plane (to 1e-6 of the patch's size): such a patch is the
// flat quadrilateral its two triangles (p00 p10 p11), (p00 p11 p01) cover.
bool patch_is_planar(const PatchCorners& p);

// The area, by 8 x 8 Gauss-Legendre quadrature of |dp/du x dp/dv| (dp/du x dp/dv is linear in u and
// v, so the integrand is the square root of a quadratic: smooth wherever it stays away from zero,
// and the rule is then accurate to float precision).
double patch_area(const PatchCorners& p);

// The bilinear interpolation of four per-corner values at (u, v).
template <class T>
T bilerp(const std::array<T, 4>& c, double u, double v) {
    return c[0] * float((1 - u) * (1 - v)) + c[1] * float(u * (1 - v)) + c[2] * float((1 - u) * v) +
           c[3] * float(u * v);
}

}  // namespace phos::scene
