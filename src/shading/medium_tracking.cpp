// Delta / ratio tracking (see medium_tracking.h for the estimator and its references).
#include "shading/medium_tracking.h"

#include <cmath>

namespace phos::shading {

FreeFlight sample_free_flight(const Medium& medium, Vec3 o, Vec3 d, float t_max, Sampler& sampler,
                              Rgb throughput) {
    FreeFlight f;
    Medium::Majorants segments = medium.majorants(o, d, 0.0f, t_max);
    float ta, tb, sigma_maj;
    while (segments.next(ta, tb, sigma_maj)) {
        if (!(sigma_maj > 0)) continue;
        float t = ta;
        while (true) {
            t -= std::log1p(-sampler.next()) / sigma_maj;
            if (!(t < tb)) break;
            const MediumCoefficients c = medium.at(o + d * t);
            if (!c.Le.is_black()) f.emitted += f.weight * c.sigma_a * c.Le * (1.0f / sigma_maj);
            const Rgb sigma_n = max(Rgb(sigma_maj) - c.sigma_t(), Rgb(0.0f));
            const Rgb w = throughput * f.weight;
            const float ws = (w * c.sigma_s).average(), wn = (w * sigma_n).average();
            if (!(ws + wn > 0)) {  // nothing but absorption left: the walk ends here
                f.weight = Rgb(0.0f);
                return f;
            }
            const float p_s = ws / (ws + wn);
            if (sampler.next() < p_s) {
                f.weight *= c.sigma_s * (1.0f / (sigma_maj * p_s));
                f.scattered = true;
                f.t = t;
                return f;
            }
            f.weight *= sigma_n * (1.0f / (sigma_maj * (1 - p_s)));
        }
    }
    return f;
}

Rgb transmittance(const Medium& medium, Vec3 o, Vec3 d, float t_max, Sampler& sampler) {
    if (medium.homogeneous()) {
        const Rgb tau = medium.sigma_t() * std::fmin(t_max, 1e30f);
        return {std::exp(-tau.r), std::exp(-tau.g), std::exp(-tau.b)};
    }
    Rgb T(1.0f);
    Medium::Majorants segments = medium.majorants(o, d, 0.0f, t_max);
    float ta, tb, sigma_maj;
    while (segments.next(ta, tb, sigma_maj)) {
        if (!(sigma_maj > 0)) continue;
        float t = ta;
        while (true) {
            t -= std::log1p(-sampler.next()) / sigma_maj;
            if (!(t < tb)) break;
            const Rgb sigma_t = medium.at(o + d * t).sigma_t();
            T *= max(Rgb(1.0f) - sigma_t * (1.0f / sigma_maj), Rgb(0.0f));
            if (T.max() < 0.05f) {  // Russian roulette: survive with probability 1/2
                if (sampler.next() < 0.5f) return Rgb(0.0f);
                T *= 2.0f;
            }
        }
    }
    return T;
}

}  // namespace phos::shading
