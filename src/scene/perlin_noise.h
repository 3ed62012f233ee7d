// Perlin's gradient noise and the sums of its octaves that pbrt's procedural textures are built
// from: fractional Brownian motion (fbm, marble, windy) and turbulence (wrinkled).
#pragma once

#include "core/vec.h"

namespace phos::scene {

// Perlin's "improved noise" (K. Perlin, "Improving Noise", SIGGRAPH 2002): at the eight corners
// of the unit lattice cell holding p, a gradient picked by hashing the corner through Perlin's
// 256-entry permutation table, dotted with the offset from that corner, blended by the quintic
// 6t^5 - 15t^4 + 10t^3. Zero at every lattice point; within about [-1, 1]. Coordinates are
// reduced modulo 2^30 first (as pbrt-v4 does, so that huge ones stay in integer range); a
// non-finite coordinate gives 0.
float perlin_noise(float x, float y, float z);
inline float perlin_noise(Vec3 p) { return perlin_noise(p.x, p.y, p.z); }

// Fractional Brownian motion as pbrt-v4 sums it (PBRT 4th ed., section 10.6.3) with zero filter
// widths, i.e. every octave: sum over i < octaves of omega^i * noise(1.99^i * p).
float fbm(Vec3 p, float omega, int octaves);

// Turbulence as pbrt-v4 sums it with zero filter widths: sum over i < octaves of
// omega^i * |noise(1.99^i * p)|, plus the 0.2 * omega^octaves pbrt adds for the octave past the
// last (its average |noise| stand-in for the octaves a filter clamps away).
float turbulence(Vec3 p, float omega, int octaves);

}  // namespace phos::scene
