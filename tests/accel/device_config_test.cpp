// Embree device configurations (accel/device_config.h): what --embree-config accepts and refuses,
// and that what it accepts makes a working Embree scene.
#include "accel/device_config.h"

#include <gtest/gtest.h>

#include "accel/embree_scene.h"
#include "scene/scene.h"
#include "support/shapes.h"

namespace phos::testing {
namespace {

using accel::embree_config_error;

TEST(EmbreeConfig, AcceptsEveryDocumentedKeyAndValue) {
    // sse2 and sse4.2 run on every x86-64 CPU phos supports (Embree's oldest kernels).
    for (const char* ok :
         {"", "isa=sse2", "max_isa=sse4.2", "frequency_level=simd128", "frequency_level=simd256",
          "frequency_level=simd512", "hugepages=0", "hugepages=1", "verbose=0", "verbose=3",
          "isa=sse4.2,frequency_level=simd256,hugepages=1,verbose=0"})
        EXPECT_EQ(embree_config_error(ok), "") << ok;
}

TEST(EmbreeConfig, RefusesWhatEmbreeWouldIgnore) {
    // Each of these rtcNewDevice takes without a word, leaving its defaults.
    const std::pair<const char*, const char*> bad[] = {
        {"isa=foo", "isa is one of"},
        {"isa=AVX2", "isa is one of"},
        {"max_isa=avx3", "max_isa is one of"},
        {"frequency_level=fast", "frequency_level is one of"},
        {"hugepages=yes", "hugepages is one of"},
        {"verbose=4", "verbose is one of"},
        {"isas=avx2", "unknown key 'isas'"},
        {"threads=2", "--threads"},
        {"set_affinity=1", "--threads"},
        {"isa", "not key=value"},
        {"isa=", "not key=value"},
        {"=avx2", "not key=value"},
        {",isa=sse2", "not key=value"},
        {"isa=sse2,,verbose=0", "not key=value"},
        {"isa=sse2,", "ends with a comma"},
        {"isa=sse2,isa=sse4.2", "given twice"},
    };
    for (const auto& [config, says] : bad) {
        const std::string e = embree_config_error(config);
        EXPECT_NE(e.find(says), std::string::npos) << config << ": " << e;
    }
}

TEST(EmbreeConfig, AnAcceptedConfigurationTracesTheScene) {
    // A triangle mesh (Embree's kernels of the chosen width) in front of an analytic sphere.
    scene::Scene s;
    s.shapes.push_back(quad({-1, -1, 2}, {1, -1, 2}, {1, 1, 2}, {-1, 1, 2}));
    s.shapes.push_back(sphere({0, 0, 0}, 1));
    for (const char* config : {"isa=sse2", "isa=sse4.2,frequency_level=simd128"}) {
        ASSERT_EQ(embree_config_error(config), "");
        const accel::EmbreeScene accel(s, config);
        accel::SurfaceHit hit;
        ASSERT_TRUE(accel.intersect(Ray{Vec3(0.5f, 0.5f, 5), Vec3(0, 0, -1)}, hit)) << config;
        EXPECT_NEAR(hit.t, 3.0f, 1e-5f) << config;
        EXPECT_EQ(hit.shape, 0) << config;
        ASSERT_TRUE(accel.intersect(Ray{Vec3(0, 0, 1.5f), Vec3(0, 0, -1)}, hit)) << config;
        EXPECT_NEAR(hit.t, 0.5f, 1e-5f) << config;
        EXPECT_EQ(hit.shape, 1) << config;
        EXPECT_FALSE(accel.intersect(Ray{Vec3(0, 3, 5), Vec3(0, 0, -1)}, hit)) << config;
    }
}

}  // namespace
}  // namespace phos::testing
