// Fresnel reflectance of smooth interfaces: exact unpolarised dielectric, Schlick's approximation,
// conductors (complex index eta + i k) and the thin-sheet series. All take the cosine on the
// incident side and the relative index eta = n_transmitted / n_incident.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>

#include "core/vec.h"

namespace phos::shading {

// Amplitude reflection coefficients squared for s (perpendicular) and p (parallel) polarisation.
struct PolarisedReflectance {
    float s = 1, p = 1;
    float unpolarised() const { return 0.5f * (s + p); }
};

// Exact Fresnel equations for a dielectric. `cos_i` < 0 means the light arrives from the other
// side, which is handled by inverting eta. Total internal reflection gives s = p = 1.
inline PolarisedReflectance fresnel_dielectric_polarised(float cos_i, float eta) {
    cos_i = std::clamp(cos_i, -1.0f, 1.0f);
    if (cos_i < 0) {
        eta = 1 / eta;
        cos_i = -cos_i;
    }
    const float sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return {1, 1};
    const float cos_t = std::sqrt(std::max(0.0f, 1 - sin2_t));
    const float r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return {r_perp * r_perp, r_par * r_par};
}

// Unpolarised dielectric reflectance (the mean of the s and p reflectances).
inline float fresnel_dielectric(float cos_i, float eta) {
    return fresnel_dielectric_polarised(cos_i, eta).unpolarised();
}

// Schlick's approximation R0 + (1 - R0)(1 - cos)^5. Leaving the denser medium it uses the cosine
// on the transmitted side (the larger angle), which keeps it close to the exact curve and gives
// total internal reflection past the critical angle.
inline float fresnel_schlick(float cos_i, float eta) {
    cos_i = std::clamp(cos_i, -1.0f, 1.0f);
    if (cos_i < 0) {
        eta = 1 / eta;
        cos_i = -cos_i;
    }
    const float r0 = ((eta - 1) / (eta + 1)) * ((eta - 1) / (eta + 1));
    float c = cos_i;
    if (eta < 1) {
        const float sin2_t = (1 - cos_i * cos_i) / (eta * eta);
        if (sin2_t >= 1) return 1;
        c = std::sqrt(1 - sin2_t);
    }
    const float m = 1 - c, m2 = m * m;
    return r0 + (1 - r0) * m2 * m2 * m;
}

// Unpolarised reflectance of a conductor with complex relative index eta + i k (light arrives
// from a dielectric, usually air). With k = 0 it reduces to fresnel_dielectric.
inline float fresnel_conductor(float cos_i, float eta, float k) {
    using C = std::complex<float>;
    cos_i = std::clamp(std::fabs(cos_i), 0.0f, 1.0f);
    const C n(eta, k);
    const float sin2_i = 1 - cos_i * cos_i;
    const C sin2_t = sin2_i / (n * n);
    const C cos_t = std::sqrt(C(1.0f) - sin2_t);
    const C r_par = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    const C r_perp = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    return 0.5f * (std::norm(r_par) + std::norm(r_perp));
}

inline Rgb fresnel_conductor(float cos_i, Rgb eta, Rgb k) {
    return {fresnel_conductor(cos_i, eta.r, k.r), fresnel_conductor(cos_i, eta.g, k.g),
            fresnel_conductor(cos_i, eta.b, k.b)};
}

// Total reflectance of a thin parallel sheet whose single interface reflects R: the geometric
// series of inter-reflections R + T^2 R / (1 - R^2) (transmission is 1 minus it, no absorption).
inline float thin_sheet_reflectance(float r) {
    if (r >= 1) return 1;
    const float t = 1 - r;
    return r + t * t * r / (1 - r * r);
}

}  // namespace phos::shading
