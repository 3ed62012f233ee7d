// The equal-area octahedral mapping: it round-trips, its pixels all cover 4 pi / N^2 steradians
// (measured as spherical polygons, independently of the mapping's own formulas), and the
// octahedral wrap moves a pixel across the border to its geometric neighbour.
#include "core/equal_area.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "core/warp.h"

namespace phos {
namespace {

double angle(Vec3 a, Vec3 b) { return std::atan2(double(length(cross(a, b))), double(dot(a, b))); }

// Solid angle of the spherical triangle (a, b, c) of unit vectors (Van Oosterom & Strackee 1983).
double triangle_solid_angle(Vec3 a, Vec3 b, Vec3 c) {
    const double num = std::fabs(double(dot(a, cross(b, c))));
    const double den = 1 + double(dot(a, b)) + double(dot(b, c)) + double(dot(c, a));
    return 2 * std::atan2(num, den);
}

TEST(EqualArea, RoundTrips) {
    Sampler rng(7);
    for (int i = 0; i < 20000; ++i) {
        const Vec3 w = warp::uniform_sphere(rng.next2());
        const Vec2 uv = equal_area_sphere_to_square(w);
        ASSERT_GE(uv.x, 0.0f);
        ASSERT_LE(uv.x, 1.0f);
        ASSERT_GE(uv.y, 0.0f);
        ASSERT_LE(uv.y, 1.0f);
        const Vec3 back = equal_area_square_to_sphere(uv);
        ASSERT_NEAR(length(back), 1.0f, 1e-5f);
        ASSERT_LT(angle(w, back), 2e-3) << "w = " << w.x << " " << w.y << " " << w.z;
        const Vec2 p = rng.next2();
        const Vec2 q = equal_area_sphere_to_square(equal_area_square_to_sphere(p));
        ASSERT_NEAR(q.x, p.x, 1e-4f);
        ASSERT_NEAR(q.y, p.y, 1e-4f);
    }
    // The landmarks: the centre is +z, the corners -z, the edge midpoints of the diamond the equator.
    const Vec3 up = equal_area_square_to_sphere({0.5f, 0.5f});
    EXPECT_NEAR(up.z, 1.0f, 1e-6f);
    EXPECT_NEAR(equal_area_square_to_sphere({0, 0}).z, -1.0f, 1e-6f);
    EXPECT_NEAR(equal_area_square_to_sphere({1, 1}).z, -1.0f, 1e-6f);
    const Vec3 px = equal_area_square_to_sphere({1, 0.5f});
    EXPECT_NEAR(px.x, 1.0f, 1e-6f);
    const Vec3 py = equal_area_square_to_sphere({0.5f, 1});
    EXPECT_NEAR(py.y, 1.0f, 1e-6f);
}

// Every pixel of an 8 x 8 map covers 4 pi / 64: each pixel is cut into 24 x 24 cells whose corners
// are mapped to the sphere, each cell measured as two spherical triangles.
TEST(EqualArea, PixelsHaveEqualSolidAngle) {
    constexpr int N = 8, S = 24;
    double total = 0;
    for (int py = 0; py < N; ++py)
        for (int px = 0; px < N; ++px) {
            double omega = 0;
            for (int j = 0; j < S; ++j)
                for (int i = 0; i < S; ++i) {
                    auto corner = [&](int a, int b) {
                        return normalize(equal_area_square_to_sphere(
                            {(float(px) + float(i + a) / S) / N, (float(py) + float(j + b) / S) / N}));
                    };
                    const Vec3 c00 = corner(0, 0), c10 = corner(1, 0), c11 = corner(1, 1), c01 = corner(0, 1);
                    omega += triangle_solid_angle(c00, c10, c11) + triangle_solid_angle(c00, c11, c01);
                }
            EXPECT_NEAR(omega, 4 * M_PI / (N * N), 4 * M_PI / (N * N) * 3e-3) << "pixel " << px << ", " << py;
            total += omega;
        }
    EXPECT_NEAR(total, 4 * M_PI, 1e-3);
}

// A pixel past the border, wrapped, is the pixel whose centre lies next to the border pixel's
// centre on the sphere (one pixel's angular size away, not across the map).
TEST(EqualArea, OctahedralWrapFindsTheNeighbourAcrossTheBorder) {
    constexpr int N = 16;
    const double pixel = std::sqrt(4 * M_PI / (N * N));
    auto centre = [&](int x, int y) {
        return normalize(equal_area_square_to_sphere({(float(x) + 0.5f) / N, (float(y) + 0.5f) / N}));
    };
    for (int k = 0; k < N; ++k) {
        const int outside[4][2] = {{-1, k}, {N, k}, {k, -1}, {k, N}};
        const int inside[4][2] = {{0, k}, {N - 1, k}, {k, 0}, {k, N - 1}};
        for (int s = 0; s < 4; ++s) {
            int x = outside[s][0], y = outside[s][1];
            wrap_octahedral(x, y, N);
            ASSERT_GE(x, 0);
            ASSERT_LT(x, N);
            ASSERT_GE(y, 0);
            ASSERT_LT(y, N);
            EXPECT_LT(angle(centre(x, y), centre(inside[s][0], inside[s][1])), 2.0 * pixel)
                << "side " << s << ", k " << k << " wrapped to " << x << ", " << y;
        }
    }
    int x = 3, y = 5;
    wrap_octahedral(x, y, N);
    EXPECT_EQ(x, 3);
    EXPECT_EQ(y, 5);
}

}  // namespace
}  // namespace phos
