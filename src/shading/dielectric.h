// The dielectric boundary lobe of Bsdf, in the local shading frame: smooth (delta reflection and
// refraction, or a thin sheet) and frosted (Walter et al. 2007 microfacet reflection + refraction).
// Conventions: wo.z > 0 (the frame is flipped to wo's side) and eta = n(other side) / n(wo side).
#pragma once

#include <optional>

#include "core/vec.h"
#include "shading/bsdf.h"
#include "shading/microfacet.h"

namespace phos::shading::dielectric {

// Fresnel reflectance at cosine `cos_i` on the wo side, exact or Schlick.
float reflectance(float cos_i, float eta, bool schlick);

// Refracts `w` (pointing away, on the side of `n`, cos = dot(w, n) > 0) through a boundary with
// relative index eta; nullopt on total internal reflection.
std::optional<Vec3> refract(Vec3 w, Vec3 n, float eta);

struct DeltaSample {
    Vec3 wi;
    float coefficient = 0;  // the delta's scalar coefficient (F, or (1-F) [/eta^2]), times kt outside
    float prob = 0;         // probability of this branch (reflect vs transmit)
    bool transmitted = false;
    float eta = 1;  // relative index crossed (1 unless refracted)
};

// Smooth interface (or thin sheet): reflect with probability F, else refract (straight through
// for the thin sheet). `u` picks the branch.
std::optional<DeltaSample> sample_smooth(Vec3 wo, float eta, bool thin, bool schlick, float u,
                                         TransportMode mode);

// Frosted interface: value, density and sampling of reflection + transmission (scalar, without
// kt). eval/pdf return 0 for configurations the sampler never produces.
float rough_eval(const MicrofacetDistribution& dist, Vec3 wo, Vec3 wi, float eta, bool schlick,
                 TransportMode mode);
float rough_pdf(const MicrofacetDistribution& dist, Vec3 wo, Vec3 wi, float eta, bool schlick);
// `uc` picks reflection vs transmission (with probability F of the sampled microfacet), `u` the
// microfacet normal. Returns wi, or nullopt when the sampled direction is invalid.
std::optional<Vec3> rough_sample(const MicrofacetDistribution& dist, Vec3 wo, float eta, bool schlick,
                                 float uc, Vec2 u);

}  // namespace phos::shading::dielectric
