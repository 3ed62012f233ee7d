// The surface scattering model: one BSDF per hit, built from a scene::Material, made of up to five
// lobes (Lambert; modified-Phong glossy, Trowbridge-Reitz microfacet reflection or ideal mirror;
// smooth or rough dielectric; Lambertian transmission), or of pbrt's layered material's two parts
// (layered_bxdf.h), or of one measured BRDF (measured_bxdf.h) or one hair fibre BSDF
// (hair_bxdf.h, which scatters to both sides: reflection or transmission by the geometric normal
// as below). eval/pdf cover the non-delta lobes; sample covers all of them. Directions are
// world-space unit vectors pointing away from the surface.
//
// Conventions (precise):
// - Sides. Reflection lobes (Lambert, Phong, mirror) are two-sided: they reflect on whichever side
//   of the surface wo is. The dielectric is oriented: wo on the side ng points to is outside, and
//   refraction goes from index 1 to `ior` (eta = ior) when entering, 1/ior when leaving.
// - Light leaks. A pair (wo, wi) on the same side of the GEOMETRIC normal ng only gets reflection,
//   a pair on opposite sides only transmission; eval and pdf are 0 otherwise and sample rejects
//   such directions (returns nullopt), so sample's density is exactly pdf().
// - Lobe selection. sample() picks one lobe with probability proportional to its average-channel
//   albedo estimate at wo (the LobeAlbedos below, per lobe), samples wi from it, and for a
//   non-delta wi returns f = eval(wo, wi) (all non-delta lobes) and pdf = pdf(wo, wi) = the sum of
//   selection probability x lobe pdf over the non-delta lobes. Below-surface Phong samples are
//   rejected without renormalising, so pdf() integrates to < 1 there.
// - Delta lobes (mirror, smooth or thin dielectric): pdf = selection probability x branch
//   probability (F or 1-F for the dielectric), f = coefficient / |cos(wi, ns)|, so that
//   weight = f |cos| / pdf = coefficient / pdf. For the exact-Fresnel dielectric the branch is
//   chosen with its own probability, so weight = kt / selection (x 1/eta^2 when refracting in
//   Radiance mode). Delta lobes never appear in eval() or pdf().
#pragma once

#include <cstdint>
#include <optional>

#include "accel/ray.h"
#include "core/frame.h"
#include "core/vec.h"
#include "scene/camera_footprint.h"
#include "scene/scene.h"
#include "shading/hair_bxdf.h"
#include "shading/layered_bxdf.h"
#include "shading/measured_bxdf.h"
#include "shading/microfacet.h"
#include "spectrum/distribution.h"
#include "spectrum/rgb_spectrum.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::shading {

enum LobeFlags : uint32_t {
    kDiffuse = 1u << 0,
    kGlossy = 1u << 1,
    kSpecular = 1u << 2,  // delta distribution (mirror, smooth glass)
    kReflection = 1u << 3,
    kTransmission = 1u << 4,
    // On a sample (never in flags()): drawn from a lobe that Bsdf::regularized widened from a delta
    // lobe (a mirror or smooth glass), so a path's classification can still count it as specular.
    kWidened = 1u << 5,
};

// Spectra. A BSDF's values are spectral: eval and sample take the path's wavelengths and return its
// values there (the material's RGB colours upsampled, rgb_spectrum.h; measured conductor η, k and
// dispersive indices where the material gives them). Everything that chooses (lobe selection,
// pdfs, the albedos for Russian roulette and lobe splits) reads the RGB colours and does not
// depend on the wavelengths, so pdf() has no wavelength argument. A smooth dispersive dielectric
// bends each wavelength its own way: sample() refracts and reflects with the hero wavelength's
// index and marks the sample `dispersive` (the caller terminates the secondary wavelengths); a
// frosted one samples with the index at the d line and evaluates each wavelength with its own.
//
// Radiance transport (camera paths) scales refracted radiance by 1/eta^2; importance / photon
// transport does not (photons carry flux).
enum class TransportMode { Radiance, Importance };

