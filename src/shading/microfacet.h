// Microfacet normal distributions: Trowbridge-Reitz (GGX), isotropic or anisotropic (roughness
// alpha_x along the shading frame's x = dpdu, alpha_y along y), and isotropic Beckmann: D, Smith
// masking (height-correlated G), and sampling of microfacet normals with its density. All vectors
// are in the local shading frame (z = macro normal). Used by the frosted / rough dielectric and the
// rough conductor (bsdf.h).
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
        : model_(model), alpha_(std::max(alpha, 1e-3f)), alpha_y_(alpha_) {}
    // Anisotropic Trowbridge-Reitz (pbrt-v4's TrowbridgeReitzDistribution; Heitz 2014, eq. 85 for
    // D and eq. 86 for Lambda).
    MicrofacetDistribution(float alpha_x, float alpha_y)
        : model_(MicrofacetModel::GGX),
          alpha_(std::max(alpha_x, 1e-3f)),
          alpha_y_(std::max(alpha_y, 1e-3f)) {}

    // Roughness equivalent to a Phong exponent n (Walter et al. 2007: alpha_b = sqrt(2/(n+2)));
    // used for GGX as well, as the .scn format only gives the Phong exponent.
    static float alpha_from_phong(float n) { return std::sqrt(2 / (std::max(n, 0.0f) + 2)); }

    MicrofacetModel model() const { return model_; }
    // The roughness along x and y, and the isotropic roughness of the same lobe solid angle
    // (sqrt(alpha_x alpha_y)): what sharpness tests compare with a Phong exponent's alpha.
    float alpha_x() const { return alpha_; }
    float alpha_y() const { return alpha_y_; }
    float alpha() const { return alpha_ == alpha_y_ ? alpha_ : std::sqrt(alpha_ * alpha_y_); }
    bool isotropic() const { return alpha_ == alpha_y_; }

    // Density of microfacet normals per unit projected area: integral of D(m) cos(m) dm = 1.
    float D(Vec3 m) const {
        const float c2 = m.z * m.z;
        if (c2 <= 0) return 0;
        if (model_ == MicrofacetModel::Beckmann && c2 < 1e-8f) return 0;  // exp(-tan^2 / a^2) = 0
        if (!isotropic() || c2 < 1e-8f) {
            // GGX in a form without cos^4 (which underflows at grazing normals):
            // cos^4 (1 + tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2))^2 = (z^2 + x^2/ax^2 + y^2/ay^2)^2.
            const float ex = m.x / alpha_, ey = m.y / alpha_y_, q = c2 + ex * ex + ey * ey;
            return 1 / (kPi * alpha_ * alpha_y_ * q * q);
        }
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
        if (!isotropic()) {
            const float at2 = (w.x * w.x * alpha_ * alpha_ + w.y * w.y * alpha_y_ * alpha_y_) / c2;
            return 0.5f * (std::sqrt(1 + at2) - 1);
        }
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
        const Vec3 wh = normalize(Vec3(alpha_ * wo.x, alpha_y_ * wo.y, wo.z));
        const Vec3 t1 = wh.z < 0.99999f ? normalize(cross(Vec3(0, 0, 1), wh)) : Vec3(1, 0, 0);
        const Vec3 t2 = cross(wh, t1);
        const float r = std::sqrt(u.x), phi = 2 * kPi * u.y;
        float px = r * std::cos(phi), py = r * std::sin(phi);
        const float h = std::sqrt(std::max(0.0f, 1 - px * px));
        const float s = 0.5f * (1 + wh.z);
        py = (1 - s) * h + s * py;
        const float pz = std::sqrt(std::max(0.0f, 1 - px * px - py * py));
        const Vec3 nh = t1 * px + t2 * py + wh * pz;
        return normalize(Vec3(alpha_ * nh.x, alpha_y_ * nh.y, std::max(1e-6f, nh.z)));
    }
    // Density of sample_wm's result m (per solid angle of m).
    float pdf_wm(Vec3 wo, Vec3 m) const {
        if (model_ == MicrofacetModel::Beckmann) return D(m) * std::max(0.0f, m.z);
        if (wo.z <= 0) return 0;
        return G1(wo) / wo.z * D(m) * std::max(0.0f, dot(wo, m));
    }

private:
    MicrofacetModel model_ = MicrofacetModel::GGX;
    float alpha_ = 1;    // alpha_x (the only roughness of an isotropic distribution)
    float alpha_y_ = 1;  // alpha_y (Beckmann: always alpha_x)
};

}  // namespace phos::shading
