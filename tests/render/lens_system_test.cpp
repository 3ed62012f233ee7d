// The realistic camera's lens system (render/lens_system.h) against closed forms: a thick biconvex
// lens's focal length by the lensmaker's equation, rays from one film point meeting again at the
// focus distance, the camera weight's mean as the projected solid angle of the rear disk, rays the
// stop blocks, and the realistic CameraModel's empty rays.
#include "render/lens_system.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "core/error.h"
#include "render/camera.h"
#include "support/double_gauss_lens.h"

namespace phos::render {
namespace {

// One biconvex lens (radii +-50 mm, 2 mm thick, n = 1.5, 20 mm across) 50 mm before the film
// (before focusing) and, optionally, a stop of radius `stop` 1 mm in front of it.
std::vector<scene::LensElement> biconvex(float stop = 0) {
    std::vector<scene::LensElement> e = {{0.05f, 0.002f, 1.5f, 0.01f}, {-0.05f, 0.05f, 1.0f, 0.01f}};
    if (stop > 0) e.insert(e.begin(), {0, 0.001f, 1.0f, stop});
    return e;
}

TEST(LensSystem, TheFocalLengthIsTheLensmakers) {
    // 1/f = (n - 1) (1/R1 - 1/R2 + (n - 1) d / (n R1 R2)) for a thick lens in air.
    const double n = 1.5, r1 = 0.05, r2 = -0.05, d = 0.002;
    const double f = 1 / ((n - 1) * (1 / r1 - 1 / r2 + (n - 1) * d / (n * r1 * r2)));
    const LensSystem lens(biconvex(), 1.0);
    EXPECT_NEAR(lens.focal_length(), f, 1e-5 * f);
}

// The point where two rays pass closest to each other (the midpoint of their common perpendicular).
LensSystem::Point meet(const LensSystem::LensRay& a, const LensSystem::LensRay& b) {
    const auto dot = [](const LensSystem::Point& p, const LensSystem::Point& q) {
        return p.x * q.x + p.y * q.y + p.z * q.z;
    };
    const LensSystem::Point w{a.o.x - b.o.x, a.o.y - b.o.y, a.o.z - b.o.z};
    const double aa = dot(a.d, a.d), ab = dot(a.d, b.d), bb = dot(b.d, b.d), aw = dot(a.d, w),
                 bw = dot(b.d, w);
    const double den = aa * bb - ab * ab;
    const double s = (ab * bw - bb * aw) / den, t = (aa * bw - ab * aw) / den;
    const LensSystem::Point p = a.at(s), q = b.at(t);
    return {(p.x + q.x) / 2, (p.y + q.y) / 2, (p.z + q.z) / 2};
}

TEST(LensSystem, RaysFromOneFilmPointMeetAtTheFocusDistance) {
    for (const double focus : {0.5, 1.0, 3.0}) {
        const LensSystem lens(biconvex(), focus);
        // Paraxial rays (near the middle of the rear disk): the thick-lens approximation is exact
        // there, so they meet on the plane `focus` from the film, at the image of the film point.
        // (Paraxial: 0.1 mm from the axis on the rear element and the film, where spherical
        // aberration and field curvature move the meeting point by far less than the tolerance; at
        // 1 mm they move it by several mm at 3 m.)
        for (const Vec2 film : {Vec2(0, 0), Vec2(0.0001f, -0.00005f)}) {
            LensSystem::LensRay ref;
            ASSERT_GT(lens.generate(film, {0.5f, 0.5f}, ref), 0);
            const Vec2 us[] = {{0.505f, 0.5f}, {0.5f, 0.496f}, {0.496f, 0.504f}};
            for (const Vec2 u : us) {
                LensSystem::LensRay r;
                ASSERT_GT(lens.generate(film, u, r), 0);
                const LensSystem::Point p = meet(ref, r);
                EXPECT_NEAR(p.z, focus, 2e-3 * focus) << focus;
                // The lens turns the image over: the film point's image is on the other side.
                if (film.x != 0) {
                    EXPECT_LT(p.x * film.x, 0);
                }
            }
        }
        // Rays from a film point behind the focus meet elsewhere: nearer the lens.
        const LensSystem other(biconvex(), 2 * focus);
        LensSystem::LensRay a, b;
        ASSERT_GT(other.generate({0, 0}, {0.5f, 0.5f}, a), 0);
        ASSERT_GT(other.generate({0, 0}, {0.52f, 0.5f}, b), 0);
        EXPECT_GT(std::fabs(meet(a, b).z - focus), 0.2 * focus);
    }
}

TEST(LensSystem, TheMeanWeightIsTheRearDisksProjectedSolidAngle) {
    // Nothing blocks rays from the film's centre through this plano-convex lens (flat rear side
    // 20 mm across, wider front), so the mean of pbrt-v4's weight cos^4 / (pdf z^2) over the rear
    // disk is the disk's projected solid angle pi r^2 / (r^2 + z^2) seen from the film's centre.
    const LensSystem lens({{0.025f, 0.004f, 1.5f, 0.012f}, {1000.0f, 0.05f, 1.0f, 0.01f}}, 1.0);
    const double r = lens.rear_radius(), z = lens.rear_z();
    const int n = 256;
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            LensSystem::LensRay out;
            const double w = lens.generate({0, 0}, {(float(i) + 0.5f) / n, (float(j) + 0.5f) / n}, out);
            ASSERT_GT(w, 0);
            sum += w;
        }
    EXPECT_NEAR(sum / (n * n), kPi * r * r / (r * r + z * z), 2e-3 * kPi * r * r / (r * r + z * z));
}

TEST(LensSystem, TheStopBlocksRaysOutsideIt) {
    // A stop 2 mm across before the lens: rays from the centre through the rear disk's middle pass,
    // those through its edge do not, and about (1 mm / 10 mm)^2 of the disk passes (rays from the
    // film near the focal plane leave the lens almost parallel).
    const LensSystem lens(biconvex(0.001f), 1.0);
    LensSystem::LensRay out;
    EXPECT_GT(lens.generate({0, 0}, {0.5f, 0.5f}, out), 0);
    EXPECT_EQ(lens.generate({0, 0}, {0.99f, 0.5f}, out), 0);
    int passed = 0;
    const int n = 200;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            passed += lens.generate({0, 0}, {(float(i) + 0.5f) / n, (float(j) + 0.5f) / n}, out) > 0;
    EXPECT_NEAR(double(passed) / (n * n), 0.01, 0.003);
    // A film point far off the axis sees no way through.
    EXPECT_EQ(lens.generate({0.05f, 0}, {0.5f, 0.5f}, out), 0);
}

// The mean weight over the rear disk from the film's centre.
double mean_weight(const LensSystem& lens, int n = 200) {
    double sum = 0;
    LensSystem::LensRay out;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            sum += lens.generate({0, 0}, {(float(i) + 0.5f) / n, (float(j) + 0.5f) / n}, out);
    return sum / (double(n) * n);
}

TEST(LensSystem, AShapedStopPassesAsMuchLightAsTheCircle) {
    // pbrt-v4's "square" diaphragm: transmission 4 over the middle half of the stop's bounding
    // square (mean pi/4 over the square, 1 over the circle's area). Where the stop limits the
    // light, the square passes what the circle does, and blocks rays outside it.
    scene::ApertureImage square;
    square.width = square.height = 8;
    square.values.assign(64, 0.0f);
    for (int y = 2; y < 6; ++y)
        for (int x = 2; x < 6; ++x) square.values[size_t(y) * 8 + size_t(x)] = float(kPi);
    const LensSystem circle(biconvex(0.001f), 1.0), shaped(biconvex(0.001f), 1.0, square);
    // (The image is bilinearly interpolated over its 8 pixels: its edges are soft, its integral
    // that of the 4 x 4 pixels, pi/4 of the square's area times (8 / 8)^2.)
    const double a = mean_weight(circle, 600), b = mean_weight(shaped, 600);
    EXPECT_NEAR(b / a, 1.0, 0.03);
    // Along the axis it passes pi, not the circle's 1.
    LensSystem::LensRay out;
    EXPECT_NEAR(shaped.generate({0, 0}, {0.5f, 0.5f}, out) / circle.generate({0, 0}, {0.5f, 0.5f}, out), kPi,
                1e-3);
    EXPECT_THROW(LensSystem(biconvex(0.001f), 1.0, scene::ApertureImage{2, 2, {1.0f}}), InputError);
}

// The double-Gauss lens of tests/support in metres, its stop `stop_diameter` mm across.
std::vector<scene::LensElement> double_gauss(float stop_diameter) {
    std::istringstream in(testing::kDoubleGaussLens);
    std::vector<scene::LensElement> e;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream fields(line.substr(0, line.find('#')));
        float r, t, eta, a;
        if (!(fields >> r >> t >> eta >> a)) continue;
        if (r == 0) a = stop_diameter;
        e.push_back({r / 1000, t / 1000, eta == 0 ? 1.0f : eta, a / 2000});
    }
    return e;
}

