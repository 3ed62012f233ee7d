// A double-Gauss photographic lens in pbrt-v4's lens file format (the f/2 design of US patent
// 2,673,491 scaled to 50 mm, as in Smith's "Modern Lens Design" and Kolb et al. 1995), for tests of
// the realistic camera.
#pragma once

namespace phos::testing {

inline constexpr const char* kDoubleGaussLens =
    "# D-GAUSS F/2 22deg HFOV, scaled to 50 mm\n"
    "# radius thickness eta aperture (mm)\n"
    "29.475  3.76   1.67   25.2\n"
    "84.83   0.12   1      25.2\n"
    "19.275  4.025  1.67   23.0\n"
    "40.77   3.275  1.699  23.0\n"
    "12.75   5.705  1      18.0\n"
    "0       4.5    0      17.1   # the aperture stop\n"
    "-14.495 1.18   1.603  17.0\n"
    "40.77   6.065  1.658  20.0\n"
    "-20.385 0.19   1      20.0\n"
    "437.065 3.22   1.717  20.0\n"
    "-39.73  40.0   1      20.0\n";

}  // namespace phos::testing
