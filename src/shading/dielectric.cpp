// Smooth and frosted dielectric lobes (see dielectric.h). The frosted model follows Walter et al.
// 2007, "Microfacet Models for Refraction through Rough Surfaces", with the generalised half vector
// and the Jacobians of its eqs. 14 and 17; the microfacet normal is sampled by visible normals.
#include "shading/dielectric.h"

#include <cmath>

#include "shading/fresnel.h"

namespace phos::shading::dielectric {
namespace {

// The (generalised) half vector of wo and wi, facing +z; nullopt when degenerate or when either
// direction sees the back of the microfacet (those pairs carry no energy in this model).
struct HalfVector {
    Vec3 wm;
    bool reflect;
    float etap;  // 1 for reflection, eta for transmission
};
std::optional<HalfVector> half_vector(Vec3 wo, Vec3 wi, float eta) {
    if (wo.z <= 0 || wi.z == 0) return std::nullopt;
    const bool reflect = wi.z > 0;
    const float etap = reflect ? 1 : eta;
    Vec3 wm = wi * etap + wo;
    const float len2 = length_squared(wm);
    if (!(len2 > 1e-14f)) return std::nullopt;
    wm = wm / std::sqrt(len2);
    if (wm.z < 0) wm = -wm;
    if (dot(wm, wi) * wi.z < 0 || dot(wm, wo) * wo.z < 0) return std::nullopt;
    return HalfVector{wm, reflect, etap};
}

}  // namespace

std::optional<Vec3> refract(Vec3 w, Vec3 n, float eta) {
    const float cos_i = dot(w, n);
    const float sin2_t = std::max(0.0f, 1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return std::nullopt;
    const float cos_t = std::sqrt(1 - sin2_t);
    return -w / eta + n * (cos_i / eta - cos_t);
}

float reflectance(float cos_i, float eta, bool schlick) {
    return schlick ? fresnel_schlick(cos_i, eta) : fresnel_dielectric(cos_i, eta);
}

std::optional<DeltaSample> sample_smooth(Vec3 wo, float eta, bool thin, bool schlick, float u,
                                         TransportMode mode) {
    if (wo.z <= 0) return std::nullopt;
    float r = reflectance(wo.z, eta, schlick);
    if (thin) r = thin_sheet_reflectance(r);
    const float t = 1 - r;
    DeltaSample ds;
    if (u < r || t <= 0) {
        ds.wi = Vec3(-wo.x, -wo.y, wo.z);
        ds.coefficient = r;
        ds.prob = r;
        return ds;
    }
    ds.transmitted = true;
    ds.prob = t;
    ds.coefficient = t;
    if (thin) {
        // Both faces bend the ray by opposite amounts: it leaves parallel to how it came in.
        ds.wi = -wo;
        return ds;
    }
    const auto wi = refract(wo, Vec3(0, 0, 1), eta);
    if (!wi) return std::nullopt;  // only reachable through rounding, as F = 1 under TIR
    ds.wi = *wi;
    ds.eta = eta;
    if (mode == TransportMode::Radiance) ds.coefficient /= eta * eta;
    return ds;
}

float rough_eval(const MicrofacetDistribution& dist, Vec3 wo, Vec3 wi, float eta, bool schlick,
                 TransportMode mode) {
    const auto h = half_vector(wo, wi, eta);
    if (!h) return 0;
    const Vec3 wm = h->wm;
    const float f = reflectance(dot(wo, wm), eta, schlick);
    const float dg = dist.D(wm) * dist.G(wo, wi);
    if (h->reflect) return dg * f / (4 * wi.z * wo.z);
    const float denom_sqrt = dot(wi, wm) + dot(wo, wm) / h->etap;
    const float denom = denom_sqrt * denom_sqrt * wi.z * wo.z;
    float ft = dg * (1 - f) * std::fabs(dot(wi, wm) * dot(wo, wm) / denom);
    if (mode == TransportMode::Radiance) ft /= h->etap * h->etap;
    return ft;
}

float rough_pdf(const MicrofacetDistribution& dist, Vec3 wo, Vec3 wi, float eta, bool schlick) {
    const auto h = half_vector(wo, wi, eta);
    if (!h) return 0;
    const Vec3 wm = h->wm;
    const float r = reflectance(dot(wo, wm), eta, schlick);
    const float pdf_wm = dist.pdf_wm(wo, wm);
    if (h->reflect) return pdf_wm / (4 * std::fabs(dot(wo, wm))) * r;
    const float denom_sqrt = dot(wi, wm) + dot(wo, wm) / h->etap;
    return pdf_wm * std::fabs(dot(wi, wm)) / (denom_sqrt * denom_sqrt) * (1 - r);
}

std::optional<Vec3> rough_sample(const MicrofacetDistribution& dist, Vec3 wo, float eta, bool schlick,
                                 float uc, Vec2 u) {
    if (wo.z <= 0) return std::nullopt;
    const Vec3 wm = dist.sample_wm(wo, u);
    const float cos_om = dot(wo, wm);
    if (cos_om <= 0) return std::nullopt;  // Beckmann samples D cos, which includes hidden normals
    const float r = reflectance(cos_om, eta, schlick);
    if (uc < r) {
        const Vec3 wi = wm * (2 * cos_om) - wo;
        if (wi.z <= 0) return std::nullopt;
        return wi;
    }
    const auto wi = refract(wo, wm, eta);
    if (!wi || wi->z >= 0) return std::nullopt;
    return wi;
}

}  // namespace phos::shading::dielectric