TEST(LensSystem, ExitPupilSamplingIsUnbiasedAndWastesFewerRays) {
    // pbrt-v4's exit-pupil bounds per film ring against the whole rear disk: the same mean weight
    // at film points across a 35 mm film, with far fewer blocked rays for a small stop.
    for (const float stop : {17.0f, 4.0f}) {
        const LensSystem disk(double_gauss(stop), 2.0), pupil(double_gauss(stop), 2.0, {}, 0.0175);
        for (const Vec2 film : {Vec2(0, 0), Vec2(0.005f, 0.003f), Vec2(-0.009f, 0.007f)}) {
            double sum_disk = 0, sum_pupil = 0;
            int passed_disk = 0, passed_pupil = 0;
            const int n = stop < 5 ? 800 : 300;  // a small pupil needs more of the disk grid
            LensSystem::LensRay out;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    const Vec2 u((float(i) + 0.5f) / n, (float(j) + 0.5f) / n);
                    const double a = disk.generate(film, u, out), b = pupil.generate(film, u, out);
                    sum_disk += a, sum_pupil += b;
                    passed_disk += a > 0, passed_pupil += b > 0;
                }
            ASSERT_GT(sum_disk, 0);
            EXPECT_NEAR(sum_pupil / sum_disk, 1.0, 0.02) << stop << " mm at " << film.x << ", " << film.y;
            if (stop < 5) {
                EXPECT_GT(passed_pupil, 4 * passed_disk);
            }
        }
    }
}

