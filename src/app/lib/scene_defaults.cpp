// Defaults chosen from how light reaches the scene (see scene_defaults.h).
#include "app/lib/scene_defaults.h"

#include <algorithm>

#include "core/format.h"
#include "integrators/light_reach_share.h"
#include "integrators/registry.h"

namespace phos::app {

std::optional<double> lit_through_interfaces(const render::Prepared& P) {
    const double share = integrators::share_lit_through_interfaces(P);
    if (share < kLitThroughInterfacesShare) return std::nullopt;
    return share;
}

std::string fit_defaults_to_light_paths(RenderCommand& cmd, integrators::IntegratorKind before, double share,
                                        const std::set<std::string>& from_scene) {
    cmd.run.integrator = integrators::IntegratorKind::PhotonMap;
    std::string why = printf_string(
        "default: %.0f %% of the light reaches the surfaces through mirrors, glass or sharp glossy lobes",
        100 * share);
    if (before != integrators::IntegratorKind::PhotonMap)
        why += "; " + integrators::integrator(before).name + " would find it only by chance";
    integrators::PhotonMapSettings& caustic = cmd.photon_map.caustic;
    const uint64_t global = cmd.photon_map.global.photons;
    const bool caustic_set =
        cmd.was_given("caustic") || from_scene.count("caustic") || cmd.was_given("photons");
    if (!caustic_set && caustic.photons > 0 && global > 0) {
        const uint64_t wanted = std::max<uint64_t>(caustic.photons, kCausticToGlobalRatio * global);
        if (wanted != caustic.photons) {
            caustic.photons = wanted;
            why += "; caustic map " + std::to_string(wanted) + " photons";
        }
    }
    return why;
}

}  // namespace phos::app
