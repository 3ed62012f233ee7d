// pbrt-v4's camera footprint approximation and (u, v) derivatives (see camera_footprint.h).
#include "scene/camera_footprint.h"

#include <algorithm>
#include <cmath>

#include "core/transform.h"

namespace phos::scene {
namespace {

// The rotation taking unit `from` to unit `to` as the product of two reflections (Hughes and
// Moeller 1999; pbrt-v4's RotateFromTo), its inverse its transpose.
Transform rotate_from_to(Vec3 from, Vec3 to) {
    Vec3 refl;
    if (std::fabs(from.x) < 0.72f && std::fabs(to.x) < 0.72f)
        refl = Vec3(1, 0, 0);
    else if (std::fabs(from.y) < 0.72f && std::fabs(to.y) < 0.72f)
        refl = Vec3(0, 1, 0);
    else
        refl = Vec3(0, 0, 1);
    const Vec3 u = refl - from, v = refl - to;
    const float uu = dot(u, u), vv = dot(v, v), uv = dot(u, v);
    Mat4 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r(i, j) = (i == j ? 1.0f : 0.0f) - 2 / uu * u[i] * u[j] - 2 / vv * v[i] * v[j] +
                      4 * uv / (uu * vv) * v[i] * u[j];
    return Transform(r, r.transposed());
}

// a b - c d.
float difference_of_products(float a, float b, float c, float d) {
    return float(double(a) * b - double(c) * d);
}

}  // namespace

void approximate_dp_dxy(const CameraFootprint& c, Vec3 p, Vec3 n, Vec3& dpdx, Vec3& dpdy) {
    dpdx = dpdy = Vec3(0.0f);
    const auto to_camera = [&](Vec3 v) { return Vec3(dot(v, c.right), dot(v, c.up), dot(v, c.forward)); };
    const Vec3 p_camera = to_camera(p - c.eye);
    const float distance = length(p_camera);
    if (!(distance > 0) || !std::isfinite(distance)) return;
    // Camera space turned so that p lies on +z; the tangent plane n . x = d there.
    const Transform down_z = rotate_from_to(p_camera / distance, Vec3(0, 0, 1));
    const Vec3 p_down = down_z.vector(p_camera);
    const Vec3 n_down = down_z.vector(to_camera(n));
    const float d = n_down.z * p_down.z;
    // The two offset rays and where they meet the plane.
    const auto offset = [&](Vec3 origin, Vec3 dir) {
        const float t = -(dot(n_down, origin) - d) / dot(n_down, dir);
        const Vec3 hit = origin + dir * t;
        const Vec3 delta = down_z.inverse().vector(hit - p_down) * c.spp_scale;
        const Vec3 world = c.right * delta.x + c.up * delta.y + c.forward * delta.z;
        return is_finite(world) ? world : Vec3(0.0f);
    };
    dpdx = offset(c.min_pos_dx, Vec3(0, 0, 1) + c.min_dir_dx);
    dpdy = offset(c.min_pos_dy, Vec3(0, 0, 1) + c.min_dir_dy);
}

UvDerivatives uv_derivatives(Vec3 dpdu, Vec3 dpdv, Vec3 dpdx, Vec3 dpdy) {
    // A^T A and A^T b for A = [dpdu dpdv] (PBR 4th ed., eq. 10.1).
    const float ata00 = dot(dpdu, dpdu), ata01 = dot(dpdu, dpdv), ata11 = dot(dpdv, dpdv);
    float inv_det = 1 / difference_of_products(ata00, ata11, ata01, ata01);
    inv_det = std::isfinite(inv_det) ? inv_det : 0.0f;
    const float atb0x = dot(dpdu, dpdx), atb1x = dot(dpdv, dpdx);
    const float atb0y = dot(dpdu, dpdy), atb1y = dot(dpdv, dpdy);
    const auto clamp = [](float v) { return std::isfinite(v) ? std::clamp(v, -1e8f, 1e8f) : 0.0f; };
    UvDerivatives r;
    r.dudx = clamp(difference_of_products(ata11, atb0x, ata01, atb1x) * inv_det);
    r.dvdx = clamp(difference_of_products(ata00, atb1x, ata01, atb0x) * inv_det);
    r.dudy = clamp(difference_of_products(ata11, atb0y, ata01, atb1y) * inv_det);
    r.dvdy = clamp(difference_of_products(ata00, atb1y, ata01, atb0y) * inv_det);
    return r;
}

}  // namespace phos::scene
