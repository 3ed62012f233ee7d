// The share of light arriving through interfaces (see light_reach_share.h).
#include "integrators/light_reach_share.h"

#include "photon/light_reach.h"
#include "photon/projection_map.h"

namespace phos::integrators {

double share_lit_through_interfaces(const render::Prepared& P) {
    const float sharp = P.options.sharp_glossy;
    if (P.lights.size() == 0 || !photon::has_caustic_casters(P.scene, sharp)) return 0.0;
    const photon::PhotonScene ps{P.scene, P.accel, P.lights, P.bsdfs, P.active_media(), sharp};
    return photon::survey_light_reach(ps, P.options.seed).followed_share();
}

}  // namespace phos::integrators
