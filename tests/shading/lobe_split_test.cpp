// Tests of Bsdf::split_lobes (delta lobes followed by ray tracing vs the rest, and the probability
// of the non-delta part) and Bsdf::is_lambertian.
#include <gtest/gtest.h>

#include "shading/bsdf.h"

namespace phos::shading {
namespace {

using scene::Material;

const scene::Scene& empty_scene() {
    static const scene::Scene s;
    return s;
}

Bsdf make(const Material& m, Vec3 ns = {0, 0, 1}) {
    accel::SurfaceHit h;
    h.ng = {0, 0, 1};
    h.ns = normalize(ns);
    h.dpdu = {1, 0, 0};
    return Bsdf(m, h, empty_scene());
}

Material with(Rgb kd, Rgb ks, float n, Rgb kt, float t_n = 1e6f) {
    Material m;
    m.diffuse = kd;
    m.specular = ks;
    m.shininess = n;
    m.transmission = kt;
    m.ior = 1.5f;
    m.transmission_shininess = t_n;
    return m;
}

const Vec3 kUp = normalize(Vec3(0.3f, 0.1f, 1.0f));
constexpr float kMirror = Material::kMirrorShininess;

TEST(LobeSplit, PureMaterials) {
    const Bsdf::LobeSplit lambert = make(with(Rgb(0.5f), Rgb(0.0f), 0, Rgb(0.0f))).split_lobes(kUp);
    EXPECT_EQ(lambert.delta, 0u);
    EXPECT_EQ(lambert.non_delta, uint32_t(kDiffuse));
    EXPECT_EQ(lambert.p_non_delta, 1.0f);

    const Bsdf::LobeSplit mirror = make(with(Rgb(0.0f), Rgb(0.9f), kMirror, Rgb(0.0f))).split_lobes(kUp);
    EXPECT_EQ(mirror.delta, uint32_t(kSpecular));
    EXPECT_EQ(mirror.non_delta, 0u);
    EXPECT_EQ(mirror.p_non_delta, 0.0f);

    const Bsdf::LobeSplit phong = make(with(Rgb(0.0f), Rgb(0.9f), 20, Rgb(0.0f))).split_lobes(kUp);
    EXPECT_EQ(phong.delta, 0u);
    EXPECT_EQ(phong.non_delta, uint32_t(kGlossy));
    EXPECT_EQ(phong.p_non_delta, 1.0f);

    const Bsdf::LobeSplit glass = make(with(Rgb(0.0f), Rgb(0.0f), 0, Rgb(1.0f))).split_lobes(kUp);
    EXPECT_EQ(glass.delta, uint32_t(kTransmission));
    EXPECT_EQ(glass.non_delta, 0u);
    EXPECT_EQ(glass.p_non_delta, 0.0f);

    const Bsdf::LobeSplit frosted = make(with(Rgb(0.0f), Rgb(0.0f), 0, Rgb(1.0f), 30)).split_lobes(kUp);
    EXPECT_EQ(frosted.delta, 0u);
    EXPECT_EQ(frosted.non_delta, uint32_t(kTransmission));
    EXPECT_EQ(frosted.p_non_delta, 1.0f);

    Material dt;
    dt.diffuse_transmission = Rgb(0.4f);
    const Bsdf::LobeSplit translucent = make(dt).split_lobes(kUp);
    EXPECT_EQ(translucent.delta, 0u);
    EXPECT_EQ(translucent.non_delta, uint32_t(kDiffuse));
}

TEST(LobeSplit, MixedMaterialsChooseByAlbedo) {
    // Lambert under a mirror coat: p = kd / (kd + ks) on the channel averages.
    const Bsdf::LobeSplit coated =
        make(with(Rgb(0.2f, 0.3f, 0.4f), Rgb(0.6f), kMirror, Rgb(0.0f))).split_lobes(kUp);
    EXPECT_EQ(coated.delta, uint32_t(kSpecular));
    EXPECT_EQ(coated.non_delta, uint32_t(kDiffuse));
    EXPECT_NEAR(coated.p_non_delta, 0.3f / 0.9f, 1e-6f);

    // Lambert plus smooth glass: the glass is delta.
    const Bsdf::LobeSplit lg = make(with(Rgb(0.2f), Rgb(0.0f), 0, Rgb(0.6f))).split_lobes(kUp);
    EXPECT_EQ(lg.delta, uint32_t(kTransmission));
    EXPECT_EQ(lg.non_delta, uint32_t(kDiffuse));
    EXPECT_NEAR(lg.p_non_delta, 0.25f, 1e-6f);

    // Frosted glass under a mirror coat: the glass joins the non-delta part.
    const Bsdf::LobeSplit fm = make(with(Rgb(0.0f), Rgb(0.3f), kMirror, Rgb(0.6f), 30)).split_lobes(kUp);
    EXPECT_EQ(fm.delta, uint32_t(kSpecular));
    EXPECT_EQ(fm.non_delta, uint32_t(kTransmission));
    EXPECT_NEAR(fm.p_non_delta, 0.6f / 0.9f, 1e-6f);

    // Lambert plus Phong: nothing delta.
    const Bsdf::LobeSplit lp = make(with(Rgb(0.3f), Rgb(0.3f), 20, Rgb(0.0f))).split_lobes(kUp);
    EXPECT_EQ(lp.delta, 0u);
    EXPECT_EQ(lp.non_delta, uint32_t(kDiffuse | kGlossy));
    EXPECT_EQ(lp.p_non_delta, 1.0f);
}

TEST(LobeSplit, SmoothGlassIsDeltaWhateverTheShadingNormal) {
    // A tilted shading normal and a grazing wo: sampling the glass may fail here, but the lobe is
    // still a delta lobe (a probe sample that failed must not make it count as glossy).
    const Bsdf b = make(with(Rgb(0.2f), Rgb(0.0f), 0, Rgb(0.6f)), Vec3(0.8f, 0, 0.6f));
    int probe_failed = 0;
    for (float x : {-0.999f, -0.9f, 0.0f, 0.9f}) {
        const Vec3 wo = normalize(Vec3(x, 0, 0.05f));
        const Bsdf::LobeSplit s = b.split_lobes(wo);
        EXPECT_EQ(s.delta, uint32_t(kTransmission));
        EXPECT_EQ(s.non_delta, uint32_t(kDiffuse));
        EXPECT_NEAR(s.p_non_delta, 0.25f, 1e-6f);
        probe_failed += !b.sample_lobes(kTransmission, wo, 0.5f, {0.5f, 0.5f});
    }
    EXPECT_GT(probe_failed, 0);  // the case this test is about does occur
}

TEST(LobeSplit, DeltaMaskSamplesOnlyDeltaLobes) {
    const Bsdf b = make(with(Rgb(0.3f), Rgb(0.6f), kMirror, Rgb(0.0f)));
    const Bsdf::LobeSplit s = b.split_lobes(kUp);
    for (float u : {0.01f, 0.3f, 0.6f, 0.99f}) {
        const auto d = b.sample_lobes(s.delta, kUp, u, {0.3f, 0.7f});
        ASSERT_TRUE(d);
        EXPECT_TRUE(d->is_specular());
        const auto n = b.sample_lobes(s.non_delta, kUp, u, {0.3f, 0.7f});
        ASSERT_TRUE(n);
        EXPECT_FALSE(n->is_specular());
    }
}

TEST(IsLambertian, OnlyASingleLambertLobe) {
    EXPECT_TRUE(make(with(Rgb(0.5f), Rgb(0.0f), 0, Rgb(0.0f))).is_lambertian());
    EXPECT_TRUE(make(Material{}).is_lambertian());  // black body: a black Lambert lobe
    EXPECT_FALSE(make(with(Rgb(0.5f), Rgb(0.2f), 20, Rgb(0.0f))).is_lambertian());
    EXPECT_FALSE(make(with(Rgb(0.5f), Rgb(0.2f), kMirror, Rgb(0.0f))).is_lambertian());
    EXPECT_FALSE(make(with(Rgb(0.5f), Rgb(0.0f), 0, Rgb(0.2f))).is_lambertian());
    Material dt = with(Rgb(0.5f), Rgb(0.0f), 0, Rgb(0.0f));
    dt.diffuse_transmission = Rgb(0.2f);
    EXPECT_FALSE(make(dt).is_lambertian());
    Material interface;
    interface.interface_only = true;
    EXPECT_FALSE(make(interface).is_lambertian());
}

}  // namespace
}  // namespace phos::shading
