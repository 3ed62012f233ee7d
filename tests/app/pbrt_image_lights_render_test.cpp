// pbrt image lights rendered by the phos binary with every integrator: an equal-area environment
// map whose only lit pixels lie overhead lights a diffuse floor by the closed form (and leaves it
// black when they lie below); a goniometric light lights the floor only when its map's lit half
// faces it; a projection light's slide lands on the floor below it with I / h^2 at its centre; an
// image area light shows its image the right way round.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/equal_area.h"
#include "io/image/image_io.h"
#include "test_util.h"

namespace phos::testing {
namespace {

// Looking straight down at the origin from y = 3, world +x to the image's right, +z up.
const std::string kView = "LookAt 0 3 0  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" 40\nWorldBegin\n";
// A diffuse floor of albedo 0.5 filling the view.
const std::string kFloor =
    "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
    "Shape \"trianglemesh\" \"point3 P\" [-8 0 -8  8 0 -8  8 0 8  -8 0 8] \"integer indices\" [0 1 2 0 2 "
    "3]\n";

const char* const kIntegrators[] = {"whitted", "path", "photonmap", "ppm", "sppm", "bdpt", "vcm"};

std::string budget(const std::string& integrator) {
    if (integrator == "photonmap") return " --spp 8 --photons 40000";
    if (integrator == "ppm" || integrator == "sppm") return " --iterations 6 --photons-per-iter 20000";
    return " --spp 16";
}

class PbrtImageLightsRender : public ::testing::Test {
protected:
    // Renders `scene` at 16 x 16 with `integrator` and returns the image.
    Image render(const std::string& scene, const std::string& integrator) {
        const std::string out = dir.file("out.pfm");
        std::filesystem::remove(out);
        const auto r = run_phos("render " + scene + " --resolution 16 16 --seed 5 --quiet --integrator " +
                                integrator + budget(integrator) + " -o " + out);
        EXPECT_EQ(r.exit_code, 0) << integrator << "\n" << r.output;
        return io::read_image(out);
    }
    static double mean(const Image& img, int x0 = 0, int y0 = 0, int x1 = 16, int y1 = 16) {
        double sum = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) sum += img.at(x, y).g;
        return sum / double((x1 - x0) * (y1 - y0));
    }
    TempDir dir;
};

// 16 x 16 map lit (L = 4) on the four pixels around the centre (light-space +z), rotated so that
// +z is world +y: the floor's irradiance is 4 x the integral of cos over those pixels (computed here
// by subdividing them), its radiance 0.5 / pi of that. With the corners lit instead (-z, below) the
// floor is black.
TEST_F(PbrtImageLightsRender, EqualAreaMapLightsTheFloorFromOverhead) {
    constexpr int n = 16;
    std::vector<Rgb> up(n * n, Rgb(0.0f)), down(n * n, Rgb(0.0f));
    for (int y = 7; y <= 8; ++y)
        for (int x = 7; x <= 8; ++x) up[size_t(y * n + x)] = Rgb(4.0f);
    for (int k : {0, n - 1, n * (n - 1), n * n - 1}) down[size_t(k)] = Rgb(4.0f);
    dir.write("up.pfm", pfm_bytes(n, n, up));
    dir.write("down.pfm", pfm_bytes(n, n, down));
    auto scene = [&](const std::string& map) {
        return dir.write(map + ".pbrt", kView + kFloor +
                                            "AttributeBegin\nRotate -90 1 0 0\nLightSource \"infinite\" "
                                            "\"string filename\" \"" +
                                            map + ".pfm\"\nAttributeEnd\n");
    };
    // E = 4 x sum over the lit pixels of cos theta x solid angle (light-space z is cos theta).
    double E = 0;
    constexpr int S = 64;
    for (int y = 7; y <= 8; ++y)
        for (int x = 7; x <= 8; ++x)
            for (int j = 0; j < S; ++j)
                for (int i = 0; i < S; ++i) {
                    const Vec3 w =
                        equal_area_square_to_sphere({(x + (i + 0.5f) / S) / n, (y + (j + 0.5f) / S) / n});
                    E += 4 * w.z * (4 * M_PI / (n * n)) / (S * S);
                }
    const double expected = 0.5 / M_PI * E;
    const std::string lit = scene("up"), dark = scene("down");
    for (const char* integrator : kIntegrators) {
        SCOPED_TRACE(integrator);
        EXPECT_NEAR(mean(render(lit, integrator)), expected, 0.05 * expected);
        EXPECT_EQ(mean(render(dark, integrator)), 0.0);
    }
}

// A constant environment L = 2 behind a 1 x 1 portal at height 2 whose sky is above (+y) lights
// the floor only through the portal: each pixel's floor point has Lambert's irradiance from the
// portal rectangle (radiance 0.5 / pi of it; the image's mean within 4 % of the pixel centres'),
// every integrator agreeing with path; turned the other way (its points in the other order) it
// leaves the floor black.
TEST_F(PbrtImageLightsRender, PortalLightsTheFloorThroughItsRectangle) {
    auto scene = [&](const std::string& name, const std::string& points) {
        return dir.write(name + ".pbrt",
                         kView + kFloor + "LightSource \"infinite\" \"rgb L\" [2 2 2] \"point3 portal\" [" +
                             points + "]\n");
    };
    // (p3 - p0) x (p1 - p0): (0, 0, 1) x (1, 0, 0) = +y for the first, -y for the second.
    const std::string up = scene("up", "0 2 0  1 2 0  1 2 1  0 2 1"),
                      down = scene("down", "0 2 0  0 2 1  1 2 1  1 2 0");
    const std::vector<Vec3> portal = {{0, 2, 0}, {1, 2, 0}, {1, 2, 1}, {0, 2, 1}};
    double expected = 0;
    const double half = 3 * std::tan(20 * M_PI / 180);
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) {
            const Vec3 x(float(half * (2 * (i + 0.5) / 16 - 1)), 0, float(half * (1 - 2 * (j + 0.5) / 16)));
            double sum = 0;
            for (size_t k = 0; k < 4; ++k) {  // Lambert: E = L / 2 |sum_k Theta_k n . Gamma_k|
                const Vec3 a = normalize(portal[k] - x), b = normalize(portal[(k + 1) % 4] - x);
                sum += std::acos(std::clamp(double(dot(a, b)), -1.0, 1.0)) * normalize(cross(a, b)).y;
            }
            expected += 0.5 / M_PI * 0.5 * 2 * std::fabs(sum) / 256;
        }
    const double path = mean(render(up, "path"));
    EXPECT_NEAR(path, expected, 0.04 * expected);
    for (const char* integrator : kIntegrators) {
        SCOPED_TRACE(integrator);
        EXPECT_NEAR(mean(render(up, integrator)), path, 0.06 * path);
    }
    for (const char* integrator : {"path", "sppm", "vcm"})
        EXPECT_EQ(mean(render(down, integrator)), 0.0) << integrator;
}