struct BsdfSample {
    Vec3 wi;
    Spectrum f;          // BSDF value (for delta lobes: the delta's coefficient divided by |cos|)
    float pdf = 0;       // solid-angle pdf of choosing wi, including the lobe-selection probability
    uint32_t flags = 0;  // the sampled lobe's LobeFlags
    float eta = 1;       // relative index of refraction crossed (1 unless refracted)
    // Throughput multiplier f * |cos(wi, ns)| / pdf (for delta lobes: coefficient / pdf).
    Spectrum weight;
    // Drawn from a smooth dispersive dielectric with the hero wavelength's index: only the hero's
    // values are meaningful, and the path must terminate its secondary wavelengths.
    bool dispersive = false;
    bool is_specular() const { return flags & kSpecular; }
};

struct BsdfOptions {
    bool schlick = false;  // Schlick's approximation instead of exact dielectric Fresnel
    // Microfacet distribution of the frosted dielectric; alpha = sqrt(2 / (n + 2)) from its
    // Phong exponent n (Material::transmission_shininess).
    MicrofacetModel microfacet = MicrofacetModel::GGX;
    // The camera footprint filtered image textures read (scene/camera_footprint.h), or null:
    // textures looked up without derivatives. Must outlive the BSDFs built with these options.
    const scene::CameraFootprint* texture_footprint = nullptr;
};

// A lone Lambert reflection lobe placed at a hit (f = kd / pi on the side of ng that wo is on): all
// that sampling a BSDF made of it alone reads. MaterialBsdfs::lambert_at gives it without building
// the whole BSDF (the photon tracer's commonest surface), and such a Bsdf samples its lobe through the
// same function (bsdf.cpp's sample_lambert), so the two agree to the bit.
struct LambertLobe {
    Frame frame;  // shading frame
    Vec3 ng;
    Rgb kd;  // its colour (what selection reads)
    spectrum::RgbSpectrum kd_spectrum;
    // Bsdf::sample_lobes(kDiffuse, wo, u_lobe, u, lambda, mode) of a BSDF of this lobe alone
    // (which reads neither u_lobe nor mode).
    std::optional<BsdfSample> sample(Vec3 wo, Vec2 u, const Wavelengths& lambda) const;
};

class Bsdf {
public:
    // Builds the BSDF of `material` at `hit` (textures looked up in `scene`). The shading frame is
    // ns with dpdu made orthogonal to it (Gram-Schmidt) when dpdu is usable: shading_frame() of
    // core/frame.h, or hit.shading where the accelerator keeps it. A material with no
    // non-black lobe gets a black Lambert lobe, so it is opaque (flags() != 0); only
    // `interface_only` materials have flags() == 0 and scatter nothing. A thin dielectric is always
    // smooth, as is a dielectric with ior == 1 (there is nothing to bend light).
    Bsdf(const scene::Material& material, const accel::SurfaceHit& hit, const scene::Scene& scene,
         const BsdfOptions& options = {});
    // The same object in two steps, for callers that build many BSDFs of few materials
    // (MaterialBsdfs): of_material() is the part that depends on the material and the options
    // only, built once; placed() completes a copy of it at a hit (shading frame, textures).
    // of_material(m, options).placed(m, hit, scene) equals Bsdf(m, hit, scene, options) bit for bit.
    static Bsdf of_material(const scene::Material& material, const BsdfOptions& options);
    Bsdf placed(const scene::Material& material, const accel::SurfaceHit& hit,
                const scene::Scene& scene) const;
    // For a material's BSDF (of_material) that is_lambertian(): the lobe that placed(material, hit,
    // scene) would hold.
    void place_lambert(const scene::Material& material, const accel::SurfaceHit& hit,
                       const scene::Scene& scene, LambertLobe& lobe) const;
    // A BSDF refers to its material's measured spectra (conductor η, k; a dispersive index) by
    // pointer; a copy made in another process (an MPI rank's visible points, copied as bytes)
    // points at them again with rebind(its material).
    void rebind(const scene::Material& material);

