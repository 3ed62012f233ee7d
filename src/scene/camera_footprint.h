// How large a pixel is where it lands on a surface: pbrt-v4's camera approximation of the
// screen-space derivatives dp/dx and dp/dy at any surface point (Camera::Approximate_dp_dxy,
// PBR 4th ed., sec. 10.1.1) and the (u, v) derivatives that follow from them
// (SurfaceInteraction::ComputeDifferentials). The render layer fills the data from its camera
// (render::CameraModel::texture_footprint); filtered image textures read the result.
#pragma once

#include "core/vec.h"

namespace phos::scene {

struct CameraFootprint {
    // Camera space: origin at eye, x = right, y = up, z = forward (unit, orthonormal).
    Vec3 eye{0, 0, 0}, right{1, 0, 0}, up{0, 1, 0}, forward{0, 0, 1};
    // pbrt-v4's minimum differentials over the image (CameraBase::FindMinimumDifferentials): the
    // smallest change of a camera ray's origin (camera space) and of its unit direction (in the
    // ray's own frame, Frame(d) of core/frame.h, where d = +z) from one pixel to the next along x
    // and along y.
    Vec3 min_pos_dx{0, 0, 0}, min_pos_dy{0, 0, 0}, min_dir_dx{0, 0, 0}, min_dir_dy{0, 0, 0};
    // max(1/8, 1/sqrt(samples per pixel)): pbrt-v4 shrinks the footprint as the pixel gets more
    // samples, each sample standing for a smaller share of it.
    float spp_scale = 1;
};

// pbrt-v4's Camera::Approximate_dp_dxy: camera space rotated so that p lies on +z (pbrt-v4's
// RotateFromTo), the rays o + min_pos_d* along +z + min_dir_d* intersected with the tangent plane
// of (p, n), and their offsets from p, back in world space, times spp_scale. Zero where the
// plane is parallel to those rays.
void approximate_dp_dxy(const CameraFootprint& camera, Vec3 p, Vec3 n, Vec3& dpdx, Vec3& dpdy);

// The (u, v) derivatives of dp/dx and dp/dy on a surface with derivatives dpdu, dpdv: the
// least-squares solution of dp/dx = dpdu du/dx + dpdv dv/dx (and in y) via the normal equations,
// as pbrt-v4 solves it; non-finite results are 0 and the rest are clamped to +-1e8.
struct UvDerivatives {
    float dudx = 0, dudy = 0, dvdx = 0, dvdy = 0;
};
UvDerivatives uv_derivatives(Vec3 dpdu, Vec3 dpdv, Vec3 dpdx, Vec3 dpdy);

}  // namespace phos::scene
