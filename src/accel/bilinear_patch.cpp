// Reshetov's ray / bilinear patch test: the ray meets the patch where it meets a u-isoline
// (the segment from lerp(u, p00, p10) to lerp(u, p01, p11)); that the ray and the isoline are
// coplanar is a quadratic in u, and each root in [0, 1] gives v and t by Cramer's rule on the
// closest points of ray and line.
#include "accel/bilinear_patch.h"

#include <cmath>

namespace phos::accel::detail {

bool intersect_patch(const std::array<D3, 4>& p, D3 o, D3 d, double tmin, double tmax, PatchHit& hit) {
    const D3 &p00 = p[0], &p10 = p[1], &p01 = p[2], &p11 = p[3];
    // a u^2 + b u + c = 0: c and a + b + c are the coplanarity of the ray and the isolines u = 0, 1.
    const double a = dot(cross(p10 - p00, p01 - p11), d);
    const double c = dot(cross(p00 - o, d), p01 - p00);
    const double b = dot(cross(p10 - o, d), p11 - p10) - (a + c);
    double roots[2];
    int n = 0;
    const double disc = b * b - 4 * a * c;
    if (disc < 0) return false;
    // Numerically stable roots (citardauq form for the one that would cancel).
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    if (a != 0 && q != 0) {
        roots[n++] = q / a;
        roots[n++] = c / q;
    } else if (a != 0) {
        roots[n++] = 0;  // b = 0 and disc = 0, so c = 0: a double root at 0
    } else if (b != 0) {
        roots[n++] = -c / b;
    } else {
        return false;
    }
    bool found = false;
    for (int i = 0; i < n; ++i) {
        const double u = roots[i];
        if (!(u >= 0 && u <= 1)) continue;
        const D3 uo = p00 + (p10 - p00) * u;
        const D3 ud = p01 + (p11 - p01) * u - uo;
        const D3 deltao = uo - o;
        const D3 perp = cross(d, ud);
        const double p2 = dot(perp, perp);
        if (!(p2 > 0)) continue;
        const double v = dot(deltao, cross(d, perp)) / p2;
        const double t = dot(deltao, cross(ud, perp)) / p2;
        if (!(v >= 0 && v <= 1) || !(t > tmin && t < tmax)) continue;
        tmax = t;
        hit = {t, u, v};
        found = true;
    }
    return found;
}

}  // namespace phos::accel::detail
