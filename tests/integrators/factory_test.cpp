// The integrator factory takes only option structs inside their tables' ranges, and reports a bad
// one with the tables' wording (the integrators themselves never check or name flags).
#include "integrators/factory.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace phos::integrators {
namespace {

std::string error_of(const std::string& name, const IntegratorConfig& c) {
    try {
        make_integrator(name, c);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(Factory, RefusesOptionsOutsideTheirTables) {
    IntegratorConfig c;
    EXPECT_EQ(error_of("sppm", c), "");
    c.progressive.alpha = 0;
    EXPECT_EQ(error_of("sppm", c), "--alpha: 0 is not in (0, 1]");
    c = {};
    c.photon_map.caustic.samples = 0;
    EXPECT_EQ(error_of("photonmap", c), "--caustic-samples: 0 is not in [1, 100000]");
    c = {};
    c.photon_map.global.cone_k = 0.5f;
    EXPECT_EQ(error_of("photonmap", c), "--global-cone-k: 0.5 is not in [1, 1000000]");
    EXPECT_EQ(error_of("magic", {}), "unknown integrator 'magic'");
}

TEST(Factory, EveryIntegratorNamesItsLayers) {
    for (const std::string& n : integrator_names()) {
        const auto layers = integrator_layers(n);
        EXPECT_GE(layers.size(), 2u) << n;
        EXPECT_EQ(layers.front(), "direct") << n;
    }
}

}  // namespace
}  // namespace phos::integrators
