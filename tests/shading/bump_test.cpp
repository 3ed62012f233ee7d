// Bump and normal mapping (shading/bump.h) against closed forms: a plane with a linear-ramp
// displacement tilts the shading normal to the normal of the displaced plane; a normal map of
// (0.5, 0.5, 1) leaves the normal as it is and one of a known tilt gives that tilt about dpdu; the
// perturbed normal is always on the geometric normal's side, even for normals mapped backwards.
#include "shading/bump.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "accel/embree_scene.h"
#include "core/rng.h"
#include "support/shapes.h"

namespace phos::testing {
namespace {

using scene::Shape;

// The 4 x 2 rectangle [0, 4] x [0, 2] at z = 0 facing +z, uv over it: dpdu = (4, 0, 0),
// dpdv = (0, 2, 0).
Shape rectangle() {
    Shape s = quad({0, 0, 0}, {4, 0, 0}, {4, 2, 0}, {0, 2, 0});
    s.mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    return s;
}

// A 2 x 2 clamped image texture holding d(u, v) = a u + b v at its texel centres: the bilinear
// lookup is that linear function exactly for u, v in [0.25, 0.75].
int add_ramp(scene::Scene& sc, float a, float b) {
    auto img = std::make_shared<scene::TextureImage>();
    img->width = img->height = 2;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) {
            const float u = (float(x) + 0.5f) / 2, v = 1 - (float(y) + 0.5f) / 2;
            img->texels.push_back(Rgb(a * u + b * v));
        }
    scene::Texture t;
    t.kind = scene::Texture::Kind::Image;
    t.image = img;
    t.wrap = scene::Texture::Wrap::Clamp;
    sc.textures.push_back(t);
    return int(sc.textures.size()) - 1;
}

// A one-texel normal map holding `rgb`.
std::shared_ptr<const scene::TextureImage> constant_map(Rgb rgb) {
    auto img = std::make_shared<scene::TextureImage>();
    img->width = img->height = 1;
    img->texels = {rgb};
    return img;
}

accel::SurfaceHit hit_at(const scene::Scene& sc, Vec3 origin, Vec3 dir) {
    const accel::EmbreeScene es(sc);
    accel::SurfaceHit h;
    EXPECT_TRUE(es.intersect({origin, dir}, h));
    return h;
}

void expect_vec(Vec3 a, Vec3 b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Bump, LinearRampTiltsThePlaneNormalByTheClosedForm) {
    for (const auto& [a, b] : {std::pair{1.0f, 0.0f}, {0.0f, 0.5f}, {1.0f, 0.5f}, {-3.0f, 2.0f}}) {
        scene::Scene sc;
        sc.shapes.push_back(rectangle());
        scene::Material m;
        m.displacement_texture = add_ramp(sc, a, b);
        sc.materials.push_back(m);
        const accel::SurfaceHit h = hit_at(sc, {2.1f, 0.9f, 1}, {0, 0, -1});
        const accel::SurfaceHit bumped = shading::with_shading_detail(sc, m, h);
        // The displaced plane p + (a u + b v) n: dp/du = (4, 0, a), dp/dv = (0, 2, b), normal
        // (4, 0, a) x (0, 2, b) = (-2a, -4b, 8).
        const Vec3 expected = normalize(Vec3(-2 * a, -4 * b, 8));
        expect_vec(bumped.ns, expected, 1e-3f);
        // The tilt from the plane's normal: cos = 8 / |(-2a, -4b, 8)|.
        EXPECT_NEAR(std::acos(std::min(1.0f, dot(bumped.ns, h.ns))),
                    std::acos(8 / std::sqrt(4 * a * a + 16 * b * b + 64)), 1e-3);
        EXPECT_EQ(bumped.ng.z, h.ng.z);  // the geometric normal stays
        EXPECT_NEAR(dot(bumped.dpdu, bumped.ns), 0, 1e-5f);
        EXPECT_EQ(bumped.shading, nullptr);
    }
}

TEST(Bump, ReversedPlaneBumpsTheOtherWay) {
    // The same plane facing -z (reverse orientation): the displacement goes along -z, so the
    // surface rises towards -z where d grows, and the normal (turned to ng = -z) tilts to +x.
    scene::Scene sc;
    Shape s = rectangle();
    s.reverse_orientation = true;
    sc.shapes.push_back(s);
    scene::Material m;
    m.displacement_texture = add_ramp(sc, 1, 0);
    const accel::SurfaceHit h = hit_at(sc, {2.1f, 0.9f, 1}, {0, 0, -1});
    ASSERT_LT(h.ng.z, 0);
    const accel::SurfaceHit bumped = shading::with_shading_detail(sc, m, h);
    // p - d z: dp/du = (4, 0, -1), normal on -z's side: -(4, 0, -1) x (0, 2, 0) / |...| = -(2, 0, 8).
    expect_vec(bumped.ns, normalize(Vec3(-2, 0, -8)), 1e-3f);
}

TEST(NormalMap, FlatMapKeepsTheNormalAndATiltedMapTiltsAboutDpdu) {
    scene::Scene sc;
    sc.shapes.push_back(rectangle());
    const accel::SurfaceHit h = hit_at(sc, {2.1f, 0.9f, 1}, {0, 0, -1});
    scene::Material flat;
    flat.normal_map = constant_map(Rgb(0.5f, 0.5f, 1));
    const accel::SurfaceHit same = shading::with_shading_detail(sc, flat, h);
    expect_vec(same.ns, h.ns, 1e-6f);
    expect_vec(same.dpdu, h.dpdu, 1e-6f);
    // Tangent-space (sin t, 0, cos t) in the frame (dpdu, ns x dpdu, ns) = (+x, +y, +z).
    for (float t : {0.3f, -0.7f, 1.2f}) {
        scene::Material tilted;
        tilted.normal_map = constant_map(Rgb(0.5f + 0.5f * std::sin(t), 0.5f, 0.5f + 0.5f * std::cos(t)));
        const accel::SurfaceHit n = shading::with_shading_detail(sc, tilted, h);
        expect_vec(n.ns, {std::sin(t), 0, std::cos(t)}, 1e-5f);
        EXPECT_NEAR(dot(n.dpdu, n.ns), 0, 1e-5f);
    }
    // A tilt across: (0, sin t, cos t) tilts towards ns x dpdu = +y.
    scene::Material across;
    across.normal_map = constant_map(Rgb(0.5f, 0.5f + 0.5f * std::sin(0.4f), 0.5f + 0.5f * std::cos(0.4f)));
    expect_vec(shading::with_shading_detail(sc, across, h).ns, {0, std::sin(0.4f), std::cos(0.4f)}, 1e-5f);
    // The normal map takes precedence over a displacement texture, as in pbrt-v4.
    scene::Material both = flat;
    both.displacement_texture = add_ramp(sc, 5, 5);
    expect_vec(shading::with_shading_detail(sc, both, h).ns, h.ns, 1e-6f);
}

TEST(ShadingDetail, PerturbedNormalIsAlwaysOnTheGeometricSide) {
    // A sphere (and its inside) under steep random bumps and backwards normal maps.
    scene::Scene sc;
    sc.shapes.push_back(sphere({0, 0, 0}, 1));
    auto noise = std::make_shared<scene::TextureImage>();
    noise->width = noise->height = 16;
    Sampler rng(5);
    for (int i = 0; i < 256; ++i) noise->texels.push_back(Rgb(20 * rng.next()));
    scene::Texture t;
    t.kind = scene::Texture::Kind::Image;
    t.image = noise;
    sc.textures.push_back(t);
    scene::Material bumpy;
    bumpy.displacement_texture = 0;
    scene::Material backwards;
    backwards.normal_map = constant_map(Rgb(0.9f, 0.2f, 0.0f));  // tangent-space z < 0
    const accel::EmbreeScene es(sc);
    int perturbed = 0;
    for (int i = 0; i < 500; ++i) {
        const Vec3 o = i % 2 ? Vec3(0.0f) : Vec3(3 * (rng.next() - 0.5f), 3 * (rng.next() - 0.5f), 4);
        const Vec3 d =
            i % 2 ? normalize(Vec3(rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f)) : Vec3(0, 0, -1);
        accel::SurfaceHit h;
        if (!es.intersect({o, d}, h)) continue;
        for (const scene::Material* m : {&bumpy, &backwards}) {
            const accel::SurfaceHit b = shading::with_shading_detail(sc, *m, h);
            EXPECT_GE(dot(b.ns, b.ng), 0) << i;
            EXPECT_NEAR(length(b.ns), 1, 1e-5f);
            perturbed += dot(b.ns, h.ns) < 0.999f;
        }
    }
    EXPECT_GT(perturbed, 400);  // the bumps did tilt most normals
}

TEST(ShadingDetail, MaterialsWithoutDetailKeepTheHit) {
    scene::Scene sc;
    sc.shapes.push_back(rectangle());
    const accel::EmbreeScene es(sc);
    accel::SurfaceHit h;
    ASSERT_TRUE(es.intersect({{2.1f, 0.9f, 1}, {0, 0, -1}}, h));
    const scene::Material plain;
    EXPECT_FALSE(shading::has_shading_detail(plain));
    const accel::SurfaceHit same = shading::with_shading_detail(sc, plain, h);
    EXPECT_EQ(same.ns.z, h.ns.z);
    EXPECT_EQ(same.shading, h.shading);  // the accelerator's frame is kept
}

}  // namespace
}  // namespace phos::testing
