// Alpha cut-outs (scene::Shape::alpha, accel/alpha_mask.h): an image alpha texture on a quad lets
// rays through exactly where its texels are 0, in intersect, occluded and intersect16 alike; a
// constant alpha keeps the expected fraction of distinct rays (binomial bounds) and the same ray
// always decides the same way; every shape kind (triangles, analytic shapes, bilinear patches,
// curves, instances) obeys alpha 0 and fractional alpha, and a sphere's two hits decide
// independently.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "accel/alpha_mask.h"
#include "accel/embree_scene.h"
#include "accel/scene_builders.h"

namespace phos::testing {
namespace {

using scene::Shape;

// The unit quad [0, 1]^2 at height z facing +z, uv = (x, y).
Shape unit_quad(float z) {
    Shape s = quad({0, 0, z}, {1, 0, z}, {1, 1, z}, {0, 1, z});
    s.mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    return s;
}

// A 4 x 4 checkerboard of alphas 0 and 1 (cell (x, y), row 0 at the top, is 1 when x + y is
// even) as an 8 x 8 image texture, each cell 2 x 2 texels, clamped at the edges: within 1/16 of a
// cell's centre the bilinear lookup reads only that cell's texels, so alpha there is exactly 0 or 1.
int add_checker_alpha(scene::Scene& sc) {
    auto img = std::make_shared<scene::TextureImage>();
    img->width = img->height = 8;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) img->texels.push_back(Rgb((x / 2 + y / 2) % 2 == 0 ? 1.0f : 0.0f));
    scene::Texture t;
    t.kind = scene::Texture::Kind::Image;
    t.image = img;
    t.wrap = scene::Texture::Wrap::Clamp;
    sc.textures.push_back(t);
    return int(sc.textures.size()) - 1;
}

// The masked quad at z = 0 above an opaque quad at z = -1 (what a ray through a hole hits).
scene::Scene checker_scene() {
    scene::Scene sc;
    Shape masked = unit_quad(0);
    masked.alpha_texture = add_checker_alpha(sc);
    sc.shapes.push_back(masked);
    sc.shapes.push_back(quad({-1, -1, -1}, {2, -1, -1}, {2, 2, -1}, {-1, 2, -1}));
    return sc;
}

TEST(Alpha, ImageTextureHolesPassRaysInEveryQuery) {
    const scene::Scene sc = checker_scene();
    const accel::EmbreeScene es(sc);
    std::vector<Ray> rays;
    std::vector<bool> opaque;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            for (float dx : {-0.3f, 0.0f, 0.3f}) {
                // Through cell (x, y) within 0.045 of its centre, from directions that differ.
                const float u = (float(x) + 0.5f) / 4 + 0.15f * dx, v = 1 - (float(y) + 0.5f) / 4 - 0.1f * dx;
                const Vec3 dir(0.2f * dx, -0.1f * dx, -1);
                rays.push_back({Vec3(u, v, 0) - dir, dir});
                opaque.push_back((x + y) % 2 == 0);
            }
    for (size_t i = 0; i < rays.size(); ++i) {
        accel::SurfaceHit h;
        ASSERT_TRUE(es.intersect(rays[i], h)) << i;
        EXPECT_EQ(h.shape, opaque[i] ? 0 : 1) << i;
        // Stopping at the masked plane: occluded only when the texel is opaque.
        Ray shadow = rays[i];
        shadow.tmax = 1.5f;
        EXPECT_EQ(es.occluded(shadow), opaque[i]) << i;
        shadow.tmax = 3;
        EXPECT_TRUE(es.occluded(shadow)) << i;  // the floor
    }
    // Packets give the same hits, lane by lane.
    for (size_t first = 0; first < rays.size(); first += 16) {
        const int n = int(std::min<size_t>(16, rays.size() - first));
        accel::SurfaceHit hits[16];
        bool found[16];
        es.intersect16(rays.data() + first, n, hits, found);
        for (int k = 0; k < n; ++k) {
            accel::SurfaceHit h;
            ASSERT_TRUE(es.intersect(rays[first + size_t(k)], h));
            ASSERT_TRUE(found[k]);
            EXPECT_EQ(hits[k].shape, h.shape);
            EXPECT_EQ(hits[k].t, h.t);
        }
    }
}

// The fraction of `n` distinct rays that hit something, for rays made by `ray(i)`; also checks
// that each ray decides the same way again and in occluded() and intersect16.
double hit_fraction(const accel::EmbreeScene& es, int n, const std::function<Ray(int)>& ray) {
    int hits = 0;
    for (int first = 0; first < n; first += 16) {
        Ray rays[16];
        const int m = std::min(16, n - first);
        for (int k = 0; k < m; ++k) rays[k] = ray(first + k);
        accel::SurfaceHit packet[16];
        bool found[16];
        es.intersect16(rays, m, packet, found);
        for (int k = 0; k < m; ++k) {
            accel::SurfaceHit h, again;
            const bool hit = es.intersect(rays[k], h);
            EXPECT_EQ(hit, es.intersect(rays[k], again));
            EXPECT_EQ(hit, es.occluded(rays[k]));
            EXPECT_EQ(hit, found[k]);
            if (hit && found[k]) {
                EXPECT_EQ(h.t, packet[k].t);
            }
            hits += hit;
        }
    }
    return double(hits) / n;
}

// |fraction - p| within 4 binomial standard deviations over n rays (a fixed-seed check: the
// rays are the same every run).
void expect_binomial(double fraction, double p, int n, const char* what) {
    const double sigma = std::sqrt(p * (1 - p) / n);
    EXPECT_NEAR(fraction, p, 4 * sigma) << what;
}

TEST(Alpha, ConstantAlphaKeepsThatFractionOfDistinctRays) {
    scene::Scene sc;
    Shape s = unit_quad(0);
    s.alpha = 0.3f;
    sc.shapes.push_back(s);
    const accel::EmbreeScene es(sc);
    const int n = 20000;
    Sampler rng(7);
    std::vector<Ray> rays(static_cast<size_t>(n));
    for (Ray& r : rays) r = {{0.1f + 0.8f * rng.next(), 0.1f + 0.8f * rng.next(), 1}, {0, 0, -1}};
    const double f = hit_fraction(es, n, [&](int i) { return rays[size_t(i)]; });
    expect_binomial(f, 0.3, n, "alpha 0.3");
    // The hash itself is uniform: its mean over the same rays is 1/2 (variance 1/12).
    double mean = 0;
    for (const Ray& r : rays) mean += accel::alpha_hash(r.origin, r.dir, 0);
    EXPECT_NEAR(mean / n, 0.5, 4 * std::sqrt(1.0 / 12 / n));
}

// Each shape kind with alpha 0 (nothing hit), alpha 1 (all hit) and alpha 0.3.
TEST(Alpha, EveryShapeKindObeysItsAlpha) {
    Shape patch;
    patch.kind = Shape::Kind::Mesh;
    patch.mesh.positions = {{-1, -1, 0.2f}, {1, -1, -0.2f}, {-1, 1, -0.2f}, {1, 1, 0.3f}};
    patch.mesh.patches = {0, 1, 2, 3};
    Shape curve;
    curve.kind = Shape::Kind::Curves;
    curve.curves.type = scene::CurveSet::Type::Flat;
    for (int k = 0; k < 4; ++k) {
        curve.curves.points.push_back({-1.0f + 2.0f * float(k) / 3.0f, 0, 0});
        curve.curves.radii.push_back(0.5f);
    }
    curve.curves.segments = {0};
    // Shapes straddling the z axis around the origin; rays go down -z through x, y in [-0.3, 0.3].
    const std::pair<const char*, Shape> shapes[] = {
        {"triangles", quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0})},
        {"box", box({-1, -1, -0.5f}, {1, 1, 0.5f})},
        {"disk", disk({0, 0, 0}, {0, 0, 1}, 1)},
        {"cylinder", cylinder({0, 0, 0}, {0, 1, 0}, 1, 2, false)},
        {"bilinear patch", patch},
        {"curve", curve},
    };
    for (const auto& [name, shape] : shapes) {
        for (float alpha : {0.0f, 1.0f, 0.3f}) {
            scene::Scene sc;
            Shape s = shape;
            s.alpha = alpha;
            sc.shapes.push_back(s);
            const accel::EmbreeScene es(sc);
            const int n = alpha == 0.3f ? 4000 : 200;
            Sampler rng(11);
            std::vector<Ray> rays(static_cast<size_t>(n));
            for (Ray& r : rays) r = {{0.6f * rng.next() - 0.3f, 0.6f * rng.next() - 0.3f, 5}, {0, 0, -1}};
            const double f = hit_fraction(es, n, [&](int i) { return rays[size_t(i)]; });
            // Closed shapes are crossed twice, each crossing kept independently: 1 - (1 - a)^2.
            const bool twice = std::string(name) == "box" || std::string(name) == "cylinder";
            const double p = twice ? 1 - (1 - alpha) * (1 - alpha) : alpha;
            if (alpha == 0.3f) {
                expect_binomial(f, p, n, name);
            } else {
                EXPECT_EQ(f, alpha) << name;
            }
        }
    }
}