    Spectrum eval(Vec3 wo, Vec3 wi, const Wavelengths& lambda,
                  TransportMode mode = TransportMode::Radiance) const;
    float pdf(Vec3 wo, Vec3 wi) const;
    // eval(wo, wi, mode), pdf(wo, wi) and pdf(wi, wo) at once, as bidirectional methods need them:
    // the same values as the three calls, with a short path for a lone Lambert lobe.
    struct Evaluation {
        Spectrum f;
        float pdf = 0, pdf_rev = 0;
    };
    Evaluation evaluate(Vec3 wo, Vec3 wi, const Wavelengths& lambda,
                        TransportMode mode = TransportMode::Radiance) const;
    // `u_lobe` picks the lobe, `u` the direction within it.
    std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u, const Wavelengths& lambda,
                                     TransportMode mode = TransportMode::Radiance) const;

    // Union of the LobeFlags of all lobes present. Lambert: kDiffuse|kReflection; Phong and
    // microfacet reflection: kGlossy|kReflection; mirror: kSpecular|kReflection; smooth dielectric:
    // kSpecular|kReflection| kTransmission; frosted: kGlossy|kReflection|kTransmission; Lambertian
    // transmission: kDiffuse|kTransmission. A BsdfSample's flags name the branch taken (reflection or
    // transmission, not both).
    uint32_t flags() const { return flags_; }
    bool has_non_specular() const { return flags_ & (kDiffuse | kGlossy); }
    bool is_purely_specular() const { return flags_ != 0 && !has_non_specular(); }
    // True if the BSDF is a single Lambert reflection lobe (f = kd / pi on wo's side): estimates and
    // gathering take fast paths that skip per-direction BSDF evaluation.
    bool is_lambertian() const { return flags_ == (kDiffuse | kReflection); }
    // Lambertian reflectance at this point (texture applied): what the photon map's estimate uses,
    // at `lambda`, and its colour.
    Spectrum diffuse_albedo(const Wavelengths& lambda) const { return kd_s_.sample(lambda); }
    const spectrum::RgbSpectrum& diffuse_spectrum() const { return kd_s_; }
    Rgb diffuse_colour() const { return kd_; }
    // True when a smooth or frosted dielectric lobe has a wavelength-dependent index.
    bool dispersive() const;
    // Directional albedo of each lobe kind for wo (probabilities for the photon tracer's Russian
    // roulette): diffuse = kd + kdt (Lambert reflection and transmission), glossy = Phong ks
    // (x conductor Fresnel at wo), specular = mirror reflectance at wo (ks, x conductor Fresnel),
    // transmission = kt of the dielectric, smooth or frosted (its Fresnel reflection included:
    // sample splits kt between reflection and refraction itself). Each is an RGB reflectance <= 1
    // for a physical material; 0 for absent lobes.
    struct LobeAlbedos {
        Rgb diffuse, glossy, specular, transmission;
    };
    LobeAlbedos lobe_albedos(Vec3 wo) const;
    // Samples only the lobes of the kinds in `lobe_mask` (used after Russian roulette). The mask is
    // read as a set of LobeAlbedos kinds written with LobeFlags bits: kDiffuse = Lambert reflection
    // and Lambertian transmission, kGlossy = Phong, kSpecular = mirror, kTransmission = the whole
    // dielectric (smooth or frosted, its reflection and refraction); kReflection is ignored. So
    // flags() (or ~0u) selects every lobe and sample() == sample_lobes(~0u, ...). Lobes are
    // selected among the masked ones only (probabilities renormalised over the mask), and f, pdf
    // and weight are those of the masked lobes alone: for a single-lobe mask the weight is that
    // lobe's own f |cos| / pdf (e.g. kd for Lambert, kt for exact-Fresnel glass), which the
    // photon tracer divides by its Russian-roulette probability.
    std::optional<BsdfSample> sample_lobes(uint32_t lobe_mask, Vec3 wo, float u_lobe, Vec2 u,
                                           const Wavelengths& lambda,
                                           TransportMode mode = TransportMode::Radiance) const;
    // The lobes split into those camera paths follow by ray tracing and those the photon estimates,
    // visible points and final gathering handle (Jensen 2001, sec. 9.1: f_r = f_r,S + f_r,D), both
    // as sample_lobes masks. Followed: the delta lobes (mirror, smooth or thin glass) and the glossy
    // lobes at least as sharp as a modified-Phong lobe of exponent `sharp_exponent` (sharp_lobes);
    // estimated: the rest (Lambert, Lambertian transmission, wider glossy lobes). A photon estimate
    // of a sharp lobe reads the few photons that happen to arrive inside it, so it is made of
    // fireflies; ray tracing it is cheap and exact. With the default (infinite) exponent only delta
    // lobes are followed. `p_estimated` is the probability of choosing the estimated part at a
    // vertex that takes one of the two: 0 without estimated lobes, 1 without followed ones, else
    // the estimated share of the lobes' average albedos at wo.
    struct LobeSplit {
        uint32_t followed = 0, estimated = 0;
        float p_estimated = 1;
    };
    LobeSplit split_lobes(Vec3 wo, float sharp_exponent = kInf) const;
    // The glossy lobes at least as sharp as a modified-Phong lobe of exponent `sharp_exponent`, as
    // a sample_lobes mask: kGlossy for a Phong lobe of that exponent or more, kTransmission for a
    // frosted dielectric of that Phong-equivalent exponent or more (alpha <= sqrt(2 / (n + 2))).
    uint32_t sharp_lobes(float sharp_exponent) const;
    // Whether split_lobes(wo, sharp_exponent).estimated / .followed is non-empty (for any wo):
    // where photons are worth storing, and whether a caustic path can go on.
    bool has_estimated(float sharp_exponent) const;
    bool has_followed(float sharp_exponent) const;
    // This BSDF with only the lobes of the kinds in `lobe_mask` (a sample_lobes mask): eval, pdf,
    // sample and the albedos then cover those lobes alone (selection renormalised over them), so
    // estimates, light sampling and gathering can be restricted to one part of a LobeSplit. A mask
    // covering every lobe gives this BSDF unchanged.
    Bsdf only(uint32_t lobe_mask) const;
    // This BSDF mollified for path regularisation (Kaplanyan & Dachsbacher 2013): every lobe
    // sharper than a modified-Phong lobe of exponent `max_exponent` is widened to it. A Phong lobe's
    // exponent is clamped; a mirror becomes a lobe sampled as a Phong lobe of that exponent whose
    // value is that density over cos theta_i (so it reflects the mirror's ks, with its Fresnel, at
    // every incidence); smooth and frosted glass become frosted glass of alpha = sqrt(2 /
    // (max_exponent + 2)). Thin glass and
    // an index of 1 (straight through, no lobe to widen) are kept. As max_exponent grows the result
    // tends to this BSDF, so an estimator that widens by a schedule growing with the samples converges
    // to the same image.
    Bsdf regularized(float max_exponent) const;
    // True if every lobe of this BSDF was widened from a delta lobe by regularized(): light found
    // through it is, for the --layers split, light through a mirror or glass.
    bool only_widened() const;
    const Frame& frame() const { return frame_; }
    Vec3 geometric_normal() const { return ng_; }

