// pbrt-v4's layered BSDF (Pharr, Jakob & Humphreys, "Physically Based Rendering", 4th ed., sec. 14.3
// "Scattering from Layered Materials"; Guo, Hasan, Zhao 2018, "Position-Free Monte Carlo
// Simulation for Arbitrary Layered BSDFs"): a dielectric interface (the coat, smooth or
// Trowbridge-Reitz rough) over a base that only reflects (a Lambertian diffuse base: pbrt's
// `coateddiffuse`; a smooth or rough conductor: `coatedconductor`), separated by a slab of
// `thickness` that may hold a homogeneous medium (unit extinction, single-scattering `albedo`,
// Henyey-Greenstein `g`). Nothing of it is tabulated: f(), pdf() and sample() each run a
// stochastic random walk between the two interfaces (at most `max_depth` events, `n_samples`
// walks averaged), so f() and pdf() are unbiased / approximate *estimates*, not values.
//
// Conventions (local shading frame, z = normal; as pbrt-v4's twoSided LayeredBxDF):
// - Two-sided: a pair with wo.z < 0 is evaluated as (-wo, -wi), so light always enters through
//   the coat. Both bases are opaque, so f = 0 for wo and wi on opposite sides.
// - f(wo, wi): the coat's own reflection plus n_samples random walks (sec. 14.3.2): the walk enters
//   by a transmission sample of the coat at wo, the exit is connected by next-event estimation
//   through a transmission sample of the coat at wi (adjoint mode) from each base or medium
//   event, MIS-weighted (power heuristic) against the event's own scattering through the coat
//   towards wi; transmittance exp(-thickness/|cos|) between the interfaces; Russian roulette after
//   3 events when the throughput falls below 0.25. Both MIS weights use the densities of the same
//   inner direction: the base's (or phase function's) and that of the coat's transmission sample
//   at wi drawing it. (pbrt-v4 weights the second strategy with exitInterface.PDF(-w, wi), the
//   reverse transmission's density, so its weights do not sum to 1: its f is 5-8 % too high for a
//   coat of alpha 0.3, against both the sampled albedo and a brute-force simulation.) Its
//   expectation over the walks is the layered BSDF (reciprocal in Radiance mode).
// - sample(): one analog walk from wo (entrance reflection or transmission, scattering at the base,
//   the medium and the coat's underside until it leaves through the coat). Its `pdf` is the
//   product of the sampled densities along the walk: only proportional to the true density of wi
//   (pdf_is_proportional), so weight = f |cos wi| / pdf is the unbiased throughput, and MIS must
//   use pdf() and f() instead. The directions it draws do not depend on the wavelengths; its
//   Russian roulette reads the largest throughput over them (as pbrt-v4), so whether a walk
//   survives does: reading the hero's alone left a coloured base's other wavelengths carried by
//   rare walks boosted up to 20-fold (a saturated red coat rendered 4.5 % dark at 128 samples).
// - pdf(wo, wi): pbrt-v4's stochastic estimate (sec. 14.3.3): the coat's reflection density plus
//   the transmission-reflection-transmission term (MIS of the base's and the exiting coat's
//   densities when both are rough), mixed as 0.9 of it + 0.1 / (4 pi), so it is positive wherever
//   f can be. It approximates, not equals, sample()'s density; it does not depend on wavelengths.
// - Determinism: every random decision comes from a counter-based Sampler keyed by a hash of the
//   float bits of (wo, wi) for f and pdf, (wo, uc, u) for sample, and `seed` (pbrt-v4 hashes its
//   Options seed), so equal inputs give bit-identical results on any thread.
// - Flags as pbrt-v4's: kReflection, kSpecular when the coat is smooth, kDiffuse when the base is
//   diffuse or the slab scatters, else kGlossy when either interface is rough. A sample that left
//   after only delta events (a smooth coat over a smooth conductor, no medium) is kSpecular, any
//   other walk kGlossy, as pbrt-v4 marks them.
#pragma once

#include <cstdint>
#include <optional>

#include "core/vec.h"
#include "shading/microfacet.h"
#include "spectrum/distribution.h"
#include "spectrum/rgb_spectrum.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::shading {

// bsdf.h's transport mode, declared here without including bsdf.h (so that a Bsdf can hold a
// LayeredBxdf); Radiance, its first value, is the default below. Flags are bsdf.h's LobeFlags.
enum class TransportMode;

// A spectral parameter: an RGB value as a spectrum (rgb_spectrum.h), or a measured distribution
// (a named metal's eta or k), which the caller keeps alive (the material owns it).
struct LayeredSpectrum {
    spectrum::RgbSpectrum rgb;
    const spectrum::Distribution* measured = nullptr;
    Spectrum at(const Wavelengths& lambda) const {
        return measured ? measured->sample(lambda) : rgb.sample(lambda);
    }
};

