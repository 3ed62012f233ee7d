// The survey of how light first reaches the scene (see light_reach.h).
#include "photon/light_reach.h"

#include "spectrum/color.h"

namespace phos::photon {

LightReach survey_light_reach(const PhotonScene& ps, uint64_t seed, uint32_t photons) {
    LightReach r;
    r.photons = photons;
    PhotonPathOptions options;
    // One pass key of its own: the survey's photons are none of the maps' photons.
    constexpr uint64_t kSurveyPass = 0x7375727665790000ULL;
    for (uint32_t i = 0; i < photons; ++i) {
        // Each photon's first stored event ends its path (the visitor returns false).
        const auto first = [&](bool after_specular, const Spectrum& power, const Wavelengths& lambda) {
            (after_specular ? r.followed : r.direct) += double(spectrum::to_srgb(power, lambda).average());
            return false;
        };
        trace_photon(
            ps, seed, kSurveyPass, i, options,
            Visitor{[&](const PhotonHit& h) { return first(h.after_specular, h.power, h.lambda); },
                    [&](const PhotonVolumeHit& h) { return first(h.after_specular, h.power, h.lambda); }});
    }
    r.direct /= double(photons);
    r.followed /= double(photons);
    return r;
}

}  // namespace phos::photon
