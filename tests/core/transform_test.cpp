// Tests of core/transform: inverse, composition, and how points, vectors and normals transform.
#include "core/transform.h"

#include <gtest/gtest.h>

namespace phos {
namespace {

void expect_near(Vec3 a, Vec3 b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

TEST(Transform, TranslateScaleRotateCompose) {
    const Transform t =
        Transform::translate({1, 2, 3}) * Transform::rotate(90, {0, 0, 1}) * Transform::scale({2, 2, 2});
    expect_near(t.point({1, 0, 0}), {1, 4, 3});
    expect_near(t.vector({1, 0, 0}), {0, 2, 0});
    expect_near(t.inverse().point(t.point({0.3f, -0.7f, 5})), {0.3f, -0.7f, 5});
}

TEST(Transform, NormalsStayPerpendicular) {
    const Transform t = Transform::scale({1, 4, 1}) * Transform::rotate(30, {1, 1, 0});
    const Vec3 tangent{1, -1, 0.5f};
    const Vec3 n = normalize(cross(tangent, Vec3{0, 0, 1}));
    EXPECT_NEAR(dot(t.vector(tangent), t.normal(n)), 0.0f, 1e-5f);
}

TEST(Transform, MatrixInverseOfSingularFails) {
    Mat4 m;
    m(1, 1) = 0;
    Mat4 out;
    EXPECT_FALSE(m.inverse(out));
}

TEST(Transform, HandednessFlip) {
    EXPECT_TRUE(Transform::scale({-1, 1, 1}).swaps_handedness());
    EXPECT_FALSE(Transform::rotate(45, {0, 1, 0}).swaps_handedness());
}

}  // namespace
}  // namespace phos
