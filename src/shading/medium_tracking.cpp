// Delta / ratio tracking (see medium_tracking.h for the estimator and its references): one walk over
// the majorant segments draws the tentative collisions, and each tracker says what a collision does.
#include "shading/medium_tracking.h"

#include <algorithm>
#include <cmath>

namespace phos::shading {

namespace {

// The null-collision walk both trackers share (Woodcock, Murphy, Hemmings & Longworth 1965, "Techniques
// used in the GEM code for Monte Carlo neutronics calculations"; the structure of pbrt-v4's SampleT_maj):
// segment by segment along o + t d, t in [0, t_max), tentative collisions are drawn with the pdf
// sigma_maj exp(-sigma_maj (t - ta)) of the segment's majorant; a step past the segment's end tb
// restarts at the next segment (the exponential is memoryless). `at_collision(t, sigma_maj)` is
// called at each tentative collision and returns false to end the walk there.
template <class AtCollision>
void walk_majorant_collisions(const Medium& medium, Vec3 o, Vec3 d, float t_max, Sampler& sampler,
                              AtCollision&& at_collision) {
    Medium::Majorants segments = medium.majorants(o, d, 0.0f, t_max);
    float ta, tb, sigma_maj;
    while (segments.next(ta, tb, sigma_maj)) {
        if (!(sigma_maj > 0)) continue;
        float t = ta;
        while (true) {
            t -= std::log1p(-sampler.next()) / sigma_maj;
            if (!(t < tb)) break;
            if (!at_collision(t, sigma_maj)) return;
        }
    }
}

}  // namespace

// Weighted delta tracking (Woodcock et al. 1965) with spectral-tracking probabilities (Kutz et al.
// 2017, sec. 5): at each tentative collision, collect sigma_a Le / sigma_maj, then scatter with
// probability P_s (weight sigma_s / (sigma_maj P_s)) or pass a null collision (weight
// sigma_n / (sigma_maj P_n)).
FreeFlight sample_free_flight(const Medium& medium, Vec3 o, Vec3 d, float t_max, Sampler& sampler,
                              const Wavelengths& lambda, const Spectrum& throughput) {
    FreeFlight f;
    walk_majorant_collisions(medium, o, d, t_max, sampler, [&](float t, float sigma_maj) {
        const MediumCoefficients c = medium.at(o + d * t, lambda);
        if (!c.Le.is_black()) f.emitted += f.weight * c.sigma_a * c.Le * (1.0f / sigma_maj);
        Spectrum sigma_n = Spectrum(sigma_maj) - c.sigma_t();
        for (float& x : sigma_n.v) x = std::max(x, 0.0f);
        const Spectrum w = throughput * f.weight;
        const float ws = (w * c.sigma_s).average(), wn = (w * sigma_n).average();
        if (!(ws + wn > 0)) {  // nothing but absorption left: the walk ends here
            f.weight = Spectrum(0.0f);
            return false;
        }
        const float p_s = ws / (ws + wn);
        if (sampler.next() < p_s) {
            f.weight *= c.sigma_s * (1.0f / (sigma_maj * p_s));
            f.scattered = true;
            f.t = t;
            return false;
        }
        f.weight *= sigma_n * (1.0f / (sigma_maj * (1 - p_s)));
        return true;
    });
    return f;
}

// Ratio tracking (Novak, Selle & Jarosz 2014, "Residual ratio tracking for estimating attenuation
// in participating media", eq. 6): T = prod over the tentative collisions of (1 - sigma_t / sigma_maj),
// with Russian roulette once T is small.
Spectrum transmittance(const Medium& medium, Vec3 o, Vec3 d, float t_max, Sampler& sampler,
                       const Wavelengths& lambda) {
    if (medium.homogeneous()) return spectrum::exp(medium.sigma_t(lambda) * -std::fmin(t_max, 1e30f));
    Spectrum T(1.0f);
    walk_majorant_collisions(medium, o, d, t_max, sampler, [&](float t, float sigma_maj) {
        const Spectrum sigma_t = medium.at(o + d * t, lambda).sigma_t();
        for (int i = 0; i < spectrum::kSpectrumSamples; ++i)
            T[i] *= std::max(1 - sigma_t[i] / sigma_maj, 0.0f);
        if (T.max() < 0.05f) {  // Russian roulette: survive with probability 1/2
            if (sampler.next() < 0.5f) {
                T = Spectrum(0.0f);
                return false;
            }
            T *= 2.0f;
        }
        return true;
    });
    return T;
}

}  // namespace phos::shading
