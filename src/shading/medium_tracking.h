// Free-flight sampling and transmittance in a participating medium by null-collision tracking
// against the medium's majorants: weighted delta tracking with spectral-tracking probabilities
// (Kutz, Habel, Li & Novak 2017, "Spectral and decomposition tracking", sec. 5) for free flights,
// ratio tracking (Novak, Selle & Jarosz 2014, eq. 6) for transmittance. Homogeneous media take the
// closed form exp(-sigma_t d) for transmittance.
//
// The RTE along a ray with a scalar majorant sigma_maj >= every channel of sigma_t (null
// coefficient sigma_n = sigma_maj - sigma_t per channel):
//   L(0) = int_0^d T_maj(t) [sigma_a Le + sigma_s L_s + sigma_n L](t) dt + T_maj(d) L_surface
// Tentative collisions are drawn with pdf sigma_maj T_maj(t); at each one the emission term
// sigma_a Le / sigma_maj is collected, then the walk either scatters (probability P_s) or passes
// through a null collision (P_n = 1 - P_s), with weights sigma_s / (sigma_maj P_s) and
// sigma_n / (sigma_maj P_n). P_s and P_n are proportional to the channel averages of weight*sigma_s
// and weight*sigma_n (weight: the path throughput times the flight's weight so far), so chromatic media stay
// unbiased and the weights stay bounded; for a grey homogeneous medium the walk scatters at its first
// collision with weight = the albedo.
#pragma once

#include "core/rng.h"
#include "core/vec.h"
#include "shading/medium.h"

namespace phos::shading {

struct FreeFlight {
    bool scattered = false;  // a real scattering event at distance t
    float t = 0;
    // Multiplies the path throughput: at the scattering point when `scattered`, else for the light
    // arriving from t_max (0 when the walk was absorbed, i.e. neither choice had any weight).
    Spectrum weight{1.0f};
    // Emission collected along the flight (collision estimator), to be multiplied by the
    // throughput before the flight.
    Spectrum emitted{0.0f};
};

// One free flight from o along unit direction d over [0, t_max) (t_max may be kInf). `throughput`
// is the path's weight before the flight: the collision probabilities follow it (Kutz et al.'s
// history-aware probabilities), which keeps the path weights bounded in chromatic media; without it
// a channel whose sigma_t is the majorant would gain a factor ~1/P_s at every scattering event.
FreeFlight sample_free_flight(const Medium& medium, Vec3 o, Vec3 d, float t_max, Sampler& sampler,
                              const Wavelengths& lambda, const Spectrum& throughput = Spectrum(1.0f));

// Transmittance between o and o + t_max d (unit d): exact for homogeneous media, ratio tracking
// (unbiased, with Russian roulette once it is small) for grids.
Spectrum transmittance(const Medium& medium, Vec3 o, Vec3 d, float t_max, Sampler& sampler,
                       const Wavelengths& lambda);

}  // namespace phos::shading
