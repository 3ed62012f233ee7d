// Tests of Bsdf::split_lobes (delta and sharp glossy lobes followed by ray tracing vs the rest, and
// the probability of the estimated part), Bsdf::only, Bsdf::regularized and Bsdf::is_lambertian.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "shading/bsdf.h"
#include "spectral_test_util.h"

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
const Wavelengths& kLambda = spectral::fixed_lambda();
constexpr float kMirror = Material::kMirrorShininess;

TEST(LobeSplit, PureMaterials) {
    const Bsdf::LobeSplit lambert = make(with(Rgb(0.5f), Rgb(0.0f), 0, Rgb(0.0f))).split_lobes(kUp);
    EXPECT_EQ(lambert.followed, 0u);
    EXPECT_EQ(lambert.estimated, uint32_t(kDiffuse));
    EXPECT_EQ(lambert.p_estimated, 1.0f);

    const Bsdf::LobeSplit mirror = make(with(Rgb(0.0f), Rgb(0.9f), kMirror, Rgb(0.0f))).split_lobes(kUp);
    EXPECT_EQ(mirror.followed, uint32_t(kSpecular));
    EXPECT_EQ(mirror.estimated, 0u);
    EXPECT_EQ(mirror.p_estimated, 0.0f);

    const Bsdf::LobeSplit phong = make(with(Rgb(0.0f), Rgb(0.9f), 20, Rgb(0.0f))).split_lobes(kUp);
    EXPECT_EQ(phong.followed, 0u);
    EXPECT_EQ(phong.estimated, uint32_t(kGlossy));
    EXPECT_EQ(phong.p_estimated, 1.0f);

    const Bsdf::LobeSplit glass = make(with(Rgb(0.0f), Rgb(0.0f), 0, Rgb(1.0f))).split_lobes(kUp);
    EXPECT_EQ(glass.followed, uint32_t(kTransmission));
    EXPECT_EQ(glass.estimated, 0u);
    EXPECT_EQ(glass.p_estimated, 0.0f);

    const Bsdf::LobeSplit frosted = make(with(Rgb(0.0f), Rgb(0.0f), 0, Rgb(1.0f), 30)).split_lobes(kUp);
    EXPECT_EQ(frosted.followed, 0u);
    EXPECT_EQ(frosted.estimated, uint32_t(kTransmission));
    EXPECT_EQ(frosted.p_estimated, 1.0f);

    Material dt;
    dt.diffuse_transmission = Rgb(0.4f);
    const Bsdf::LobeSplit translucent = make(dt).split_lobes(kUp);
    EXPECT_EQ(translucent.followed, 0u);
    EXPECT_EQ(translucent.estimated, uint32_t(kDiffuse));
}

TEST(LobeSplit, MixedMaterialsChooseByAlbedo) {
    // Lambert under a mirror coat: p = kd / (kd + ks) on the channel averages.
    const Bsdf::LobeSplit coated =
        make(with(Rgb(0.2f, 0.3f, 0.4f), Rgb(0.6f), kMirror, Rgb(0.0f))).split_lobes(kUp);
    EXPECT_EQ(coated.followed, uint32_t(kSpecular));
    EXPECT_EQ(coated.estimated, uint32_t(kDiffuse));
    EXPECT_NEAR(coated.p_estimated, 0.3f / 0.9f, 1e-6f);

    // Lambert plus smooth glass: the glass is delta.
    const Bsdf::LobeSplit lg = make(with(Rgb(0.2f), Rgb(0.0f), 0, Rgb(0.6f))).split_lobes(kUp);
    EXPECT_EQ(lg.followed, uint32_t(kTransmission));
    EXPECT_EQ(lg.estimated, uint32_t(kDiffuse));
    EXPECT_NEAR(lg.p_estimated, 0.25f, 1e-6f);

    // Frosted glass under a mirror coat: the glass joins the non-delta part.
    const Bsdf::LobeSplit fm = make(with(Rgb(0.0f), Rgb(0.3f), kMirror, Rgb(0.6f), 30)).split_lobes(kUp);
    EXPECT_EQ(fm.followed, uint32_t(kSpecular));
    EXPECT_EQ(fm.estimated, uint32_t(kTransmission));
    EXPECT_NEAR(fm.p_estimated, 0.6f / 0.9f, 1e-6f);

    // Lambert plus Phong: nothing delta.
    const Bsdf::LobeSplit lp = make(with(Rgb(0.3f), Rgb(0.3f), 20, Rgb(0.0f))).split_lobes(kUp);
    EXPECT_EQ(lp.followed, 0u);
    EXPECT_EQ(lp.estimated, uint32_t(kDiffuse | kGlossy));
    EXPECT_EQ(lp.p_estimated, 1.0f);
}

