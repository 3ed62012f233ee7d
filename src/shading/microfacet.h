// Isotropic microfacet normal distributions (GGX / Trowbridge-Reitz and Beckmann) for the frosted
// dielectric: D, Smith masking (height-correlated G), and sampling of microfacet normals with its
// density. All vectors are in the local shading frame (z = macro normal).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/vec.h"

namespace phos::shading {

enum class MicrofacetModel { GGX, Beckmann };

class MicrofacetDistribution {
public:
    MicrofacetDistribution() = default;
    MicrofacetDistribution(MicrofacetModel model, float alpha)
        : model_(model), alpha_(std::max(alpha, 1e-3f)) {}

    // Roughness equivalent to a Phong exponent n (Walter et al. 2007: alpha_b = sqrt(2/(n+2)));
    // used for GGX as well, as the .scn format only gives the Phong exponent.
    static float alpha_from_phong(float n) { return std::sqrt(2 / (std::max(n, 0.0f) + 2)); }

    MicrofacetModel model() const { return model_; }
    float alpha() const { return alpha_; }

    // Density of microfacet normals per unit projected area: integral of D(m) cos(m) dm = 1.
    float D(Vec3 m) const {
        const float c2 = m.z * m.z;
        if (c2 <= 0) return 0;
        const float t2 = (1 - c2) / c2, a2 = alpha_ * alpha_;
        if (model_ == MicrofacetModel::Beckmann) return std::exp(-t2 / a2) / (kPi * a2 * c2 * c2);
        const float e = 1 + t2 / a2;
        return 1 / (kPi * a2 * c2 * c2 * e * e);
    }

    // Smith's auxiliary function Lambda(w) (masking G1 = 1 / (1 + Lambda)).
    float lambda(Vec3 w) const {
        const float c2 = w.z * w.z;
        if (c2 >= 1) return 0;
        if (c2 <= 0) return kInf;
        const float tan_t = std::sqrt((1 - c2) / c2);
        if (model_ == MicrofacetModel::GGX) {
            const float at = alpha_ * tan_t;
            return 0.5f * (std::sqrt(1 + at * at) - 1);
        }
        // Beckmann: Walter et al.'s rational approximation of the erf expression.
        const float a = 1 / (alpha_ * tan_t);
        if (a >= 1.6f) return 0;
        return (1 - 1.259f * a + 0.396f * a * a) / (3.535f * a + 2.181f * a * a);
    }
    float G1(Vec3 w) const { return 1 / (1 + lambda(w)); }
    // Height-correlated masking-shadowing.
    float G(Vec3 wo, Vec3 wi) const { return 1 / (1 + lambda(wo) + lambda(wi)); }

    // Samples a microfacet normal (m.z > 0) for an outgoing direction with wo.z > 0. GGX samples
    // the visible normals (Heitz 2018), Beckmann the plain D(m) cos(m) distribution.
    Vec3 sample_wm(Vec3 wo, Vec2 u) const {
        if (model_ == MicrofacetModel::Beckmann) {
            const float t2 = -alpha_ * alpha_ * std::log(std::max(1 - u.x, 1e-12f));
            const float cz = 1 / std::sqrt(1 + t2);
            const float r = std::sqrt(std::max(0.0f, 1 - cz * cz));
            const float phi = 2 * kPi * u.y;
            return {r * std::cos(phi), r * std::sin(phi), cz};
        }
        // Stretch wo to the unit-roughness configuration, sample the projected hemisphere there.
        const Vec3 wh = normalize(Vec3(alpha_ * wo.x, alpha_ * wo.y, wo.z));
        const Vec3 t1 = wh.z < 0.99999f ? normalize(cross(Vec3(0, 0, 1), wh)) : Vec3(1, 0, 0);
        const Vec3 t2 = cross(wh, t1);
        const float r = std::sqrt(u.x), phi = 2 * kPi * u.y;
        float px = r * std::cos(phi), py = r * std::sin(phi);
        const float h = std::sqrt(std::max(0.0f, 1 - px * px));
        const float s = 0.5f * (1 + wh.z);
        py = (1 - s) * h + s * py;
        const float pz = std::sqrt(std::max(0.0f, 1 - px * px - py * py));
        const Vec3 nh = t1 * px + t2 * py + wh * pz;
        return normalize(Vec3(alpha_ * nh.x, alpha_ * nh.y, std::max(1e-6f, nh.z)));
    }
    // Density of sample_wm's result m (per solid angle of m).
    float pdf_wm(Vec3 wo, Vec3 m) const {
        if (model_ == MicrofacetModel::Beckmann) return D(m) * std::max(0.0f, m.z);
        if (wo.z <= 0) return 0;
        return G1(wo) / wo.z * D(m) * std::max(0.0f, dot(wo, m));
    }

private:
    MicrofacetModel model_ = MicrofacetModel::GGX;
    float alpha_ = 1;
};

}  // namespace phos::shading
