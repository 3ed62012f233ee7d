// The surface scattering model: one BSDF per hit, built from a scene::Material, made of up to five
// lobes (Lambert, modified-Phong glossy or ideal mirror, smooth or frosted dielectric, Lambertian
// transmission). eval/pdf cover the non-delta lobes; sample covers all of them. Directions are
// world-space unit vectors pointing away from the surface.
#pragma once

#include <cstdint>
#include <optional>

#include "accel/ray.h"
#include "core/frame.h"
#include "core/vec.h"
#include "scene/scene.h"

namespace phos::shading {

enum LobeFlags : uint32_t {
    kDiffuse = 1u << 0,
    kGlossy = 1u << 1,
    kSpecular = 1u << 2,  // delta distribution (mirror, smooth glass)
    kReflection = 1u << 3,
    kTransmission = 1u << 4,
};

// Radiance transport (camera paths) scales refracted radiance by 1/eta^2; importance / photon
// transport does not (photons carry flux).
enum class TransportMode { Radiance, Importance };

struct BsdfSample {
    Vec3 wi;
    Rgb f;            // BSDF value (for delta lobes: the delta's coefficient divided by |cos|)
    float pdf = 0;    // solid-angle pdf of choosing wi, including the lobe-selection probability
    uint32_t flags = 0;  // the sampled lobe's LobeFlags
    float eta = 1;    // relative index of refraction crossed (1 unless refracted)
    // Throughput multiplier f * |cos(wi, ns)| / pdf.
    Rgb weight;
    bool is_specular() const { return flags & kSpecular; }
};

struct BsdfOptions {
    bool schlick = false;  // Schlick's approximation instead of exact dielectric Fresnel
};

class Bsdf {
public:
    // Builds the BSDF of `material` at `hit` (textures looked up in `scene`).
    Bsdf(const scene::Material& material, const accel::SurfaceHit& hit, const scene::Scene& scene,
         const BsdfOptions& options = {});

    Rgb eval(Vec3 wo, Vec3 wi, TransportMode mode = TransportMode::Radiance) const;
    float pdf(Vec3 wo, Vec3 wi) const;
    // `u_lobe` picks the lobe, `u` the direction within it.
    std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u,
                                     TransportMode mode = TransportMode::Radiance) const;

    // Union of the LobeFlags of all lobes present.
    uint32_t flags() const { return flags_; }
    bool has_non_specular() const { return flags_ & (kDiffuse | kGlossy); }
    bool is_purely_specular() const { return flags_ != 0 && !has_non_specular(); }
    // Lambertian reflectance at this point (texture applied): what the photon map's estimate uses.
    Rgb diffuse_albedo() const { return kd_; }
    // Directional albedo of each lobe kind for wo (probabilities for the photon tracer's Russian
    // roulette): diffuse reflection+transmission, glossy, specular reflection, specular/frosted
    // transmission. Each is an RGB reflectance <= 1 for a physical material.
    struct LobeAlbedos {
        Rgb diffuse, glossy, specular, transmission;
    };
    LobeAlbedos lobe_albedos(Vec3 wo) const;
    // Samples only the lobes whose flags intersect `lobe_mask` (used after Russian roulette).
    std::optional<BsdfSample> sample_lobes(uint32_t lobe_mask, Vec3 wo, float u_lobe, Vec2 u,
                                           TransportMode mode = TransportMode::Radiance) const;
    const Frame& frame() const { return frame_; }
    Vec3 geometric_normal() const { return ng_; }

private:
    Frame frame_;  // shading frame (n = shading normal)
    Vec3 ng_;
    uint32_t flags_ = 0;
    Rgb kd_, ks_, kt_, kdt_;
    float shininess_ = 0, t_shininess_ = 0;
    bool mirror_ = false, sharp_glass_ = false, thin_ = false, conductor_ = false;
    Rgb cond_eta_, cond_k_;
    float ior_ = 1;
    bool schlick_ = false;
};

}  // namespace phos::shading