TEST(LensSystem, FocusingCloserThanTheLensCanIsRefused) {
    EXPECT_THROW(LensSystem(biconvex(), 0.1), InputError);
    std::vector<scene::LensElement> closed = biconvex(0.001f);
    closed[0].aperture_radius = 1e-9f;
    EXPECT_THROW(LensSystem(closed, 1.0), InputError);
}

TEST(RealisticCamera, BlockedRaysAreEmptyWithWeightZero) {
    scene::Camera c;
    c.projection = scene::Camera::Projection::Realistic;
    c.eye = Vec3(0, 0, 0);
    c.forward = Vec3(0, 0, 1);
    c.flip_x = true;  // camera +x is world +x, as pbrt's LookAt along +z makes it
    c.lens_elements = biconvex(0.002f);
    c.lens_focus_distance = 1;
    c.film_diagonal = 2.0f;  // far wider than the lens can cover: its corners see nothing
    const CameraModel cam(c, 40, 30);
    float w = -1;
    const Ray centre = cam.generate_ray(20, 15, {0.5f, 0.5f}, w);
    EXPECT_GT(w, 0);
    EXPECT_LT(centre.tmin, centre.tmax);
    EXPECT_GT(centre.dir.z, 0.99f);     // along the axis, into the scene
    EXPECT_GT(centre.origin.z, 0.05f);  // from the front element
    const Ray corner = cam.generate_ray(0.5f, 0.5f, {0.5f, 0.5f}, w);
    EXPECT_EQ(w, 0);
    EXPECT_LT(corner.tmax, corner.tmin);
    // Light paths cannot reach it: no direction density, no connection, no projection.
    EXPECT_EQ(cam.direction_pdf(Vec3(0, 0, 1)), 0);
    CameraModel::Connection conn;
    EXPECT_FALSE(cam.connect(Vec3(0, 0, 5), {0.5f, 0.5f}, conn));
    // Image left (small x) sees the camera's left (-x), its top the camera's up (+y).
    const Ray left = cam.generate_ray(18, 15, {0.5f, 0.5f}, w);
    ASSERT_GT(w, 0);
    EXPECT_LT(left.dir.x, 0);
    const Ray top = cam.generate_ray(20, 13, {0.5f, 0.5f}, w);
    ASSERT_GT(w, 0);
    EXPECT_GT(top.dir.y, 0);
    EXPECT_GT(cam.pixel_footprint().slope, 0);
}

}  // namespace
}  // namespace phos::render
