// Photon emission and Russian-roulette scattering (see photon_path.h).
#include "photon/photon_path.h"

#include <algorithm>
#include <cmath>

namespace phos::photon {

bool packets_possible(const PhotonScene& ps) {
    if (ps.media && ps.media->active()) return false;
    for (const scene::Material& m : ps.scene.materials)
        if (m.interface_only) return false;
    return true;
}

}  // namespace phos::photon

namespace phos::photon::detail {

bool emit_photon(const PhotonScene& ps, Sampler& sampler, const Wavelengths& lambda, Ray& ray,
                 Spectrum& power, int& medium) {
    if (ps.lights.size() == 0) return false;
    float pmf = 0;
    const size_t li = ps.lights.choose(sampler.next(), pmf);
    if (!(pmf > 0)) return false;
    const Vec2 u_pos = sampler.next2();
    const Vec2 u_dir = sampler.next2();
    const shading::LightLeSample s = ps.lights[li].sample_Le(u_pos, u_dir, lambda);
    if (s.weight.is_black() || !s.weight.is_finite()) return false;
    ray = s.ray;
    power = s.weight * (1.0f / pmf);
    medium = ps.lights.emission_medium(li, s);
    return true;
}

// One Lambert lobe: the code of the general case below with its three absent kinds left out (their
// probabilities are 0, so they neither change the total nor catch u), and sample_lobes(kDiffuse)
// of such a BSDF.
bool scatter_photon(const shading::LambertLobe& lobe, Vec3 wo, Sampler& sampler, const Wavelengths& lambda,
                    Spectrum& power, Vec3& wi_out) {
    Rgb albedo(0.0f);  // the selection reads the colour
    albedo += lobe.kd;
    float p = std::max(albedo.average(), 0.0f);
    if (!(p > 0)) return false;
    if (p > 1) p /= p;
    const float u = sampler.next();
    sampler.next();  // u_lobe: one lobe, nothing to choose
    const Vec2 u_dir = sampler.next2();
    if (u >= p) return false;  // absorbed
    const auto s = lobe.sample(wo, u_dir, lambda);
    if (!s || s->weight.is_black() || !s->weight.is_finite()) return false;
    power = power * s->weight * (1.0f / p);
    wi_out = s->wi;
    return true;
}

bool scatter_photon(const shading::Bsdf& bsdf, Vec3 wo, Sampler& sampler, Wavelengths& lambda,
                    Spectrum& power, Vec3& wi_out, bool& specular, float sharp_exponent) {
    using namespace shading;
    // (surface_step gives a lone Lambert lobe to the overload above instead; this code would draw
    // the same sample for it.)
    const Bsdf::LobeAlbedos a = bsdf.lobe_albedos(wo);
    // Probability of each lobe kind = its albedo averaged over channels (Jensen). If the material
    // reflects more than it receives, the probabilities are scaled down so they sum to 1 and the
    // survival weights grow accordingly, keeping the expected power exact.
    float p[4] = {a.diffuse.average(), a.glossy.average(), a.specular.average(), a.transmission.average()};
    // sample_lobes masks by lobe kind: mirror = kSpecular, dielectric (smooth or frosted) = kTransmission.
    const uint32_t masks[4] = {kDiffuse, kGlossy, kSpecular, kTransmission};
    float total = 0;
    for (float& v : p) total += v = std::max(v, 0.0f);
    if (!(total > 0)) return false;
    if (total > 1)
        for (float& v : p) v /= total;
    float u = sampler.next();
    const float u_lobe = sampler.next();
    const Vec2 u_dir = sampler.next2();
    for (int k = 0; k < 4; ++k) {
        if (u >= p[k]) {
            u -= p[k];
            continue;
        }
        const auto s = bsdf.sample_lobes(masks[k], wo, u_lobe, u_dir, lambda, TransportMode::Importance);
        if (!s || s->weight.is_black() || !s->weight.is_finite()) return false;
        power = power * s->weight * (1.0f / p[k]);
        if (s->dispersive) spectrum::terminate_secondary(lambda, power);
        wi_out = s->wi;
        specular = s->is_specular() || (masks[k] & bsdf.sharp_lobes(sharp_exponent));
        return true;
    }
    return false;  // absorbed
}

}  // namespace phos::photon::detail
