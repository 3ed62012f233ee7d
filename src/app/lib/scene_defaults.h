// Defaults that fit the scene: how the lights' power first reaches the surfaces decides the
// default integrator and its caustic budget (docs/usage.md, "Defaults that fit the scene").
#pragma once

#include <optional>
#include <set>
#include <string>

#include "app/lib/render_options.h"
#include "render/prepared.h"

namespace phos::app {

// A scene counts as lit through interfaces when at least this share of the lights' power first
// reaches the surfaces (or media) through mirrors, glass or sharp glossy lobes.
inline constexpr double kLitThroughInterfacesShare = 0.5;
// Its caustic map then holds this many times the global map's photons (unless set explicitly).
inline constexpr uint64_t kCausticToGlobalRatio = 5;

// The survey's verdict on a prepared scene: its share of light through interfaces
// (integrators::share_lit_through_interfaces) when that is at least kLitThroughInterfacesShare,
// else nothing. Such a scene is lit mostly by caustics: photonmap reads them from its caustic map,
// where a path tracer finds that light only when a path happens to pass the glass to the light.
std::optional<double> lit_through_interfaces(const render::Prepared& P);

// The defaults for such a scene, applied to `cmd` (whose integrator was a default one: neither the
// command line nor the scene file chose it, pbrt's implied path included): photonmap, and a caustic
// map of kCausticToGlobalRatio x the global map's photons (as --quality left them) unless the
// command line or the scene file (`from_scene`) set its budget or --photons fixes the emission.
// `before` is the integrator the defaults had chosen. Returns what was chosen and why, for the
// start-up line ("default: ...").
std::string fit_defaults_to_light_paths(RenderCommand& cmd, integrators::IntegratorKind before, double share,
                                        const std::set<std::string>& from_scene);

}  // namespace phos::app
