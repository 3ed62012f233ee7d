// The share of light arriving through interfaces (see light_reach_share.h).
#include "integrators/light_reach_share.h"

#include <algorithm>

#include "photon/light_reach.h"
#include "photon/projection_map.h"

namespace phos::integrators {

double share_lit_through_interfaces(const render::Prepared& P) {
    const float sharp = P.options.sharp_glossy;
    if (P.lights.size() == 0 ||
        std::none_of(P.scene.materials.begin(), P.scene.materials.end(),
                     [&](const scene::Material& m) { return photon::is_caustic_caster(m, sharp); }))
        return 0.0;
    const photon::PhotonScene ps{P.scene, P.accel, P.lights, P.bsdfs, P.active_media(), sharp};
    return photon::survey_light_reach(ps, P.options.seed).followed_share();
}

}  // namespace phos::integrators