// A goniometric light 1 above the floor whose map is lit (I = 1) outside the diamond (light-space
// z < 0, which pbrt-v4's y/z swap turns to world -y): the floor is lit, every integrator agreeing
// with path; the complementary map (the diamond, world +y) leaves it black.
TEST_F(PbrtImageLightsRender, GoniometricLightsTheFloorOnlyFromItsLitHalf) {
    constexpr int n = 16;
    std::vector<Rgb> lower(n * n), upper(n * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const float u = 2 * (x + 0.5f) / n - 1, v = 2 * (y + 0.5f) / n - 1;
            const bool inside = std::fabs(u) + std::fabs(v) < 1;
            lower[size_t(y * n + x)] = Rgb(inside ? 0.0f : 1.0f);
            upper[size_t(y * n + x)] = Rgb(inside ? 1.0f : 0.0f);
        }
    dir.write("lower.pfm", pfm_bytes(n, n, lower));
    dir.write("upper.pfm", pfm_bytes(n, n, upper));
    auto scene = [&](const std::string& map) {
        return dir.write(map + ".pbrt", kView + kFloor +
                                            "Translate 0 1 0\nLightSource \"goniometric\" "
                                            "\"string filename\" \"" +
                                            map + ".pfm\"\n");
    };
    const std::string lit = scene("lower"), dark = scene("upper");
    const Image path = render(lit, "path");
    // Directly below: E = I / h^2 = 1, radiance 0.5 / pi.
    EXPECT_NEAR(mean(path, 7, 7, 9, 9), 0.5 / M_PI, 0.05 * 0.5 / M_PI);
    const double reference = mean(path);
    for (const char* integrator : kIntegrators) {
        SCOPED_TRACE(integrator);
        EXPECT_NEAR(mean(render(lit, integrator)), reference, 0.05 * reference);
        EXPECT_EQ(mean(render(dark, integrator)), 0.0);
    }
}

// A projection light 1 above the floor pointing down (Rotate 90 about x takes its +z to world -y)
// with a 60-degree white slide of scale 2: the floor below gets E = 2 / h^2 at the centre and
// nothing outside the slide's square (half-width tan 30 = 0.58 of the view's 1.09); pointing up it
// leaves the floor black.
TEST_F(PbrtImageLightsRender, ProjectionLandsOnTheFloorBelow) {
    dir.write("white.pfm", pfm_bytes(2, 2, std::vector<Rgb>(4, Rgb(1.0f))));
    auto scene = [&](float angle) {
        return dir.write("p" + std::to_string(int(angle)) + ".pbrt",
                         kView + kFloor + "Translate 0 1 0\nRotate " + std::to_string(angle) +
                             " 1 0 0\nLightSource \"projection\" \"string filename\" \"white.pfm\" "
                             "\"float fov\" 60 \"float scale\" 2\n");
    };
    const std::string down = scene(90), up = scene(-90);
    const Image path = render(down, "path");
    EXPECT_NEAR(mean(path, 7, 7, 9, 9), 2 * 0.5 / M_PI, 0.05 * 2 * 0.5 / M_PI);
    EXPECT_EQ(mean(path, 0, 0, 2, 16), 0.0);  // the view's left edge lies outside the slide
    // Compared inside the slide's square (pixels 4 to 11 of the view): ppm sees each pixel at one
    // point, so pixels the slide's edge crosses differ from the others' pixel averages.
    const double reference = mean(path, 5, 5, 11, 11);
    for (const char* integrator : kIntegrators) {
        SCOPED_TRACE(integrator);
        EXPECT_NEAR(mean(render(down, integrator), 5, 5, 11, 11), reference, 0.05 * reference);
        EXPECT_EQ(mean(render(up, integrator)), 0.0);
    }
}