TEST(LobeSplit, SmoothGlassIsDeltaWhateverTheShadingNormal) {
    // A tilted shading normal and a grazing wo: sampling the glass may fail here, but the lobe is
    // still a delta lobe (a probe sample that failed must not make it count as glossy).
    const Bsdf b = make(with(Rgb(0.2f), Rgb(0.0f), 0, Rgb(0.6f)), Vec3(0.8f, 0, 0.6f));
    int probe_failed = 0;
    for (float x : {-0.999f, -0.9f, 0.0f, 0.9f}) {
        const Vec3 wo = normalize(Vec3(x, 0, 0.05f));
        const Bsdf::LobeSplit s = b.split_lobes(wo);
        EXPECT_EQ(s.followed, uint32_t(kTransmission));
        EXPECT_EQ(s.estimated, uint32_t(kDiffuse));
        EXPECT_NEAR(s.p_estimated, 0.25f, 1e-6f);
        probe_failed += !b.sample_lobes(kTransmission, wo, 0.5f, {0.5f, 0.5f}, kLambda);
    }
    EXPECT_GT(probe_failed, 0);  // the case this test is about does occur
}

TEST(LobeSplit, DeltaMaskSamplesOnlyDeltaLobes) {
    const Bsdf b = make(with(Rgb(0.3f), Rgb(0.6f), kMirror, Rgb(0.0f)));
    const Bsdf::LobeSplit s = b.split_lobes(kUp);
    for (float u : {0.01f, 0.3f, 0.6f, 0.99f}) {
        const auto d = b.sample_lobes(s.followed, kUp, u, {0.3f, 0.7f}, kLambda);
        ASSERT_TRUE(d);
        EXPECT_TRUE(d->is_specular());
        const auto n = b.sample_lobes(s.estimated, kUp, u, {0.3f, 0.7f}, kLambda);
        ASSERT_TRUE(n);
        EXPECT_FALSE(n->is_specular());
    }
}

TEST(LobeSplit, GlossyLobesAtLeastAsSharpAsTheThresholdAreFollowed) {
    // Phong exponent 20: estimated below a threshold of 30, followed from 20 down.
    const Bsdf phong = make(with(Rgb(0.0f), Rgb(0.9f), 20, Rgb(0.0f)));
    EXPECT_EQ(phong.split_lobes(kUp, 30).estimated, uint32_t(kGlossy));
    EXPECT_EQ(phong.split_lobes(kUp, 30).followed, 0u);
    EXPECT_TRUE(phong.has_estimated(30));
    for (float sharp : {20.0f, 10.0f, 0.0f}) {
        const Bsdf::LobeSplit s = phong.split_lobes(kUp, sharp);
        EXPECT_EQ(s.followed, uint32_t(kGlossy));
        EXPECT_EQ(s.estimated, 0u);
        EXPECT_EQ(s.p_estimated, 0.0f);
        EXPECT_EQ(phong.sharp_lobes(sharp), uint32_t(kGlossy));
        EXPECT_FALSE(phong.has_estimated(sharp));
    }
    // Frosted glass of Phong-equivalent exponent 30: followed at 10, like smooth glass.
    const Bsdf frosted = make(with(Rgb(0.0f), Rgb(0.0f), 0, Rgb(1.0f), 30));
    EXPECT_EQ(frosted.split_lobes(kUp, 10).followed, uint32_t(kTransmission));
    EXPECT_EQ(frosted.sharp_lobes(10), uint32_t(kTransmission));
    EXPECT_EQ(frosted.sharp_lobes(31), 0u);
    // Smooth glass is followed but is not a sharp glossy lobe.
    EXPECT_EQ(make(with(Rgb(0.0f), Rgb(0.0f), 0, Rgb(1.0f))).sharp_lobes(0), 0u);
    // Plastic: Lambert estimated, the sharp highlight followed, chosen by albedo.
    const Bsdf plastic = make(with(Rgb(0.45f, 0.3f, 0.15f), Rgb(0.35f), 60, Rgb(0.0f)));
    const Bsdf::LobeSplit p = plastic.split_lobes(kUp, 10);
    EXPECT_EQ(p.estimated, uint32_t(kDiffuse));
    EXPECT_EQ(p.followed, uint32_t(kGlossy));
    EXPECT_NEAR(p.p_estimated, 0.3f / 0.65f, 1e-6f);
    EXPECT_TRUE(plastic.has_estimated(10));
}

