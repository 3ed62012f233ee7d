// Bilinear patch geometry: the planarity test and the area by Gauss-Legendre quadrature.
#include "scene/bilinear_patch.h"

#include <algorithm>
#include <cmath>

namespace phos::scene {
namespace {

struct D3 {
    double x, y, z;
};
D3 sub(Vec3 a, Vec3 b) { return {double(a.x) - b.x, double(a.y) - b.y, double(a.z) - b.z}; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

}  // namespace

bool patch_is_planar(const PatchCorners& p) {
    const D3 e1 = sub(p[1], p[0]), e2 = sub(p[2], p[0]), e3 = sub(p[3], p[0]);
    double size = 0;
    for (const D3& e : {e1, e2, e3, sub(p[3], p[1]), sub(p[3], p[2]), sub(p[2], p[1])})
        size = std::max(size, std::sqrt(dot(e, e)));
    // The volume of the tetrahedron the corners span, against the size cubed.
    return std::fabs(dot(cross(e1, e2), e3)) <= 1e-6 * size * size * size;
}

double patch_area(const PatchCorners& p) {
    // 8-point Gauss-Legendre nodes and weights on [-1, 1] (Abramowitz & Stegun, table 25.4).
    static constexpr double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                    0.9602898564975363};
    static constexpr double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                    0.1012285362903763};
    double nodes[8], weights[8];
    for (int i = 0; i < 4; ++i) {
        nodes[2 * i] = 0.5 * (1 - x[i]), nodes[2 * i + 1] = 0.5 * (1 + x[i]);
        weights[2 * i] = weights[2 * i + 1] = 0.5 * w[i];
    }
    const D3 a = sub(p[1], p[0]), b = sub(p[3], p[2]), c = sub(p[2], p[0]), d = sub(p[3], p[1]);
    double area = 0;
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) {
            const double u = nodes[i], v = nodes[j];
            // dp/du = lerp(v, p10 - p00, p11 - p01), dp/dv = lerp(u, p01 - p00, p11 - p10).
            const D3 du{a.x + v * (b.x - a.x), a.y + v * (b.y - a.y), a.z + v * (b.z - a.z)};
            const D3 dv{c.x + u * (d.x - c.x), c.y + u * (d.y - c.y), c.z + u * (d.z - c.z)};
            const D3 n = cross(du, dv);
            area += weights[i] * weights[j] * std::sqrt(dot(n, n));
        }
    return area;
}

}  // namespace phos::scene
