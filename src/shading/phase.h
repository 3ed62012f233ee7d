// The Henyey-Greenstein phase function (Henyey & Greenstein 1941): evaluation and exact importance
// sampling (pbrt-v4, sec. 11.3.1). Directions follow the BSDF convention: wo points back along the
// incoming path (towards the camera or the photon's origin) and wi away from the scattering point,
// so the scattering angle theta is between -wo and wi.
#pragma once

#include <cmath>

#include "core/frame.h"
#include "core/vec.h"

namespace phos::shading {

// p(cos theta) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos theta)^(3/2)); g > 0 scatters forwards. It
// integrates to 1 over the sphere and is its own sampling pdf.
inline float henyey_greenstein(float cos_theta, float g) {
    const float denom = 1 + g * g - 2 * g * cos_theta;
    return (1 - g * g) / (4 * kPi * denom * std::sqrt(std::fmax(denom, 1e-12f)));
}

struct PhaseFunction {
    float g = 0;

    // Value (= pdf) for the pair (wo, wi).
    float eval(Vec3 wo, Vec3 wi) const { return henyey_greenstein(dot(-wo, wi), g); }
    // Samples wi given wo; returns the pdf (= the value, so the sample's weight is exactly 1).
    float sample(Vec3 wo, Vec2 u, Vec3& wi) const {
        // Invert the HG cdf for cos theta (measured from the forward direction -wo).
        float cos_theta;
        if (std::fabs(g) < 1e-3f) {
            cos_theta = 1 - 2 * u.x;
        } else {
            const float sq = (1 - g * g) / (1 + g - 2 * g * u.x);
            cos_theta = (1 + g * g - sq * sq) / (2 * g);
        }
        cos_theta = std::fmin(std::fmax(cos_theta, -1.0f), 1.0f);
        const float sin_theta = std::sqrt(std::fmax(0.0f, 1 - cos_theta * cos_theta));
        const float phi = 2 * kPi * u.y;
        const Frame frame(-wo);
        wi = frame.to_world(Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
        return henyey_greenstein(cos_theta, g);
    }
};

}  // namespace phos::shading