TEST(LobeSplit, TheTwoPartsSumToTheWholeBsdf) {
    // Lambert + Phong 60 + frosted glass 30, split at 10: every lobe but the Lambert is followed.
    // eval of the whole = eval of the parts; each part's pdf is what sampling its mask gives.
    const Bsdf b = make(with(Rgb(0.3f), Rgb(0.2f), 60, Rgb(0.4f), 30), Vec3(0.1f, 0.2f, 1.0f));
    const Bsdf::LobeSplit s = b.split_lobes(kUp, 10);
    ASSERT_EQ(s.estimated, uint32_t(kDiffuse));
    ASSERT_EQ(s.followed, uint32_t(kGlossy | kTransmission));
    const Bsdf est = b.only(s.estimated), fol = b.only(s.followed);
    EXPECT_TRUE(est.is_lambertian());
    EXPECT_EQ(fol.flags() & kDiffuse, 0u);
    Sampler sampler(7, 1, 2);
    int sampled = 0;
    for (int i = 0; i < 200; ++i) {
        const Wavelengths lambda = spectral::stratified_lambda(i, 200);
        const auto bs = b.sample_lobes(s.followed, kUp, sampler.next(), sampler.next2(), lambda);
        if (!bs) continue;
        ++sampled;
        const Spectrum whole = b.eval(kUp, bs->wi, lambda),
                       parts = est.eval(kUp, bs->wi, lambda) + fol.eval(kUp, bs->wi, lambda);
        for (int c = 0; c < spectral::kSpectrumSamples; ++c)
            EXPECT_NEAR(whole[c], parts[c], 1e-5f * std::max(1.0f, whole[c]));
        EXPECT_NEAR(fol.pdf(kUp, bs->wi), bs->pdf, 1e-4f * bs->pdf);
        const Spectrum f = fol.eval(kUp, bs->wi, lambda);
        for (int c = 0; c < spectral::kSpectrumSamples; ++c)
            EXPECT_NEAR(f[c], bs->f[c], 1e-5f * std::max(1.0f, bs->f[c]));
    }
    EXPECT_GT(sampled, 150);
}

TEST(Regularized, WidensSharpLobesToTheExponentAndKeepsTheRest) {
    const Vec3 wo = normalize(Vec3(0.3f, 0.0f, 1.0f));
    // A mirror becomes a lobe sampled as a Phong lobe of the exponent: no longer delta, around the
    // mirror direction.
    const Bsdf mirror = make(with(Rgb(0.0f), Rgb(0.9f), kMirror, Rgb(0.0f))).regularized(200);
    EXPECT_EQ(mirror.flags() & kSpecular, 0u);
    EXPECT_EQ(mirror.flags() & kGlossy, uint32_t(kGlossy));
    const Vec3 r(-wo.x, -wo.y, wo.z);
    Sampler sampler(11, 2, 3);
    double cos_sum = 0, weight_sum = 0;
    const int n = 4000;
    for (int i = 0; i < n; ++i) {
        const auto s = mirror.sample(wo, sampler.next(), sampler.next2(), spectral::stratified_lambda(i, n));
        if (!s) continue;
        EXPECT_FALSE(s->is_specular());
        EXPECT_TRUE(s->weight.is_flat());  // grey ks: the same at every wavelength
        cos_sum += dot(s->wi, r);
        weight_sum += s->weight.average();
    }
    // cos^200 about the mirror direction: mean cosine (n + 1) / (n + 2) = 0.995.
    EXPECT_NEAR(cos_sum / n, 201.0 / 202.0, 0.002);
    // It reflects the mirror's ks at any incidence (each sample's weight is ks), so it tends to the
    // mirror as the exponent grows; a modified Phong lobe would reflect ks cos theta_i.
    EXPECT_NEAR(weight_sum / n, 0.9, 1e-4);

    // Smooth glass becomes frosted glass of that exponent; a sharper Phong lobe is clamped; a wider
    // one, Lambert and thin glass are kept.
    const Bsdf glass = make(with(Rgb(0.0f), Rgb(0.0f), 0, Rgb(1.0f))).regularized(50);
    EXPECT_EQ(glass.flags() & kSpecular, 0u);
    EXPECT_EQ(glass.sharp_lobes(50), uint32_t(kTransmission));
    EXPECT_EQ(glass.sharp_lobes(51), 0u);
    const Bsdf phong = make(with(Rgb(0.2f), Rgb(0.5f), 1000, Rgb(0.0f)));
    EXPECT_EQ(phong.regularized(100).sharp_lobes(101), 0u);
    EXPECT_EQ(phong.regularized(100).sharp_lobes(100), uint32_t(kGlossy));
    const Bsdf wide = make(with(Rgb(0.2f), Rgb(0.5f), 20, Rgb(0.0f)));
    const Vec3 wi = normalize(Vec3(-0.2f, 0.1f, 1.0f));
    EXPECT_EQ(wide.regularized(100).eval(wo, wi, kLambda), wide.eval(wo, wi, kLambda));
    Material thin = with(Rgb(0.0f), Rgb(0.0f), 0, Rgb(1.0f));
    thin.thin = true;
    EXPECT_EQ(make(thin).regularized(10).flags(), make(thin).flags());
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
