// PathRadiance (render/path_radiance.h): which --layers component each contribution of a camera
// path goes to, decided from the events the path reports, each taken to colour at the path's
// wavelengths.
#include "render/path_radiance.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "spectrum/color.h"

namespace phos::render {
namespace {

const Wavelengths kLambda = Wavelengths::visible(0.3f);

// The component a unit of emission and a unit of sampled light go to after `bounces` (true: delta).
std::pair<Component, Component> where(std::initializer_list<bool> bounces) {
    const auto component_of = [](const RadianceParts& p) {
        for (const Component c : all_components())
            if (RadianceParts(p)[c] == spectrum::to_srgb(Spectrum(1.0f), kLambda)) return c;
        ADD_FAILURE() << "no component holds the contribution";
        return Component::Direct;
    };
    RadianceParts emitted, sampled;
    PathRadiance e(kLambda, &emitted), l(kLambda, &sampled);
    for (const bool delta : bounces) {
        e.bounce(delta);
        l.bounce(delta);
    }
    e.emission(Spectrum(1.0f));
    l.light(Spectrum(1.0f));
    return {component_of(emitted), component_of(sampled)};
}

using C = Component;
using Both = std::pair<Component, Component>;

TEST(PathRadiance, FirstSurfaceSeenDirectlyIsDirect) {
    EXPECT_EQ(where({}), Both(C::Direct, C::Direct));                  // camera ray: emitter seen, x's light
    EXPECT_EQ(where({false}), Both(C::Direct, C::Indirect));           // x's BSDF sample finds emission
    EXPECT_EQ(where({false, false}), Both(C::Indirect, C::Indirect));  // two diffuse bounces
}

TEST(PathRadiance, DeltaBouncesAfterXAreCaustic) {
    EXPECT_EQ(where({false, true}), Both(C::Caustic, C::Indirect));  // x S L
    EXPECT_EQ(where({false, true, true}), Both(C::Caustic, C::Indirect));
    EXPECT_EQ(where({false, true, false}), Both(C::Indirect, C::Indirect));
}

TEST(PathRadiance, EverythingAfterADeltaBounceFromTheCameraIsSpecular) {
    EXPECT_EQ(where({true}), Both(C::Specular, C::Specular));
    EXPECT_EQ(where({true, false}), Both(C::Specular, C::Specular));
    EXPECT_EQ(where({true, false, true, false}), Both(C::Specular, C::Specular));
}

TEST(PathRadiance, TotalIsTheSumWithOrWithoutParts) {
    RadianceParts parts;
    PathRadiance split(kLambda, &parts), plain(kLambda);
    for (PathRadiance* L : {&split, &plain}) {
        L->emission(Spectrum(0.5f));
        L->bounce(false);
        L->light(Spectrum(0.25f));
        L->emission(Spectrum(0.125f));
    }
    const Rgb one = spectrum::to_srgb(Spectrum(1.0f), kLambda);
    const auto near = [&](Rgb a, Rgb b) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-6f * one.max());
    };
    near(split.total(), one * 0.875f);
    near(plain.total(), one * 0.875f);
    near(parts.direct, one * 0.625f);
    near(parts.indirect, one * 0.25f);
    near(parts.total(), split.total());
}

TEST(PathRadiance, ComponentsNameTheirLayers) {
    std::vector<std::string> names;
    for (const Component c : all_components()) names.push_back(component_name(c));
    EXPECT_EQ(names, (std::vector<std::string>{"direct", "caustic", "indirect", "specular"}));
}

}  // namespace
}  // namespace phos::render
