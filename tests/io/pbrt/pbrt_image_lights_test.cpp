// pbrt image-driven lights as scene data: a square infinite map is an equal-area map (with pbrt-v4's
// "illuminance" normalisation), goniometric and projection lights carry their image, pbrt-v4's
// light-space conventions (goniometric's y/z swap, projection's y flip) and their "power"; bad
// input is a located error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/equal_area.h"
#include "pbrt_test_util.h"

namespace phos::io::test {
namespace {

using scene::Light;

scene::Scene load_in(PbrtTempDir& dir, const std::string& body) {
    QuietLog quiet;
    return load_pbrt(dir.write("scene.pbrt", "WorldBegin\n" + body));
}

TEST(PbrtImageLights, SquareInfiniteMapIsEqualAreaWithIlluminance) {
    PbrtTempDir dir;
    constexpr int n = 8;
    std::vector<Rgb> px(n * n, Rgb(0.5f));
    px[3] = Rgb(4, 2, 1);
    dir.write("sky.pfm", phos::testing::pfm_bytes(n, n, px));
    dir.write("wide.pfm", phos::testing::pfm_bytes(4, 2, std::vector<Rgb>(8, Rgb(1.0f))));
    const scene::Scene s =
        load_in(dir,
                "LightSource \"infinite\" \"string filename\" \"sky.pfm\" \"float scale\" 2\n"
                "LightSource \"infinite\" \"string filename\" \"sky.pfm\" \"float illuminance\" 10\n"
                "LightSource \"infinite\" \"string filename\" \"wide.pfm\"\n");
    ASSERT_EQ(s.lights.size(), 3u);
    const Light& a = s.lights[0];
    EXPECT_EQ(a.kind, Light::Kind::Infinite);
    EXPECT_TRUE(a.equal_area);
    ASSERT_GE(a.texture, 0);
    EXPECT_EQ(s.textures[size_t(a.texture)].image->width, n);
    EXPECT_EQ(s.textures[size_t(a.texture)].image->at(3, 0), Rgb(4, 2, 1));  // row 0 is the top
    EXPECT_EQ(a.color, Rgb(2.0f));
    // pbrt-v4's normalisation: 2 pi / N^2 times the sum of luminance x cos over the pixel centres
    // of the upper hemisphere, computed here independently.
    double k = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const Vec3 w = equal_area_square_to_sphere({(x + 0.5f) / n, (y + 0.5f) / n});
            if (w.z > 0) k += double(px[size_t(y * n + x)].luminance()) * w.z;
        }
    k *= 2 * M_PI / (n * n);
    EXPECT_NEAR(s.lights[1].color.g, 10 / k, 1e-4 * 10 / k);
    EXPECT_FALSE(s.lights[2].equal_area);  // a non-square map stays a lat-long map
}

// Goniometric: "I" x "scale", "power" = 4 pi I mean(grey map); pbrt-v4 swaps y and z, so the map's
// centre (light-space +z) looks along world +y under the identity.
TEST(PbrtImageLights, GoniometricConventions) {
    PbrtTempDir dir;
    constexpr int n = 4;
    std::vector<Rgb> px(n * n, Rgb(0.0f));
    for (int y = 1; y <= 2; ++y)
        for (int x = 1; x <= 2; ++x) px[size_t(y * n + x)] = Rgb(3, 6, 0);  // grey 3
    dir.write("g.pfm", phos::testing::pfm_bytes(n, n, px));
    const scene::Scene s = load_in(
        dir,
        "Translate 1 2 3\nLightSource \"goniometric\" \"string filename\" \"g.pfm\" \"rgb I\" [1 2 3] "
        "\"float scale\" 2\n"
        "LightSource \"goniometric\" \"string filename\" \"g.pfm\" \"float power\" 100\n");
    ASSERT_EQ(s.lights.size(), 2u);
    const Light& g = s.lights[0];
    EXPECT_EQ(g.kind, Light::Kind::Goniometric);
    EXPECT_EQ(g.color, Rgb(2, 4, 6));
    EXPECT_NEAR(g.position.y, 2.0f, 1e-6f);
    const Vec3 up = g.to_world.vector({0, 0, 1});  // light-space +z: the map's centre
    EXPECT_NEAR(up.y, 1.0f, 1e-6f);
    // power: 4 pi I mean(grey) = 100 with mean(grey) = 3 x 4 / 16.
    EXPECT_NEAR(s.lights[1].color.g * 4 * M_PI * 3 * 4 / 16, 100.0, 1e-3);
}

// Projection: "fov", "scale", "power" normalised by the image's luminance flux; pbrt-v4 flips y so
// the top row of the slide lands on +y in the light's space.
TEST(PbrtImageLights, ProjectionConventions) {
    PbrtTempDir dir;
    dir.write("slide.pfm", phos::testing::pfm_bytes(2, 2, {Rgb(1.0f), Rgb(1.0f), Rgb(1.0f), Rgb(1.0f)}));
    const scene::Scene s =
        load_in(dir,
                "LightSource \"projection\" \"string filename\" \"slide.pfm\" \"float fov\" "
                "40 \"float scale\" 3\n"
                "LightSource \"projection\" \"string filename\" \"slide.pfm\" \"float power\" "
                "50\n");
    ASSERT_EQ(s.lights.size(), 2u);
    const Light& p = s.lights[0];
    EXPECT_EQ(p.kind, Light::Kind::Projection);
    EXPECT_NEAR(p.fov, 40 * kPi / 180, 1e-6f);
    EXPECT_EQ(p.color, Rgb(3.0f));
    EXPECT_NEAR(p.to_world.vector({0, 1, 0}).y, -1.0f, 1e-6f);  // the flip
    // A white 90-degree square slide: flux = integral over the window of cos^3 dA, midpoint rule
    // over the four pixels (each centre at (+-0.5, +-0.5) on the plane z = 1): 4 x cos^3 x 1.
    const double c = 1 / std::sqrt(1.5);
    EXPECT_NEAR(s.lights[1].color.g * 4 * c * c * c, 50.0, 1e-3);
}

// AreaLightSource "diffuse" with "filename": the mesh's light carries the image, L = scale, and
// "power" is normalised by the image's mean luminance; a sphere carries the image too (read at its
// (u, v)); "L" and "filename" together are an error.
TEST(PbrtImageLights, AreaLightImage) {
    PbrtTempDir dir;
    dir.write("e.pfm", phos::testing::pfm_bytes(2, 1, {Rgb(1, 2, 3), Rgb(3, 2, 1)}));
    const std::string quad =
        "Shape \"trianglemesh\" \"point3 P\" [0 0 0 2 0 0 2 2 0 0 2 0] \"integer indices\" [0 1 2 0 2 3]\n";
    const scene::Scene s = load_in(
        dir, "AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"e.pfm\" \"float scale\" 2\n" +
                 quad +
                 "AttributeEnd\nAttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"e.pfm\" "
                 "\"float power\" 10\n" +
                 quad + "Shape \"sphere\"\nAttributeEnd\n");
    ASSERT_EQ(s.lights.size(), 3u);
    const Light& a = s.lights[0];
    EXPECT_EQ(a.kind, Light::Kind::Area);
    ASSERT_GE(a.texture, 0);
    EXPECT_EQ(s.textures[size_t(a.texture)].image->width, 2);
    EXPECT_EQ(a.color, Rgb(2.0f));
    // power: pi A L mean-luminance = 10 with A = 4 and the mean (2, 2, 2) of luminance 2.
    EXPECT_NEAR(s.lights[1].color.g * kPi * 4 * 2, 10.0f, 1e-4f);
    EXPECT_EQ(s.lights[2].texture, s.lights[1].texture);  // the sphere: the image
    const float k = 10.0f / (kPi * 4 * kPi * 2);          // the power normalisation on the unit sphere's area
    EXPECT_NEAR(s.lights[2].color.g, k, 1e-4f);
    QuietLog quiet;
    expect_pbrt_error(dir.write("both.pbrt",
                                "WorldBegin\nAreaLightSource \"diffuse\" \"string filename\" "
                                "\"e.pfm\" \"rgb L\" [1 1 1]\n" +
                                    quad),
                      2, 1, "either \"L\" or \"filename\"");
}

// "portal": four world-space points of a rectangle (with any map or a constant L), kept as given
// whatever the current transform. A non-rectangle is a located error.
TEST(PbrtImageLights, Portal) {
    PbrtTempDir dir;
    dir.write("sky.pfm", phos::testing::pfm_bytes(4, 4, std::vector<Rgb>(16, Rgb(1.0f))));
    dir.write("wide.pfm", phos::testing::pfm_bytes(4, 2, std::vector<Rgb>(8, Rgb(1.0f))));
    const scene::Scene s =
        load_in(dir,
                "Rotate 30 0 1 0\nLightSource \"infinite\" \"string filename\" \"sky.pfm\" "
                "\"point3 portal\" [0 0 0  0 1 0  1 1 0  1 0 0]\n"
                "LightSource \"infinite\" \"rgb L\" [1 1 1] \"point3 portal\" [0 0 0  0 1 0  1 1 0  1 0 0]\n"
                "LightSource \"infinite\" \"string filename\" \"wide.pfm\" \"point3 portal\" [0 0 0  0 1 0  "
                "1 1 0  1 0 0]\n");
    ASSERT_EQ(s.lights.size(), 3u);
    const std::vector<Vec3> corners = {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
    for (const scene::Light& l : s.lights) EXPECT_EQ(l.portal, corners);
    QuietLog quiet;
    expect_pbrt_error(dir.write("skew.pbrt",
                                "WorldBegin\nLightSource \"infinite\" \"point3 portal\" "
                                "[0 0 0  0 1 0  1 1.5 0  1 0 0]\n"),
                      2, 24, "not parallel");
    expect_pbrt_error(dir.write("three.pbrt",
                                "WorldBegin\nLightSource \"infinite\" \"point3 portal\" "
                                "[0 0 0  0 1 0  1 1 0]\n"),
                      2, 24, "four points");
}

// pbrt-v3's goniometric "mapname" is a lat-long map in the light's y/z-swapped space: s = phi / 2 pi,
// t = theta / pi of wp = (x, z, y) (pbrt-v3's GonioPhotometricLight::Scale). A 32 x 16 map lit only in
// its top-left quarter (theta < pi/2, phi in [0, pi/2): light-space x > 0, z > 0, y > 0) becomes an
// equal-area map that pbrt-v4's swapped lookup finds bright towards (1, 1, 1) and dark towards the
// directions that differ from it in one sign.
TEST(PbrtImageLights, GoniometricV3LatLongMapKeepsItsOrientation) {
    PbrtTempDir dir;
    std::vector<Rgb> px(32 * 16, Rgb(0.25f));
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) px[size_t(y * 32 + x)] = Rgb(4.0f);
    dir.write("gonio.pfm", phos::testing::pfm_bytes(32, 16, px));
    const scene::Scene s = load_in(dir, "LightSource \"goniometric\" \"string mapname\" \"gonio.pfm\"\n");
    ASSERT_EQ(s.lights.size(), 1u);
    const scene::Light& l = s.lights[0];
    ASSERT_GE(l.texture, 0);
    const scene::TextureImage& map = *s.textures[size_t(l.texture)].image;
    ASSERT_EQ(map.width, map.height);
    auto profile = [&](Vec3 world) {
        const Vec3 local = normalize(l.to_world.inverse().vector(world));
        const Vec2 uv = equal_area_sphere_to_square(local);
        const int n = map.width;
        return map.at(std::min(int(uv.x * float(n)), n - 1), std::min(int(uv.y * float(n)), n - 1)).g;
    };
    EXPECT_NEAR(profile({1, 1, 1}), 4.0f, 1e-4f);
    for (const Vec3 w : {Vec3(-1, 1, 1), Vec3(1, -1, 1), Vec3(1, 1, -1), Vec3(-1, -1, -1)})
        EXPECT_NEAR(profile(w), 0.25f, 1e-4f) << w.x << " " << w.y << " " << w.z;
}

TEST(PbrtImageLights, BadInputIsLocated) {
    PbrtTempDir dir;
    QuietLog quiet;
    dir.write("wide.pfm", phos::testing::pfm_bytes(4, 2, std::vector<Rgb>(8, Rgb(1.0f))));
    expect_pbrt_error(dir.write("a.pbrt", "WorldBegin\nLightSource \"goniometric\"\n"), 2, 1,
                      "missing \"string filename\"");
    expect_pbrt_error(
        dir.write("b.pbrt", "WorldBegin\nLightSource \"goniometric\" \"string filename\" \"wide.pfm\"\n"), 2,
        27, "square");
    expect_pbrt_error(dir.write("c.pbrt",
                                "WorldBegin\nLightSource \"projection\" \"string filename\" \"wide.pfm\" "
                                "\"float fov\" 180\n"),
                      2, 55, "fov");
    expect_pbrt_error(
        dir.write("d.pbrt", "WorldBegin\nLightSource \"projection\" \"string filename\" \"no.pfm\"\n"), 2, 26,
        "cannot read");
}

}  // namespace
}  // namespace phos::io::test
