// A hit on a shape whose material is pbrt's mix reports one of the mixed materials, fixed by the
// point (the packet path agrees with the single-ray path) (scene/material_mix.h resolved in EmbreeScene).
#include <gtest/gtest.h>

#include "accel/embree_scene.h"
#include "core/rng.h"
#include "support/shapes.h"

namespace phos::testing {
namespace {

TEST(MixMaterialHits, HitsReportAMixedMaterialFixedByThePoint) {
    scene::Scene sc;
    sc.materials.resize(3);
    sc.materials[2].mix_a = 0;
    sc.materials[2].mix_b = 1;
    sc.materials[2].mix_amount = 0.4f;
    sc.shapes.push_back(sphere({0, 0, 0}, 1, 2));
    const accel::EmbreeScene es(sc);
    Sampler rng(4);
    int second = 0;
    const int n = 4000;
    for (int i = 0; i < n; i += 16) {
        Ray rays[16];
        for (Ray& r : rays) r = Ray{{0.8f * (rng.next() - 0.5f), 0.8f * (rng.next() - 0.5f), 5}, {0, 0, -1}};
        accel::SurfaceHit packet[16];
        bool found[16];
        es.intersect16(rays, 16, packet, found);
        for (int k = 0; k < 16; ++k) {
            accel::SurfaceHit h;
            ASSERT_TRUE(es.intersect(rays[k], h));
            ASSERT_TRUE(h.material == 0 || h.material == 1);
            second += h.material == 1;
            // The packet path resolves the mix as the single-ray path does.
            ASSERT_TRUE(found[k]);
            EXPECT_EQ(packet[k].material, h.material);
        }
    }
    EXPECT_NEAR(double(second) / n, 0.4, 5 * std::sqrt(0.4 * 0.6 / n));
}

}  // namespace
}  // namespace phos::testing
