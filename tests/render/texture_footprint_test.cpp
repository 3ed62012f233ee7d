// pbrt-v4's camera footprint (CameraModel::texture_footprint, scene/camera_footprint.h) against
// closed forms: a perspective camera's minimum direction differential is the angle between the
// rays of the image corner's pixel and its neighbour (the smallest pixel over the diagonal), so a
// plane seen head-on at distance d gets dp/dx of length d tan(that angle), which for a narrow
// field of view is the pixel's size at distance d; an orthographic camera's pixel is its size at
// any depth; 1/sqrt(spp) (at least 1/8) scales both; the (u, v) derivatives solve
// dp/dx = dpdu du/dx + dpdv dv/dx.
#include <gtest/gtest.h>

#include <cmath>

#include "render/camera.h"
#include "scene/camera_footprint.h"

namespace phos::render {
namespace {

double angle(double ax, double ay, double bx, double by) {
    const double na = std::sqrt(ax * ax + ay * ay + 1), nb = std::sqrt(bx * bx + by * by + 1);
    const double c = (ax * bx + ay * by + 1) / (na * nb);
    return std::acos(std::min(1.0, c));
}

TEST(TextureFootprint, HeadOnPlaneSeenByAPerspectiveCamera) {
    const int w = 64, h = 48;
    const double fov = 10.0 * 3.14159265358979 / 180;  // along the shorter side (the height)
    scene::Camera cam;
    cam.eye = Vec3(1, 2, 3);
    cam.forward = Vec3(0, 0, -1);
    cam.up = Vec3(0, 1, 0);
    cam.fov = float(fov);
    const CameraModel model(cam, w, h);
    // Image plane at distance 1: half extents and the pixel pitch.
    const double half_h = std::tan(fov / 2), half_w = half_h * w / h, a = 2 * half_h / h;
    // The smallest pixel over the diagonal: at the bottom-right corner (film (w, h)), its
    // neighbours one pixel further right and further down.
    const double theta_x = angle(half_w, -half_h, half_w + a, -half_h);
    const double theta_y = angle(half_w, -half_h, half_w, -half_h - a);
    for (const double d : {2.0, 50.0}) {
        const scene::CameraFootprint f = model.texture_footprint(1);
        EXPECT_EQ(f.spp_scale, 1.0f);
        Vec3 dpdx, dpdy;
        const Vec3 p = cam.eye + Vec3(0, 0, -float(d));
        scene::approximate_dp_dxy(f, p, Vec3(0, 0, 1), dpdx, dpdy);
        EXPECT_NEAR(length(dpdx), d * std::tan(theta_x), 1e-4 * d * a) << d;
        EXPECT_NEAR(length(dpdy), d * std::tan(theta_y), 1e-4 * d * a) << d;
        EXPECT_NEAR(dpdx.z, 0.0f, 1e-6 * d);  // in the plane
        EXPECT_NEAR(dpdy.z, 0.0f, 1e-6 * d);
        // Nearly perpendicular (the corner's neighbours, seen in that ray's own frame).
        EXPECT_NEAR(std::fabs(dot(normalize(dpdx), normalize(dpdy))), 0.0f, 0.02f);
        // A narrow view: that is the pixel's size at distance d, within 3 %.
        EXPECT_NEAR(length(dpdx) / (d * a), 1.0, 0.03);
        // More samples per pixel: 1 / sqrt(spp), at least 1/8.
        Vec3 dpdx16, dpdy16;
        scene::approximate_dp_dxy(model.texture_footprint(16), p, Vec3(0, 0, 1), dpdx16, dpdy16);
        EXPECT_NEAR(length(dpdx16), 0.25 * length(dpdx), 1e-5 * d);
        scene::approximate_dp_dxy(model.texture_footprint(10000), p, Vec3(0, 0, 1), dpdx16, dpdy16);
        EXPECT_NEAR(length(dpdx16), 0.125 * length(dpdx), 1e-5 * d);
    }
    // A plane tilted by 60 degrees about x stretches dp/dy by 1 / cos 60 = 2 (to first order, and
    // with dp/dy nearly along the image's y).
    const float t = 60.0f * kPi / 180;
    Vec3 dpdx, dpdy;
    scene::approximate_dp_dxy(model.texture_footprint(1), cam.eye + Vec3(0, 0, -10),
                              Vec3(0, std::sin(t), std::cos(t)), dpdx, dpdy);
    EXPECT_NEAR(length(dpdy) / (10 * std::tan(theta_y)), 2.0, 0.03);
    EXPECT_NEAR(length(dpdx) / (10 * std::tan(theta_x)), 1.0, 0.03);
}

TEST(TextureFootprint, OrthographicPixelAtAnyDepth) {
    scene::Camera cam;
    cam.projection = scene::Camera::Projection::Orthographic;
    cam.forward = Vec3(0, -1, 0);
    cam.up = Vec3(0, 0, 1);
    cam.ortho_half_size = 2;
    const CameraModel model(cam, 32, 32);
    const scene::CameraFootprint f = model.texture_footprint(4);
    for (const float d : {1.0f, 100.0f}) {
        Vec3 dpdx, dpdy;
        scene::approximate_dp_dxy(f, Vec3(0, -d, 0), Vec3(0, 1, 0), dpdx, dpdy);
        EXPECT_NEAR(length(dpdx), 0.5f * 4.0f / 32, 1e-6f);  // spp 4: half the 1/8 pixel
        EXPECT_NEAR(length(dpdy), 0.5f * 4.0f / 32, 1e-6f);
    }
}

TEST(TextureFootprint, UvDerivativesSolveTheTangentPlane) {
    const Vec3 dpdu(2, 0, 0), dpdv(1, 0, -4);  // not orthogonal
    // dp/dx = 0.1 dpdu + 0.2 dpdv, dp/dy = -0.3 dpdu + 0.05 dpdv, plus a normal component that
    // the least-squares solution ignores.
    const Vec3 n(0, 1, 0);
    const scene::UvDerivatives d =
        scene::uv_derivatives(dpdu, dpdv, dpdu * 0.1f + dpdv * 0.2f + n * 0.7f, dpdu * -0.3f + dpdv * 0.05f);
    EXPECT_NEAR(d.dudx, 0.1f, 1e-6f);
    EXPECT_NEAR(d.dvdx, 0.2f, 1e-6f);
    EXPECT_NEAR(d.dudy, -0.3f, 1e-6f);
    EXPECT_NEAR(d.dvdy, 0.05f, 1e-6f);
    // Degenerate derivatives give zeros, not NaNs.
    const scene::UvDerivatives z =
        scene::uv_derivatives(Vec3(0.0f), Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 1, 0));
    EXPECT_EQ(z.dudx, 0.0f);
    EXPECT_EQ(z.dvdy, 0.0f);
}

}  // namespace
}  // namespace phos::render