private:
    Frame frame_;  // shading frame (n = shading normal)
    Vec3 ng_;
    uint32_t flags_ = 0;
    Rgb kd_, ks_, kt_, kdt_;                            // the colours (selection, albedos)
    spectrum::RgbSpectrum kd_s_, ks_s_, kt_s_, kdt_s_;  // and their spectra
    // Phong exponents; for microfacet lobes the exponent of the same sharpness, 2 / alpha^2 - 2 with
    // alpha = MicrofacetDistribution::alpha() (what sharp_lobes and regularized compare).
    float shininess_ = 0, t_shininess_ = 0;
    bool mirror_ = false, sharp_glass_ = false, thin_ = false, conductor_ = false;
    bool widened_mirror_ = false, widened_glass_ = false;  // regularized(): from delta lobes
    Rgb cond_eta_, cond_k_;
    spectrum::RgbSpectrum cond_eta_s_, cond_k_s_;  // RGB-given η, k as spectra
    // Measured η, k and a dispersive index: the material's (which outlives its BSDFs); null when
    // not given.
    const spectrum::Distribution *cond_eta_spectrum_ = nullptr, *cond_k_spectrum_ = nullptr;
    const spectrum::Distribution* ior_spectrum_ = nullptr;
    float ior_ = 1;  // the index (at the d line when dispersive)
    bool schlick_ = false;
    MicrofacetModel microfacet_ = MicrofacetModel::GGX;  // BsdfOptions::microfacet
    const scene::CameraFootprint* footprint_ = nullptr;  // BsdfOptions::texture_footprint
    uint32_t lobes_ = 0;                // bit i set when lobe i (bsdf.cpp's Lobe enum) is present
    MicrofacetDistribution dist_;       // the rough dielectric's
    MicrofacetDistribution spec_dist_;  // the microfacet reflection lobe's
    bool pbrt_microfacet_ = false;      // Material::microfacet (roughness as alphas, not exponents)
    bool cond_from_refl_ = false;       // Material::conductor_from_reflectance
    // pbrt's coateddiffuse / coatedconductor: its two parts are lobes kCoat and kWalk (bsdf.cpp),
    // whose kinds the layered BSDF says (coat_kind, walk_kind).
    LayeredBxdf layered_;
    float layered_fi_ = 0;           // the coat's internal diffuse reflectance (walk selection)
    float layered_base_albedo_ = 0;  // the base's average albedo (walk selection)
    float coat_shininess_ = 0, walk_shininess_ = 0;  // Phong-equivalent sharpness of each part
    // pbrt's measured and hair materials: lobes kMeasured and kHair (bsdf.cpp), each the material's
    // only lobe, with the Phong-equivalent sharpness of each (what sharp_lobes compares).
    MeasuredBxdf measured_;
    HairBxdf hair_;
    float measured_shininess_ = 0, hair_shininess_ = 0;

    Bsdf() = default;
    // The constructor's three steps: the frame at the hit, the material's lobes, its textures.
    void place(const accel::SurfaceHit& hit);
    void set_material(const scene::Material& m, const BsdfOptions& options);
    void set_flags();  // flags_ from lobes_
    // split_lobes' two masks, which do not depend on wo.
    void part_masks(float sharp_exponent, uint32_t& followed, uint32_t& estimated) const;
    void apply_textures(const scene::Material& m, const accel::SurfaceHit& hit, const scene::Scene& scene);
    Rgb specular_reflectance(float cos_o) const;
    Spectrum specular_reflectance(float cos_o, const Wavelengths& lambda) const;
    void selection_weights(Vec3 wo_local, uint32_t mask, float w[]) const;
    // The specular and dielectric lobes of a microfacet material for alphas (ax, ay): delta when
    // both are below 1e-3, else microfacet lobes of that distribution.
    void set_microfacet_lobes(float ax, float ay);
    // The layered lobes of material m (set_material) and at a hit (textured reflectance or
    // roughness); `scene`/`hit` null for the untextured values.
    void set_layered(const scene::Material& m, const scene::Scene* scene, const accel::SurfaceHit* hit);
    // The LobeAlbedos kind of lobe i (fixed, except the layered parts').
    uint32_t kind_of(int lobe) const;
    Spectrum eval_masked(Vec3 wo, Vec3 wi, uint32_t mask, const Wavelengths& lambda,
                         TransportMode mode) const;
    float pdf_masked(Vec3 wo, Vec3 wi, uint32_t mask) const;
    Spectrum eval_local(Vec3 wo_l, Vec3 wi, float side, uint32_t mask, const Wavelengths& lambda,
                        TransportMode mode) const;
    float pdf_local(Vec3 wo_l, Vec3 wi, float side, const float w[]) const;
};

}  // namespace phos::shading
