// The per-pixel statistics of progressive photon mapping (N, R², τ, direct-light sum) and the
// equations that update them, as small pure functions: the state beside its estimator.
//
// SPPM (Hachisuka & Jensen 2009, "Stochastic progressive photon mapping", eq. 9-12) shares one
// set of statistics per pixel over all iterations; PPM (Hachisuka, Ogaki & Jensen 2008,
// "Progressive photon mapping": radius reduction, flux correction, radiance evaluation) keeps the
// same statistics per hit point. After an iteration in which M_i photons land within R_i and their
// BSDF-weighted flux sums to Φ_i (camera throughput β included):
//   N_{i+1}  = N_i + α M_i                                   (eq. 9)
//   R²_{i+1} = R²_i (N_i + α M_i) / (N_i + M_i)              (eq. 10, squared)
//   τ_{i+1}  = (τ_i + Φ_i) R²_{i+1} / R²_i                   (eq. 11)
//   L        = τ / (π R² N_emitted)                          (eq. 12)
// N_emitted counts every photon emitted over all iterations (photon powers are flux / photons
// emitted in one pass). A pixel that received no photon (M_i = 0) keeps N, R², τ unchanged.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "render/progressive_checkpoint.h"

namespace phos::integrators {
using namespace render;  // the render support the algorithms are written over (src/render/)
}  // namespace phos::integrators

namespace phos::integrators::sppm {

// The statistics of one hit-point slot (render/progressive_checkpoint.h saves them bit for bit).
using render::PixelStats;

// Eq. 9: the photon count after an iteration that found m photons, of which α are kept.
inline double next_n(double n, double alpha, double m) { return n + alpha * m; }

// Eq. 10 (squared): the radius shrinks so that the disc would have held N + αM photons at the
// density seen. n_next = next_n(n, alpha, m). Needs n + m > 0.
inline double next_r2(double r2, double n, double n_next, double m) { return r2 * n_next / (n + m); }

// Eq. 11: the flux within the shrunk disc, τ scaled by the area ratio `shrink` = R²_{i+1} / R²_i.
inline double next_tau(double tau, double phi, double shrink) { return (tau + phi) * shrink; }

// One progressive update of `s` (eq. 9-11) after an iteration that found `m` photons with
// throughput-weighted flux sums phi[3] (β Φ_i per channel). m = 0: nothing changes (the update
// would divide 0 by 0 on a pixel that never received a photon).
inline void progressive_update(PixelStats& s, uint64_t m, const double phi[3], double alpha) {
    if (m == 0) return;
    const double n_next = next_n(s.n, alpha, double(m));
    const double r2_next = next_r2(s.r2, s.n, n_next, double(m));
    const double shrink = r2_next / s.r2;
    for (int k = 0; k < 3; ++k) s.tau[k] = next_tau(s.tau[k], phi[k], shrink);
    s.n = n_next;
    s.r2 = r2_next;
}

// The same in a medium (Knaus & Zwicker 2011 with kernel dimension 3): the ball's volume shrinks
// by (N + αM)/(N + M), so R² shrinks by its 2/3 power and τ by the volume ratio.
inline void progressive_update_volume(PixelStats& s, uint64_t m, const double phi[3], double alpha) {
    if (m == 0) return;
    const double n_next = next_n(s.n, alpha, double(m));
    const double shrink = n_next / (s.n + double(m));  // R³_{i+1} / R³_i
    for (int k = 0; k < 3; ++k) s.tau[k] = next_tau(s.tau[k], phi[k], shrink);
    s.n = n_next;
    s.r2 *= std::cbrt(shrink * shrink);
}

// Eq. 12's normalisation 1 / (π R² N_emitted) for a slot of squared radius r2, given
// inv_emitted = 1 / N_emitted (0 before any photon): multiplies τ into radiance. 0 when r2 = 0
// (no visible point yet).
inline double radiance_scale(double r2, double inv_emitted) {
    return r2 > 0 ? inv_emitted / (M_PI * r2) : 0.0;
}
// The same for a volume slot: 1 / (4/3 π R³ N_emitted).
inline double volume_radiance_scale(double r2, double inv_emitted) {
    return r2 > 0 ? inv_emitted / (4.0 / 3.0 * M_PI * r2 * std::sqrt(r2)) : 0.0;
}

}  // namespace phos::integrators::sppm
