// Camera model tests: the field of view spans the shorter image side, projection inverts ray
// generation, and thin-lens rays through one film point all meet on the focal plane.
#include "render/camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/stats.h"
#include "render/prepared.h"

namespace phos::render {
namespace {

scene::Camera test_camera() {
    scene::Camera c;
    c.eye = Vec3(1, 2, 3);
    c.forward = Vec3(0, 0, -1);
    c.up = Vec3(0, 1, 0);
    c.fov = 2 * 0.331613f;  // the bench scenes' half angle of 19 degrees
    return c;
}

TEST(Camera, FieldOfViewSpansTheShorterSide) {
    for (auto [w, h] : {std::pair{256, 256}, std::pair{400, 200}, std::pair{200, 400}}) {
        const CameraModel cam(test_camera(), w, h);
        // The ray through the middle of the shorter side's edge makes half the fov with the axis.
        const Ray edge = w >= h ? cam.generate_ray(0.5f * float(w), 0, {0.5f, 0.5f})
                                : cam.generate_ray(0, 0.5f * float(h), {0.5f, 0.5f});
        EXPECT_NEAR(std::acos(dot(normalize(edge.dir), Vec3(0, 0, -1))), 0.331613f, 1e-5f) << w << "x" << h;
    }
}

// The .scene format's d: the fov spans the image height whatever the aspect (a tall image is not
// narrowed to keep the fov on its shorter, horizontal side).
TEST(Camera, VerticalFieldOfView) {
    scene::Camera c = test_camera();
    c.fov_vertical = true;
    for (auto [w, h] : {std::pair{256, 256}, std::pair{400, 200}, std::pair{200, 400}}) {
        const CameraModel cam(c, w, h);
        const Ray top = cam.generate_ray(0.5f * float(w), 0, {0.5f, 0.5f});
        EXPECT_NEAR(std::acos(dot(normalize(top.dir), Vec3(0, 0, -1))), 0.331613f, 1e-5f) << w << "x" << h;
    }
}

// near / far (the .scn camera's clip distances) are measured along the viewing axis: a ray at
// angle a to the axis starts at near / cos a and ends at far / cos a, so a wall the camera sits
// against (spotlight2) is clipped away.
TEST(Camera, NearAndFarClipAlongTheAxis) {
    scene::Camera c = test_camera();
    c.near_clip = 0.25f;
    c.far_clip = 40.0f;
    const CameraModel cam(c, 200, 100);
    for (const auto& [fx, fy] : {std::pair{100.0f, 50.0f}, std::pair{0.5f, 0.5f}, std::pair{199.5f, 70.0f}}) {
        const Ray r = cam.generate_ray(fx, fy, {0.5f, 0.5f});
        const float cos_a = dot(normalize(r.dir), Vec3(0, 0, -1));
        EXPECT_NEAR(r.tmin * length(r.dir) * cos_a, 0.25f, 1e-5f);
        EXPECT_NEAR(r.tmax * length(r.dir) * cos_a, 40.0f, 1e-3f);
    }
}

TEST(Camera, ImageRightIsCrossOfForwardAndUpAndTopIsUp) {
    const CameraModel cam(test_camera(), 100, 100);
    const Ray right = cam.generate_ray(99.5f, 50, {0.5f, 0.5f});
    const Ray top = cam.generate_ray(50, 0.5f, {0.5f, 0.5f});
    EXPECT_GT(right.dir.x, 0.1f);
    EXPECT_GT(top.dir.y, 0.1f);
}

TEST(Camera, ProjectInvertsGenerateRay) {
    const CameraModel cam(test_camera(), 320, 240);
    for (float fx : {3.5f, 100.25f, 319.0f})
        for (float fy : {0.5f, 120.0f, 239.5f}) {
            const Ray r = cam.generate_ray(fx, fy, {0.5f, 0.5f});
            float px, py;
            ASSERT_TRUE(cam.project(r.origin + r.dir * 7.0f, px, py));
            EXPECT_NEAR(px, fx, 1e-3f);
            EXPECT_NEAR(py, fy, 1e-3f);
        }
}

TEST(Camera, ThinLensRaysMeetOnTheFocalPlane) {
    scene::Camera c = test_camera();
    c.lens_radius = 0.05f;
    c.focal_distance = 2.5f;
    const CameraModel cam(c, 64, 64);
    const Vec3 focus_ref = [&] {
        scene::Camera pin = c;
        pin.lens_radius = 0;
        const Ray r = CameraModel(pin, 64, 64).generate_ray(20.3f, 41.7f, {0.5f, 0.5f});
        return r.origin + r.dir * (2.5f / dot(normalize(r.dir), Vec3(0, 0, -1)));
    }();
    float spread = 0;
    for (float u : {0.1f, 0.4f, 0.9f})
        for (float v : {0.05f, 0.6f, 0.95f}) {
            const Ray r = cam.generate_ray(20.3f, 41.7f, {u, v});
            // Origins are spread over the lens disk...
            EXPECT_LE(length(r.origin - c.eye), c.lens_radius * 1.0001f);
            spread = std::max(spread, length(r.origin - c.eye));
            // ...and every ray passes through the same point of the focal plane.
            const float t = (focus_ref.z - r.origin.z) / r.dir.z;
            const Vec3 p = r.origin + r.dir * t;
            EXPECT_NEAR(p.x, focus_ref.x, 1e-4f);
            EXPECT_NEAR(p.y, focus_ref.y, 1e-4f);
        }
    EXPECT_GT(spread, 0.02f);
}

TEST(Camera, ACropRendersItsPartOfTheImage) {
    // Pixel (x, y) of a crop starting at (20, 10) is pixel (x + 20, y + 10) of the whole image, and
    // light tracing's film density counts only the part rendered.
    const CameraModel whole(test_camera(), 64, 48);
    const CameraModel part(test_camera(), 16, 8, CropWindow{20, 10, 64, 48});
    const Ray a = whole.generate_ray(25.5f, 13.25f, {0.5f, 0.5f}),
              b = part.generate_ray(5.5f, 3.25f, {0.5f, 0.5f});
    EXPECT_NEAR(length(normalize(a.dir) - normalize(b.dir)), 0.0f, 1e-6f);
    float fx, fy;
    ASSERT_TRUE(part.project(b.origin + b.dir * 3.0f, fx, fy));
    EXPECT_NEAR(fx, 5.5f, 1e-3f);
    EXPECT_NEAR(fy, 3.25f, 1e-3f);
    EXPECT_FALSE(part.project(whole.generate_ray(2.0f, 2.0f, {0.5f, 0.5f}).dir * 3.0f + a.origin, fx, fy));
    const Vec3 d = normalize(a.dir);
    EXPECT_NEAR(part.direction_pdf(d) / whole.direction_pdf(d), (64.0 * 48) / (16.0 * 8), 1e-3);
}

TEST(Camera, SphericalMappingsCoverEveryDirectionAsPbrtDoes) {
    scene::Camera c = test_camera();
    c.projection = scene::Camera::Projection::Spherical;
    for (const auto mapping :
         {scene::Camera::SphericalMapping::Equirectangular, scene::Camera::SphericalMapping::EqualArea}) {
        c.spherical_mapping = mapping;
        const CameraModel cam(c, 64, 32);
        // project inverts generate_ray over the whole image.
        for (float fy : {1.5f, 8.25f, 16.0f, 30.5f})
            for (float fx : {0.5f, 17.0f, 40.75f, 63.5f}) {
                const Ray r = cam.generate_ray(fx, fy, {0.5f, 0.5f});
                EXPECT_NEAR(length(r.dir), 1.0f, 1e-5f);
                float px, py;
                ASSERT_TRUE(cam.project(r.origin + r.dir * 2.0f, px, py));
                EXPECT_NEAR(px, fx, 2e-2f) << fx << " " << fy;
                EXPECT_NEAR(py, fy, 2e-2f) << fx << " " << fy;
            }
        // The camera's density per unit solid angle integrates to 1 over the sphere.
        double total = 0;
        const int n = 400;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < 2 * n; ++j) {
                const double theta = kPi * (i + 0.5) / n, phi = 2 * kPi * (j + 0.5) / (2 * n);
                const Vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                             float(std::sin(theta) * std::sin(phi)));
                total += cam.direction_pdf(d) * std::sin(theta) * (kPi / n) * (2 * kPi / (2 * n));
            }
        EXPECT_NEAR(total, 1.0, 1e-2);
    }
    // Equirectangular: the top row looks up, u = 1/4 looks forward; equal-area: the centre looks up.
    c.spherical_mapping = scene::Camera::SphericalMapping::Equirectangular;
    const CameraModel eq(c, 64, 32);
    EXPECT_GT(eq.generate_ray(10.0f, 0.01f, {0.5f, 0.5f}).dir.y, 0.999f);
    EXPECT_GT(dot(eq.generate_ray(16.0f, 16.0f, {0.5f, 0.5f}).dir, Vec3(0, 0, -1)), 0.999f);
    c.spherical_mapping = scene::Camera::SphericalMapping::EqualArea;
    const CameraModel ea(c, 32, 32);
    EXPECT_GT(ea.generate_ray(16.0f, 16.0f, {0.5f, 0.5f}).dir.y, 0.999f);
}