TEST(Alpha, SphereEntryAndExitDecideIndependently) {
    scene::Scene sc;
    Shape s = sphere({0, 0, 0}, 1);
    s.alpha = 0.3f;
    sc.shapes.push_back(s);
    const accel::EmbreeScene es(sc);
    const int n = 6000;
    Sampler rng(3);
    int hits = 0, front = 0;
    for (int i = 0; i < n; ++i) {
        const Ray r{{0.4f * rng.next() - 0.2f, 0.4f * rng.next() - 0.2f, 5}, {0, 0, -1}};
        accel::SurfaceHit h;
        if (!es.intersect(r, h)) continue;
        ++hits;
        front += h.p.z > 0;
    }
    expect_binomial(double(hits) / n, 0.51, n, "hit");
    expect_binomial(double(front) / n, 0.3, n, "entry hit");
}

TEST(Alpha, InstancedMaskAndTextureOnAnObject) {
    scene::Scene sc = checker_scene();
    // The same masked quad as an object placed twice, 2 and 4 units along x.
    scene::Object obj;
    obj.shapes.push_back(sc.shapes[0]);
    sc.objects.push_back(obj);
    sc.instances.push_back({0, Transform::translate({2, 0, 0})});
    sc.instances.push_back({0, Transform::translate({4, 0, 0})});
    const accel::EmbreeScene es(sc);
    for (float ox : {2.0f, 4.0f})
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) {
                const Ray r{{ox + (float(x) + 0.5f) / 4, 1 - (float(y) + 0.5f) / 4, 1}, {0, 0, -1}};
                accel::SurfaceHit h;
                const bool hit = es.intersect(r, h);
                EXPECT_EQ(hit, (x + y) % 2 == 0) << ox << " " << x << " " << y;
                Ray shadow = r;
                shadow.tmax = 1.5f;
                EXPECT_EQ(es.occluded(shadow), hit);
            }
}

}  // namespace
}  // namespace phos::testing
