// How the lights' power first reaches what the photon estimates read: straight from a light, or
// through followed interfaces first (mirrors, glass, sharp glossy lobes: the L S+ paths of the
// caustic maps). A scene whose light comes mostly the second way (lamps behind glass, a room lit
// through frosted panes, a pool floor under water) is lit mostly by caustics; the render command
// chooses its defaults from this survey (docs/usage.md, "Defaults that fit the scene").
#pragma once

#include <cstdint>

#include "photon/photon_path.h"

namespace phos::photon {

struct LightReach {
    double direct = 0;     // power (channel average, per emitted photon) first stored straight from a light
    double followed = 0;   // power first stored after at least one followed bounce
    uint32_t photons = 0;  // photons traced
    // followed / (direct + followed); 0 when no photon was stored.
    double followed_share() const {
        const double total = direct + followed;
        return total > 0 ? followed / total : 0.0;
    }
};

// Traces `photons` photons from the lights (full emission, seeded by `seed`, the same at any
// thread count) and sums their power where each is first stored: on a surface with estimated
// lobes or at a scattering event in a medium (PhotonScene::sharp_exponent decides which lobes are
// followed). A few thousand photons give the share to about a percent.
LightReach survey_light_reach(const PhotonScene& ps, uint64_t seed, uint32_t photons = 8192);

}  // namespace phos::photon
