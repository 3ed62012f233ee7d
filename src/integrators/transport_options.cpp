// The light-transport option table (see transport_options.h).
#include "integrators/transport_options.h"

#include "integrators/registry.h"
#include "render/options.h"

namespace phos::integrators {

const options::Table& transport_options() {
    static const options::Table table = [] {
        using options::at_least;
        using K = IntegratorKind;
        options::TableBuilder<render::RenderOptions> b(
            "Light transport", "which lobes camera paths follow, and path tracing's firefly control");
        b.number("sharp-glossy", &render::RenderOptions::sharp_glossy, "N", at_least(0),
                 "glossy lobes at least as sharp as a Phong lobe of exponent N (frosted glass and microfacet "
                 "lobes: alpha <= sqrt(2 / (N + 2))) are followed by camera rays like mirrors and glass, and "
                 "light through them is a caustic; wider lobes read the photon maps (0: every glossy lobe is "
                 "followed)")
            .applies_to = integrator_set({K::PhotonMap, K::Ppm, K::Sppm});
        auto& r =
            b.number("regularize", &render::RenderOptions::regularize, "N", at_least(0),
                     "after a path's first rough bounce, lobes sharper than a Phong lobe of exponent "
                     "N (s + 1)^(1/3) at camera sample s, mirrors and glass included, are widened to it "
                     "(path regularisation: caustics and glints behind glossy glass stop being "
                     "fireflies; the widening vanishes as samples grow, so the render converges to the "
                     "same image); 0 = off");
        r.applies_to = integrator_set({K::Path});
        return b.build();
    }();
    return table;
}

}  // namespace phos::integrators