// What pbrt-v4's CoatedDiffuseMaterial / CoatedConductorMaterial give the layered BxDF, with
// roughness already mapped to alphas (pbrt's remaproughness: alpha = sqrt(roughness)).
struct LayeredParams {
    // The coat: relative index eta (0 reads as 1, as pbrt-v4) and Trowbridge-Reitz alphas; smooth
    // when eta == 1 or both alphas are below 1e-3.
    float eta = 1.5f;
    float coat_alpha_x = 0, coat_alpha_y = 0;
    // The base: Lambertian of `reflectance` (clamped to [0, 1]), or a conductor.
    enum class Base { Diffuse, Conductor } base = Base::Diffuse;
    spectrum::RgbSpectrum reflectance;
    // Conductor: eta + i k relative to the outside (as the material gives them; divided by the
    // coat's eta here, as pbrt-v4's CoatedConductorMaterial does), or, when
    // conductor_from_reflectance, pbrt-v4's "reflectance" form: `reflectance` r (clamped to
    // [0, 0.9999]) gives eta = 1, k = 2 sqrt(r) / sqrt(1 - r) (also divided by the coat's eta).
    LayeredSpectrum conductor_eta, conductor_k;
    bool conductor_from_reflectance = false;
    float base_alpha_x = 0, base_alpha_y = 0;  // smooth when both are below 1e-3
    // The slab: thickness (at least the smallest normal float, as pbrt-v4), medium albedo (clamped
    // to [0, 1]; black = no medium, transmittance exp(-thickness / |cos|) only) and HG g.
    float thickness = 0.01f;
    spectrum::RgbSpectrum albedo;
    float g = 0;
    int max_depth = 10, n_samples = 1;  // pbrt-v4's defaults
    uint64_t seed = 0;                  // pbrt-v4's Options seed
};

// The two parts of a layered BSDF, for callers that split a BSDF into what paths follow and what
// photon estimates read (bsdf.h's split_lobes): the coat's own reflection (a delta when the coat is
// smooth) and the light that enters the slab (the walks: diffuse or glossy). All = both, as
// pbrt-v4 samples and evaluates them.
enum class LayeredPart { All, Coat, Walk };

// sample()'s result. weight = f |cos(wi)| / pdf.
struct LayeredSample {
    Vec3 wi;
    Spectrum f;
    float pdf = 0;
    uint32_t flags = 0;  // LobeFlags: kReflection, kSpecular or kGlossy
    Spectrum weight;
    // True (as pbrt-v4 marks every layered sample, the coat's own reflection included, whose pdf
    // leaves out the walks) except for sample(Coat): callers use f() and pdf() for MIS.
    bool pdf_is_proportional = true;
    // Which part produced it: Coat (the coat's reflection at the entrance) or Walk.
    LayeredPart part = LayeredPart::Walk;
    bool is_specular() const;
};

class LayeredBxdf {
public:
    LayeredBxdf() = default;
    explicit LayeredBxdf(const LayeredParams& params);

    // The estimate of f(wo, wi) at `lambda` (spectral; see the conventions above). Coat: the coat's
    // reflection alone (exact; 0 when smooth); Walk: the walks alone; with the same inputs
    // f(All) = f(Coat) + f(Walk).
    Spectrum f(Vec3 wo, Vec3 wi, const Wavelengths& lambda, TransportMode mode = TransportMode{},
               LayeredPart part = LayeredPart::All) const;
    // All: pbrt-v4's density estimate, mixed with the uniform sphere density (0.9 / 0.1). Coat:
    // the exact density of sample(Coat) (0 when smooth). Walk: pbrt-v4's estimate without the coat's
    // reflection term, mixed with the uniform density as All is.
    float pdf(Vec3 wo, Vec3 wi, LayeredPart part = LayeredPart::All) const;
    // All: one walk from wo as pbrt-v4's (the coat reflects with its Fresnel probability, else the
    // walk). Coat: the coat's reflection alone (weight = its albedo at wo; the pdf is exact, not
    // proportional). Walk: entry forced through the coat (the weight carries its transmittance),
    // then the walk. nullopt when absorbed or terminated. So weight(All) has the expectation of
    // weight(Coat) + weight(Walk).
    std::optional<LayeredSample> sample(Vec3 wo, float uc, Vec2 u, const Wavelengths& lambda,
                                        TransportMode mode = TransportMode{},
                                        LayeredPart part = LayeredPart::All) const;

    // Albedo estimates for choosing between the parts (Russian roulette, lobe selection): the
    // coat's Fresnel reflectance at wo (exact for a smooth coat, the rough coat's roughly), and the
    // walk's albedo for a thin clear slab over a base of albedo `base_albedo`:
    // (1 - F(wo)) a (1 - Fi) / (1 - a Fi), Fi = internal_reflectance(eta) (exact for a smooth coat
    // over a Lambertian base; an estimate otherwise).
    float coat_albedo(float cos_o) const;
    float walk_albedo(float cos_o, float base_albedo, float fi) const;
    // The cosine-weighted hemispherical reflectance of a smooth interface of relative index eta
    // seen from inside (the fraction of diffuse light it reflects back), by quadrature: compute it
    // once per material.
    static float internal_reflectance(float eta);

    uint32_t flags() const { return flags_; }
    // The kind of each part (a LobeFlags bit): the coat's reflection is kSpecular when the coat is
    // smooth, else kGlossy; the walk is kDiffuse over a diffuse base or through a medium, kSpecular
    // when every event is a delta (smooth coat, smooth conductor, no medium), else kGlossy.
    uint32_t coat_kind() const;
    uint32_t walk_kind() const;
    const LayeredParams& params() const { return p_; }
    // A LayeredBxdf refers to measured eta/k spectra by pointer; a copy made as bytes in another
    // process points at them again through this.
    void rebind(const spectrum::Distribution* eta, const spectrum::Distribution* k) {
        p_.conductor_eta.measured = eta;
        p_.conductor_k.measured = k;
    }

private:
    LayeredParams p_;
    bool coat_smooth_ = true, base_smooth_ = false, medium_ = false;
    MicrofacetDistribution coat_dist_, base_dist_;
    uint32_t flags_ = 0;
};

}  // namespace phos::shading
