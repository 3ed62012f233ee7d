// The equal-area octahedral mapping between the unit square and the unit sphere (Clarberg 2008,
// "Fast Equal-Area Mapping of the (Hemi)Sphere using SIMD", the form pbrt-v4 uses for its
// environment maps and goniometric lights): equal areas of the square map to equal solid angles,
// so each pixel of an N x N map covers 4 pi / N^2 steradians.
#pragma once

#include "core/vec.h"

namespace phos {

// A point of [0,1]^2 to a unit direction. (0.5, 0.5) is +z, the square's corners are -z, the inner
// diamond |2u-1| + |2v-1| <= 1 the upper hemisphere; u grows towards +x, v towards +y.
Vec3 equal_area_square_to_sphere(Vec2 p);
// A unit direction to its point of [0,1]^2 (the inverse of the above).
Vec2 equal_area_sphere_to_square(Vec3 d);
// Pixel coordinates (x, y) of an n x n equal-area map that fall outside it, moved to the pixel
// across the border as the octahedron folds (pbrt-v4's "octahedral sphere" wrap): over a side the
// image is mirrored along that side.
void wrap_octahedral(int& x, int& y, int n);

}  // namespace phos
