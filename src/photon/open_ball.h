// The share of a density-estimation ball that photons can reach: the part of the ball seen from
// its centre before any surface. A volume estimate divides the photons found by this volume
// instead of the whole ball's, so a ball that reaches through a medium's boundary or into a solid
// does not count the empty part as dark (boundary bias of volume kernels).
#pragma once

#include "accel/embree_scene.h"
#include "core/vec.h"

namespace phos::photon {

// Directions the fraction is measured along (a fixed spherical-Fibonacci set).
inline constexpr int kOpenBallDirections = 16;
// The least fraction returned: a ball nearly all behind surfaces keeps a bounded weight.
inline constexpr float kOpenBallMinFraction = 1.0f / 16;

// The fraction of the ball of radius `r` around `p` that lies in front of the first surface in
// each direction: in spherical coordinates the region's volume is the integral over directions of
// min(d(w), r)^3 / 3, estimated with kOpenBallDirections rays, (1/K) sum_k min(d_k, r)^3 / r^3.
// 1 when nothing is within r; never below kOpenBallMinFraction.
float open_ball_fraction(const accel::EmbreeScene& accel, Vec3 p, float r);

}  // namespace phos::photon