TEST(Camera, FramesScenesWithoutACamera) {
    Bounds b;
    b.extend(Vec3(-1, 0, -2));
    b.extend(Vec3(3, 1, 0));
    const scene::Camera c = CameraModel::frame_bounds(b);
    const CameraModel cam(c, 64, 64);
    float fx, fy;
    EXPECT_TRUE(cam.project(b.center(), fx, fy));
    EXPECT_NEAR(fx, 32, 1e-3f);
    EXPECT_TRUE(cam.project(Vec3(-1, 0, 0), fx, fy));  // a front corner is in view
}

}  // namespace
}  // namespace phos::render

namespace phos::render {
namespace {

TEST(Camera, DepthOfFieldOverrideKeepsTheFramingOfCameralessScenes) {
    scene::Scene s;
    s.materials.emplace_back();
    scene::Shape sphere;
    sphere.kind = scene::Shape::Kind::Sphere;
    sphere.center = Vec3(5, 1, -3);
    sphere.radius = 0.5f;
    s.shapes.push_back(sphere);
    RenderOptions opt;
    opt.width = opt.height = 32;
    PrepareOptions prep;
    prep.lens_radius = 0.01f;
    prep.focal_distance = 2.0f;
    Stats stats;
    const Prepared P(s, opt, prep, stats);
    // The framing camera looks at the sphere (it is not replaced by a default camera at the origin)...
    float fx, fy;
    ASSERT_TRUE(P.camera.project(sphere.center, fx, fy));
    EXPECT_NEAR(fx, 16, 1e-3f);
    EXPECT_NEAR(fy, 16, 1e-3f);
    // ...and its rays start on the lens, not all at one point.
    const Ray a = P.camera.generate_ray(16, 16, {0.1f, 0.1f});
    const Ray b = P.camera.generate_ray(16, 16, {0.9f, 0.9f});
    EXPECT_GT(length(a.origin - b.origin), 0.005f);
}

}  // namespace
}  // namespace phos::render
