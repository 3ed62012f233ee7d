// Tests of photon/open_ball.h: the share of a ball in front of surfaces, against the closed form of
// a ball cut by a plane (the cap beyond a plane at distance h < r has volume
// pi (r - h)^2 (2r + h) / 3), in free space, and at its floor.
#include "photon/open_ball.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/shapes.h"

namespace phos::photon {
namespace {

double plane_cut_fraction(double h, double r) {
    if (h >= r) return 1;
    const double cap = M_PI * (r - h) * (r - h) * (2 * r + h) / 3;
    return 1 - cap / (4.0 / 3.0 * M_PI * r * r * r);
}

TEST(OpenBall, FreeSpaceIsWhole) {
    const scene::Scene s = testing::floor_scene();
    const accel::EmbreeScene accel(s);
    EXPECT_EQ(open_ball_fraction(accel, {0, 2, 0}, 1.0f), 1.0f);
}

TEST(OpenBall, APlaneThroughTheBallMatchesTheCapVolume) {
    const scene::Scene s = testing::floor_scene();
    const accel::EmbreeScene accel(s);
    // Sixteen directions estimate the integral over the sphere: within 0.06 of the closed form.
    for (double h : {0.05, 0.25, 0.5, 0.75}) {
        const float f = open_ball_fraction(accel, {0.1f, float(h), -0.2f}, 1.0f);
        EXPECT_NEAR(f, plane_cut_fraction(h, 1.0), 0.06) << "h " << h;
    }
    // Monotone in the distance to the plane.
    EXPECT_LT(open_ball_fraction(accel, {0, 0.1f, 0}, 1.0f), open_ball_fraction(accel, {0, 0.6f, 0}, 1.0f));
}

TEST(OpenBall, AClosedTightBoxGivesTheFloor) {
    scene::Scene s;
    s.materials.emplace_back();
    scene::Shape b = testing::box(Vec3(-0.01f), Vec3(0.01f));
    b.material = 0;
    s.shapes.push_back(b);
    const accel::EmbreeScene accel(s);
    EXPECT_EQ(open_ball_fraction(accel, Vec3(0.0f), 1.0f), kOpenBallMinFraction);
}

}  // namespace
}  // namespace phos::photon
