// The value functions of pbrt-v4's procedural textures at a point, as pbrt-v4 defines them
// (PBRT 4th ed., sections 10.5-10.6) and without filtering: checkerboard parity, polka dots,
// windy waves and marble. fbm and wrinkled are perlin_noise.h's fbm and turbulence.
#pragma once

#include "core/vec.h"

namespace phos::scene {

// Whether the cell of (s, t) (cells centred on integer points) holds an odd checker: the sum of
// floor(s) + floor(t) (2D) or of the three floors (3D) is odd. Exact for any float (all floats
// beyond 2^24 are even integers); non-finite coordinates count as even.
bool checker_odd(Vec2 st);
bool checker_odd(Vec3 p);

// pbrt's polka dots: the cell of (s, t) around the nearest integer point holds a dot when the
// noise at its centre (z = 1/2) is positive; the dot, of radius 0.35, is shifted from the cell's
// integer point by up to 0.15 in s and t, by noise.
bool inside_polka_dot(Vec2 st);

// pbrt's windy texture: |fbm(p / 10, 1/2, 3)| (wind strength) times fbm(p, 1/2, 6) (waves).
float windy(Vec3 p);

// pbrt's marble: with q = scale p, t = 1/2 + sin(q.y + variation fbm(q, omega, octaves)) / 2
// picks a point on pbrt's piecewise cubic Bezier spline through nine marble colours, times 1.5.
// Each channel lies in [0.3, 0.9].
Rgb marble(Vec3 p, float scale, float variation, float omega, int octaves);

}  // namespace phos::scene