// An area light with an 8 x 8 image (only its top-left quarter lit, L = 3) on a quad facing the
// camera, uv (x, z) over it: the rendered top-left quarter (world -x, +z) shows L and the other
// three quarters are dark (neither mirrored nor flipped), in every integrator.
TEST_F(PbrtImageLightsRender, AreaLightImageIsSeenTheRightWayRound) {
    std::vector<Rgb> px(64, Rgb(0.0f));
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) px[size_t(y * 8 + x)] = Rgb(3.0f);
    dir.write("emit.pfm", pfm_bytes(8, 8, px));
    const std::string scene =
        dir.write("area.pbrt", kView +
                                   "AreaLightSource \"diffuse\" \"string filename\" \"emit.pfm\"\n"
                                   "Shape \"trianglemesh\" \"point3 P\" [-1 0 -1  1 0 -1  1 0 1  -1 0 1] "
                                   "\"point2 uv\" [0 0 1 0 1 1 0 1] \"integer indices\" [0 2 1 0 3 2]\n");
    for (const char* integrator : kIntegrators) {
        SCOPED_TRACE(integrator);
        const Image img = render(scene, integrator);
        EXPECT_NEAR(mean(img, 3, 3, 7, 7), 3.0, 0.1);
        EXPECT_LT(mean(img, 9, 3, 13, 7), 0.05);   // top right
        EXPECT_LT(mean(img, 3, 9, 7, 13), 0.05);   // bottom left
        EXPECT_LT(mean(img, 9, 9, 13, 13), 0.05);  // bottom right
    }
}

// Image emission on pbrt's analytic shapes, at their pbrt (u, v) (u = phi / 2 pi from object +x):
// a 16 x 1 image red (3, 0, 0) on its left half and green on its right lies on a disk facing the
// camera (object +z turned to world +y, so object phi = atan2(-z, x)) red where phi < pi (less the
// bilinear blend of the middle pixels) and green beyond: the image's bottom right quadrant (x > 0,
// z < 0) red, its top right green. A small sphere with the same image above the floor lights the
// floor below the image's centre (z < 0, facing phi around pi / 2) red and above it green, by camera
// paths, photons and light subpaths.
TEST_F(PbrtImageLightsRender, AreaLightImageOnDiskAndSphereFollowsTheirUv) {
    std::vector<Rgb> rg(16, Rgb(3, 0, 0));
    for (int x = 8; x < 16; ++x) rg[size_t(x)] = Rgb(0, 3, 0);
    dir.write("rg.pfm", pfm_bytes(16, 1, rg));
    const std::string emitter = "AreaLightSource \"diffuse\" \"string filename\" \"rg.pfm\"\n";
    const std::string disk = dir.write("disk.pbrt", kView + "AttributeBegin\nRotate -90 1 0 0\n" + emitter +
                                                        "Shape \"disk\" \"float radius\" 2\nAttributeEnd\n");
    const std::string sphere =
        dir.write("sphere.pbrt", kView + kFloor + "AttributeBegin\nTranslate 0 0.6 0\nRotate -90 1 0 0\n" +
                                     emitter + "Shape \"sphere\" \"float radius\" 0.2\nAttributeEnd\n");
    auto channel_mean = [](const Image& img, int c, int x0, int y0, int x1, int y1) {
        double sum = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) sum += img.at(x, y)[c];
        return sum / double((x1 - x0) * (y1 - y0));
    };
    for (const char* integrator : {"path", "photonmap", "bdpt"}) {
        SCOPED_TRACE(integrator);
        const Image d = render(disk, integrator);
        EXPECT_NEAR(channel_mean(d, 0, 10, 10, 14, 14), 3.0, 0.3);  // bottom right: red
        EXPECT_LT(channel_mean(d, 1, 10, 10, 14, 14), 0.2);
        EXPECT_NEAR(channel_mean(d, 1, 10, 2, 14, 6), 3.0, 0.3);  // top right: green
        EXPECT_LT(channel_mean(d, 0, 10, 2, 14, 6), 0.2);
        const Image s = render(sphere, integrator);
        const double br_r = channel_mean(s, 0, 6, 12, 10, 16), br_g = channel_mean(s, 1, 6, 12, 10, 16);
        const double tr_r = channel_mean(s, 0, 6, 0, 10, 4), tr_g = channel_mean(s, 1, 6, 0, 10, 4);
        EXPECT_GT(br_r, 3 * br_g) << br_r << " " << br_g;
        EXPECT_GT(tr_g, 3 * tr_r) << tr_r << " " << tr_g;
        EXPECT_GT(br_r, 0.002);
    }
}

}  // namespace
}  // namespace phos::testing
