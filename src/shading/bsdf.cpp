// Bsdf: builds the lobes of a scene::Material at a hit and implements eval / pdf / sample over them
// (lobe selection, shading frame, side and light-leak rules). The dielectric lobe's own maths is in
// dielectric.cpp; the conventions are documented in bsdf.h.
#include "shading/bsdf.h"

#include <cmath>

#include "core/warp.h"
#include "shading/bump.h"
#include "shading/dielectric.h"
#include "shading/fresnel.h"
#include "shading/texture_context.h"
#include "shading/texture_eval.h"

namespace phos::shading {
namespace {

// kMicrofacet is the Trowbridge-Reitz reflection lobe of pbrt's materials (rough conductors,
// Fresnel-weighted microfacet reflection); a material has at most one of kPhong, kMirror and it.
// kCoat and kWalk are the two parts of pbrt's layered materials (the coat's own reflection and the
// light that enters the slab, LayeredPart): a layered material has these two and no other.
// kMeasured (pbrt's measured BRDF) and kHair (its hair fibre BSDF) are each the material's only lobe.
enum Lobe : int {
    kLambert,
    kPhong,
    kMirror,
    kDielectric,
    kDiffTrans,
    kMicrofacet,
    kCoat,
    kWalk,
    kMeasured,
    kHair,
    kNumLobes
};
// The LobeAlbedos kind (sample_lobes mask bit) each lobe belongs to; the layered parts' kinds
// depend on the material (Bsdf::kind_of).
constexpr uint32_t kKind[kNumLobes] = {kDiffuse, kGlossy, kSpecular, kTransmission, kDiffuse,
                                       kGlossy,  0,       0,         kGlossy,       kGlossy};
// The lobes whose sharpness is shininess_ (a Phong exponent or a microfacet lobe's equivalent).
constexpr uint32_t kGlossyReflection = (1u << kPhong) | (1u << kMicrofacet);

// pbrt-v4's RoughnessToAlpha: alpha = sqrt(roughness) when remapping, the roughness itself if not.
float roughness_alpha(float roughness, bool remap) {
    roughness = std::max(roughness, 0.0f);
    return remap ? std::sqrt(roughness) : roughness;
}
// A microfacet lobe is a delta below this roughness (pbrt-v4's EffectivelySmooth).
constexpr float kSmoothAlpha = 1e-3f;
// The Phong exponent of the same sharpness as roughness alpha (Walter et al. 2007, sec. 5.2:
// alpha = sqrt(2 / (n + 2))), the inverse of MicrofacetDistribution::alpha_from_phong.
float phong_of_alpha(float alpha) { return std::max(2 / (alpha * alpha) - 2, 0.0f); }

// pbrt-v4's conductor given by a reflectance r: eta = 1 and k = 2 sqrt(r) / sqrt(1 - r), whose
// Fresnel reflectance at normal incidence is r (r kept below 1 so that k stays finite).
float k_of_reflectance(float r) {
    r = std::clamp(r, 0.0f, 0.9999f);
    return 2 * std::sqrt(r) / std::sqrt(1 - r);
}

// +1 when w is on the side ng points to, -1 on the other, 0 exactly in the tangent plane.
float side_of(Vec3 w, Vec3 ng) {
    const float d = dot(w, ng);
    return d > 0 ? 1.0f : (d < 0 ? -1.0f : 0.0f);
}

// The shading frame and geometric normal of a BSDF at `hit` (Bsdf::place).
void frame_at(const accel::SurfaceHit& hit, Frame& frame, Vec3& ng) {
    if (hit.shading) {  // copied straight from the accelerator's (no stack temporary)
        ng = hit.shading->ng;
        frame = hit.shading->frame;
    } else {
        const ShadingFrame f = shading_frame(hit.ng, hit.ns, hit.dpdu);
        ng = f.ng;
        frame = f.frame;
    }
}

// Where a material's textures are looked up at `hit` (pbrt-v4's TextureEvalContext: the point, its
// uv and the geometric normal, and the screen-space footprint when the scene's textures read it).
scene::TextureContext texture_context(const accel::SurfaceHit& hit, const scene::Scene& scene,
                                      const scene::CameraFootprint* footprint) {
    return shading::texture_context(scene, hit, footprint);
}

// The diffuse reflectance kd of material m at `hit`, its texture applied (Bsdf::apply_textures).
void texture_diffuse(const scene::Material& m, const accel::SurfaceHit& hit, const scene::Scene& scene,
                     const scene::CameraFootprint* footprint, Rgb& kd, spectrum::RgbSpectrum& kd_spectrum) {
    if (m.diffuse_texture < 0) return;
    kd *= eval_texture(scene, m.diffuse_texture, texture_context(hit, scene, footprint));
    kd_spectrum =
        spectrum::RgbSpectrum(kd, spectrum::RgbSpectrum::Use::Albedo, spectrum::RgbSpectrum::Fit::Table);
}

spectrum::RgbSpectrum albedo_spectrum(Rgb c) { return {c, spectrum::RgbSpectrum::Use::Albedo}; }
spectrum::RgbSpectrum unbounded_spectrum(Rgb c) { return {c, spectrum::RgbSpectrum::Use::Unbounded}; }

// A direction of the side-flipped local frame (eval_local's) back in the shading frame itself, for
// the hair BSDF, which is not symmetric under the flip.
Vec3 unflipped(Vec3 v, float side) { return {v.x, v.y, v.z * side}; }

// The absorption of a hair material, with `colour` its reflectance (textured at a hit) when the
// material gives one; scene constants fitted exactly, per-hit colours by the table.
HairAbsorption hair_absorption(const scene::Material& m, Rgb colour,
                               spectrum::RgbSpectrum::Fit fit = spectrum::RgbSpectrum::Fit::Exact) {
    using C = scene::Material::HairColour;
    switch (m.hair_colour) {
        case C::SigmaA:
            return HairAbsorption::of_sigma_a(m.hair_sigma_a, fit);
        case C::Reflectance:
            return HairAbsorption::of_reflectance(colour, m.hair_beta_n, fit);
        case C::Melanin:
            break;
    }
    return HairAbsorption::of_concentration(m.hair_eumelanin, m.hair_pheomelanin, fit);
}

// sample_lobes for a BSDF made of one Lambert lobe (the commonest material; every photon bounce
// on a diffuse wall), wo on side s of ng (s != 0), without the lobe selection and with wi taken to
// the local frame once: each operation that the general code does on this path, in its order, so
// the sample is the same to the bit (bsdf_test.cpp compares the two).
std::optional<BsdfSample> sample_lambert(const Frame& frame, Vec3 ng, const Rgb& kd,
                                         const spectrum::RgbSpectrum& kd_spectrum, float s, Vec2 u,
                                         const Wavelengths& lambda) {
    const float w = std::max(kd.average(), 0.0f);  // the selection weight, and the total
    if (!(w > 0)) return std::nullopt;
    BsdfSample bs;
    const Vec3 wi_l = warp::cosine_hemisphere(u);
    bs.flags = kDiffuse | kReflection;
    Vec3 wi_world = wi_l;
    wi_world.z *= s;
    bs.wi = frame.to_world(wi_world);
    const float gi = dot(bs.wi, ng) * s;
    if (!(gi > 0)) return std::nullopt;
    const float abs_cos = std::fabs(wi_l.z);
    if (!(abs_cos > 0)) return std::nullopt;
    // eval_local and pdf_local: wi back in the local frame, reflection only.
    Vec3 wi_back = frame.to_local(bs.wi);
    wi_back.z *= s;
    if (!(wi_back.z > 0)) return std::nullopt;  // f = 0
    Spectrum f(0.0f);
    f += kd_spectrum.sample(lambda) * kInvPi;
    const float pdf = (0.0f + w * warp::cosine_hemisphere_pdf(wi_back.z)) / w;
    if (!(pdf > 0) || f.is_black()) return std::nullopt;
    bs.f = f;
    bs.pdf = pdf;
    bs.weight = f * (abs_cos / pdf);
    return bs;
}

// Modified Phong: f = ks (n+2)/(2 pi) cos^n(alpha) (without Fresnel), alpha from the mirror
// direction of wo. Local frame, wi.z > 0 checked by the caller.
float phong_cos_alpha(Vec3 wo, Vec3 wi) { return dot(wi, Vec3(-wo.x, -wo.y, wo.z)); }

}  // namespace

Bsdf::Bsdf(const scene::Material& m, const accel::SurfaceHit& hit, const scene::Scene& scene,
           const BsdfOptions& options) {
    place(has_shading_detail(m) ? with_shading_detail(scene, m, hit) : hit);
    if (m.interface_only) return;  // flags_ == 0: integrators continue straight through
    footprint_ = options.texture_footprint;
    set_material(m, options);
    apply_textures(m, hit, scene);
}

Bsdf Bsdf::of_material(const scene::Material& m, const BsdfOptions& options) {
    Bsdf b;
    b.footprint_ = options.texture_footprint;
    if (!m.interface_only) b.set_material(m, options);
    return b;
}

Bsdf Bsdf::placed(const scene::Material& m, const accel::SurfaceHit& hit, const scene::Scene& scene) const {
    Bsdf b = *this;
    b.place(has_shading_detail(m) ? with_shading_detail(scene, m, hit) : hit);
    if (!m.interface_only) b.apply_textures(m, hit, scene);
    return b;
}

void Bsdf::place_lambert(const scene::Material& m, const accel::SurfaceHit& hit, const scene::Scene& scene,
                         LambertLobe& lobe) const {
    frame_at(has_shading_detail(m) ? with_shading_detail(scene, m, hit) : hit, lobe.frame, lobe.ng);
    lobe.kd = kd_;
    lobe.kd_spectrum = kd_s_;
    texture_diffuse(m, hit, scene, footprint_, lobe.kd, lobe.kd_spectrum);
}

void Bsdf::place(const accel::SurfaceHit& hit) { frame_at(hit, frame_, ng_); }

void Bsdf::set_material(const scene::Material& m, const BsdfOptions& options) {
    kd_ = m.diffuse;
    ks_ = m.specular;
    kt_ = m.transmission;
    kdt_ = m.diffuse_transmission;
    shininess_ = std::max(m.shininess, 0.0f);
    t_shininess_ = std::max(m.transmission_shininess, 0.0f);
    mirror_ = m.shininess >= scene::Material::kMirrorShininess;
    thin_ = m.thin;
    ior_ = m.ior > 0 ? m.ior : 1.0f;
    sharp_glass_ = thin_ || ior_ == 1 || t_shininess_ >= scene::Material::kMirrorShininess;
    conductor_ = m.conductor;
    cond_eta_ = m.conductor_eta;
    cond_k_ = m.conductor_k;
    kd_s_ = albedo_spectrum(kd_);
    ks_s_ = albedo_spectrum(ks_);
    kt_s_ = albedo_spectrum(kt_);
    kdt_s_ = albedo_spectrum(kdt_);
    if (conductor_) {
        cond_eta_s_ = unbounded_spectrum(cond_eta_);
        cond_k_s_ = unbounded_spectrum(cond_k_);
    }
    rebind(m);
    schlick_ = options.schlick;
    microfacet_ = options.microfacet;
    pbrt_microfacet_ = m.microfacet;
    cond_from_refl_ = m.conductor_from_reflectance;
    // Only the frosted dielectric reads the microfacet distribution.
    if (!kt_.is_black() && !sharp_glass_ && !pbrt_microfacet_)
        dist_ = MicrofacetDistribution(options.microfacet,
                                       MicrofacetDistribution::alpha_from_phong(t_shininess_));

    if (!m.diffuse.is_black()) lobes_ |= 1u << kLambert;
    if (!ks_.is_black()) lobes_ |= 1u << (mirror_ ? kMirror : kPhong);
    if (!kt_.is_black()) lobes_ |= 1u << kDielectric;
    if (!kdt_.is_black()) lobes_ |= 1u << kDiffTrans;
    if (lobes_ == 0) lobes_ = 1u << kLambert;  // black body: opaque, absorbs everything
    if (m.measured) {
        lobes_ = 1u << kMeasured;
        measured_ = MeasuredBxdf(*m.measured);
        measured_shininess_ = phong_of_alpha(m.measured->equivalent_alpha());
    } else if (m.hair) {
        lobes_ = 1u << kHair;
        HairParams p;
        p.eta = m.hair_eta;
        p.beta_m = m.hair_beta_m;
        p.beta_n = m.hair_beta_n;
        p.alpha_degrees = m.hair_alpha;
        p.sigma_a = hair_absorption(m, m.hair_reflectance);
        hair_ = HairBxdf(p);
        hair_shininess_ = 1 / std::max(hair_.longitudinal_variance(1), 1e-6f);
    } else if (m.layered) {
        lobes_ = (1u << kCoat) | (1u << kWalk);
        layered_fi_ = LayeredBxdf::internal_reflectance(m.coat_eta);
        set_layered(m, nullptr, nullptr);
    } else if (pbrt_microfacet_)
        set_microfacet_lobes(roughness_alpha(m.roughness_u, m.remap_roughness),
                             roughness_alpha(m.roughness_v, m.remap_roughness));

    set_flags();
}

uint32_t Bsdf::kind_of(int lobe) const {
    if (lobe == kCoat) return layered_.coat_kind();
    if (lobe == kWalk) return layered_.walk_kind();
    return kKind[lobe];
}

void Bsdf::set_layered(const scene::Material& m, const scene::Scene* scene, const accel::SurfaceHit* hit) {
    const bool at_hit = scene && hit;
    const auto texture = [&](int tex) {
        return at_hit && tex >= 0 ? eval_texture(*scene, tex, texture_context(*hit, *scene, footprint_))
                                  : Rgb(1.0f);
    };
    const auto alpha = [&](float value, int tex) {
        return roughness_alpha(tex >= 0 ? (at_hit ? texture(tex).average() : 0.0f) : value,
                               m.remap_roughness);
    };
    const auto albedo = [&](Rgb c, int tex) {
        return at_hit && tex >= 0 ? spectrum::RgbSpectrum(c, spectrum::RgbSpectrum::Use::Albedo,
                                                          spectrum::RgbSpectrum::Fit::Table)
                                  : albedo_spectrum(c);
    };
    LayeredParams p;
    p.eta = m.coat_eta;
    p.coat_alpha_x = alpha(m.roughness_u, m.roughness_u_texture);
    p.coat_alpha_y = alpha(m.roughness_v, m.roughness_v_texture);
    if (m.layered_conductor_base) {
        p.base = LayeredParams::Base::Conductor;
        p.base_alpha_x = alpha(m.base_roughness_u, m.base_roughness_u_texture);
        p.base_alpha_y = alpha(m.base_roughness_v, m.base_roughness_v_texture);
        if (m.conductor_from_reflectance) {
            const Rgb r = m.specular * texture(m.specular_texture);
            p.conductor_from_reflectance = true;
            p.reflectance = albedo(r, m.specular_texture);
            layered_base_albedo_ = r.average();
        } else {
            p.conductor_eta = {unbounded_spectrum(m.conductor_eta),
                               m.conductor_eta_spectrum ? &*m.conductor_eta_spectrum : nullptr};
            p.conductor_k = {unbounded_spectrum(m.conductor_k),
                             m.conductor_k_spectrum ? &*m.conductor_k_spectrum : nullptr};
            // Seen through the coat: eta and k relative to it, as the layered BSDF uses them.
            layered_base_albedo_ =
                fresnel_conductor(1.0f, m.conductor_eta / m.coat_eta, m.conductor_k / m.coat_eta).average();
        }
    } else {
        const Rgb r = m.diffuse * texture(m.diffuse_texture);
        p.reflectance = albedo(r, m.diffuse_texture);
        layered_base_albedo_ = r.average();
    }
    p.thickness = m.layer_thickness;
    p.albedo = albedo(m.layer_albedo * texture(m.layer_albedo_texture), m.layer_albedo_texture);
    p.g = m.layer_g;
    p.max_depth = m.layer_max_depth;
    p.n_samples = m.layer_samples;
    layered_ = LayeredBxdf(p);
    // Sharpness as a Phong exponent (what --sharp-glossy compares): the coat's own, and the
    // walk's through the rougher of the coat and the base.
    const float coat_alpha = std::sqrt(p.coat_alpha_x * p.coat_alpha_y);
    coat_shininess_ = coat_alpha < kSmoothAlpha ? kInf : phong_of_alpha(coat_alpha);
    const float base_alpha = std::sqrt(p.base_alpha_x * p.base_alpha_y);
    walk_shininess_ = phong_of_alpha(std::max({coat_alpha, base_alpha, kSmoothAlpha}));
}

void Bsdf::set_microfacet_lobes(float ax, float ay) {
    const bool smooth = std::max(ax, ay) < kSmoothAlpha;
    if (lobes_ & ((1u << kPhong) | (1u << kMirror) | (1u << kMicrofacet))) {
        lobes_ &= ~((1u << kPhong) | (1u << kMirror) | (1u << kMicrofacet));
        lobes_ |= 1u << (smooth ? kMirror : kMicrofacet);
        mirror_ = smooth;
        if (!smooth) {
            spec_dist_ = MicrofacetDistribution(ax, ay);
            shininess_ = phong_of_alpha(spec_dist_.alpha());
        }
    }
    if ((lobes_ & (1u << kDielectric)) && !thin_ && ior_ != 1) {
        sharp_glass_ = smooth;
        if (!smooth) {
            dist_ = MicrofacetDistribution(ax, ay);
            t_shininess_ = phong_of_alpha(dist_.alpha());
        }
    }
}

void Bsdf::set_flags() {
    flags_ = 0;
    if (lobes_ & (1u << kLambert)) flags_ |= kDiffuse | kReflection;
    if (lobes_ & kGlossyReflection) flags_ |= kGlossy | kReflection;
    if (lobes_ & (1u << kMirror)) flags_ |= kSpecular | kReflection;
    if (lobes_ & (1u << kDielectric))
        flags_ |= (sharp_glass_ ? kSpecular : kGlossy) | kReflection | kTransmission;
    if (lobes_ & (1u << kDiffTrans)) flags_ |= kDiffuse | kTransmission;
    if (lobes_ & (1u << kCoat)) flags_ |= kind_of(kCoat) | kReflection;
    if (lobes_ & (1u << kWalk)) flags_ |= kind_of(kWalk) | kReflection;
    if (lobes_ & (1u << kMeasured)) flags_ |= measured_.flags();
    if (lobes_ & (1u << kHair)) flags_ |= HairBxdf::flags();
}

Bsdf Bsdf::regularized(float max_exponent) const {
    Bsdf b = *this;
    if ((lobes_ & (1u << kPhong)) && shininess_ > max_exponent) b.shininess_ = max_exponent;
    // A microfacet lobe sharper than that exponent: each alpha raised to the exponent's.
    const float alpha_min = MicrofacetDistribution::alpha_from_phong(max_exponent);
    if ((lobes_ & (1u << kMicrofacet)) && shininess_ > max_exponent) {
        b.spec_dist_ = MicrofacetDistribution(std::max(spec_dist_.alpha_x(), alpha_min),
                                              std::max(spec_dist_.alpha_y(), alpha_min));
        b.shininess_ = phong_of_alpha(b.spec_dist_.alpha());
    }
    if (lobes_ & (1u << kMirror)) {
        b.lobes_ = (b.lobes_ & ~(1u << kMirror)) | (1u << kPhong);
        b.mirror_ = false;
        b.shininess_ = max_exponent;
        b.widened_mirror_ = true;
    }
    const bool widenable = (lobes_ & (1u << kDielectric)) && !thin_ && ior_ != 1;
    if (widenable && (sharp_glass_ || t_shininess_ > max_exponent)) {
        b.widened_glass_ = widened_glass_ || sharp_glass_;
        b.sharp_glass_ = false;
        if (pbrt_microfacet_ && !sharp_glass_) {
            b.dist_ = MicrofacetDistribution(std::max(dist_.alpha_x(), alpha_min),
                                             std::max(dist_.alpha_y(), alpha_min));
            b.t_shininess_ = phong_of_alpha(b.dist_.alpha());
        } else {
            b.t_shininess_ = max_exponent;
            b.dist_ =
                MicrofacetDistribution(pbrt_microfacet_ ? MicrofacetModel::GGX : microfacet_, alpha_min);
        }
    }
    b.set_flags();
    return b;
}

bool Bsdf::only_widened() const {
    const uint32_t widened =
        (widened_mirror_ ? 1u << kPhong : 0u) | (widened_glass_ ? 1u << kDielectric : 0u);
    return widened != 0 && (lobes_ & ~widened) == 0;
}

Bsdf Bsdf::only(uint32_t lobe_mask) const {
    Bsdf b = *this;
    for (int i = 0; i < kNumLobes; ++i)
        if (!(lobe_mask & kind_of(i))) b.lobes_ &= ~(1u << i);
    b.set_flags();
    return b;
}

void Bsdf::apply_textures(const scene::Material& m, const accel::SurfaceHit& hit, const scene::Scene& scene) {
    if (lobes_ & (1u << kHair)) {
        hair_.set_h(-1 + 2 * hit.uv.y);  // pbrt-v4's HairMaterial: v runs across the fibre
        if (m.hair_colour == scene::Material::HairColour::Reflectance && m.hair_reflectance_texture >= 0) {
            const Rgb c = m.hair_reflectance * eval_texture(scene, m.hair_reflectance_texture,
                                                            texture_context(hit, scene, footprint_));
            hair_.set_sigma_a(hair_absorption(m, c, spectrum::RgbSpectrum::Fit::Table));
        }
        return;
    }
    texture_diffuse(m, hit, scene, footprint_, kd_, kd_s_);
    if (m.specular_texture >= 0) {
        ks_ *= eval_texture(scene, m.specular_texture, texture_context(hit, scene, footprint_));
        ks_s_ =
            spectrum::RgbSpectrum(ks_, spectrum::RgbSpectrum::Use::Albedo, spectrum::RgbSpectrum::Fit::Table);
    }
    if (m.diffuse_transmission_texture >= 0) {
        // pbrt-v4's diffusetransmission clamps scale x texture to [0, 1].
        const Rgb t = kdt_ * eval_texture(scene, m.diffuse_transmission_texture,
                                          texture_context(hit, scene, footprint_));
        kdt_ = Rgb(std::clamp(t.r, 0.0f, 1.0f), std::clamp(t.g, 0.0f, 1.0f), std::clamp(t.b, 0.0f, 1.0f));
        kdt_s_ = spectrum::RgbSpectrum(kdt_, spectrum::RgbSpectrum::Use::Albedo,
                                       spectrum::RgbSpectrum::Fit::Table);
    }
    if (m.layered) {
        if (m.diffuse_texture >= 0 || m.specular_texture >= 0 || m.roughness_u_texture >= 0 ||
            m.roughness_v_texture >= 0 || m.base_roughness_u_texture >= 0 ||
            m.base_roughness_v_texture >= 0 || m.layer_albedo_texture >= 0) {
            set_layered(m, &scene, &hit);
            set_flags();  // a textured roughness can make the coat smooth or rough here
        }
        return;
    }
    if (pbrt_microfacet_ && (m.roughness_u_texture >= 0 || m.roughness_v_texture >= 0)) {
        const auto rough = [&](int tex, float value) {
            return tex >= 0 ? eval_texture(scene, tex, texture_context(hit, scene, footprint_)).average()
                            : value;
        };
        set_microfacet_lobes(roughness_alpha(rough(m.roughness_u_texture, m.roughness_u), m.remap_roughness),
                             roughness_alpha(rough(m.roughness_v_texture, m.roughness_v), m.remap_roughness));
        set_flags();
    }
}

void Bsdf::rebind(const scene::Material& m) {
    cond_eta_spectrum_ = conductor_ && m.conductor_eta_spectrum ? &*m.conductor_eta_spectrum : nullptr;
    cond_k_spectrum_ = conductor_ && m.conductor_k_spectrum ? &*m.conductor_k_spectrum : nullptr;
    ior_spectrum_ = m.ior_spectrum && !m.ior_spectrum->is_constant() ? &*m.ior_spectrum : nullptr;
    if (m.measured) measured_.rebind(*m.measured);
    if (m.layered && m.layered_conductor_base && !m.conductor_from_reflectance)
        layered_.rebind(m.conductor_eta_spectrum ? &*m.conductor_eta_spectrum : nullptr,
                        m.conductor_k_spectrum ? &*m.conductor_k_spectrum : nullptr);
}

bool Bsdf::dispersive() const { return ior_spectrum_ != nullptr && (lobes_ & (1u << kDielectric)); }

Rgb Bsdf::specular_reflectance(float cos_o) const {
    if (cond_from_refl_)
        return {fresnel_conductor(cos_o, 1.0f, k_of_reflectance(ks_.r)),
                fresnel_conductor(cos_o, 1.0f, k_of_reflectance(ks_.g)),
                fresnel_conductor(cos_o, 1.0f, k_of_reflectance(ks_.b))};
    return conductor_ ? ks_ * fresnel_conductor(cos_o, cond_eta_, cond_k_) : ks_;
}

Spectrum Bsdf::specular_reflectance(float cos_o, const Wavelengths& lambda) const {
    Spectrum r = ks_s_.sample(lambda);
    if (cond_from_refl_) {
        for (int i = 0; i < spectrum::kSpectrumSamples; ++i)
            r[i] = fresnel_conductor(cos_o, 1.0f, k_of_reflectance(r[i]));
        return r;
    }
    if (!conductor_) return r;
    const Spectrum eta = cond_eta_spectrum_ ? cond_eta_spectrum_->sample(lambda) : cond_eta_s_.sample(lambda);
    const Spectrum k = cond_k_spectrum_ ? cond_k_spectrum_->sample(lambda) : cond_k_s_.sample(lambda);
    for (int i = 0; i < spectrum::kSpectrumSamples; ++i) r[i] *= fresnel_conductor(cos_o, eta[i], k[i]);
    return r;
}

void Bsdf::selection_weights(Vec3 wo_local, uint32_t mask, float w[kNumLobes]) const {
    const float cos_o = std::fabs(wo_local.z);
    for (int i = 0; i < kNumLobes; ++i) {
        w[i] = 0;
        if (!(lobes_ & (1u << i)) || !(mask & kind_of(i))) continue;
        switch (i) {
            case kLambert:
                w[i] = kd_.average();
                break;
            case kPhong:
            case kMirror:
            case kMicrofacet:
                w[i] = specular_reflectance(cos_o).average();
                break;
            case kDielectric:
                w[i] = kt_.average();
                break;
            case kDiffTrans:
                w[i] = kdt_.average();
                break;
            case kCoat:
                w[i] = layered_.coat_albedo(cos_o);
                break;
            case kWalk:
                // Floored so that a black base under a scattering slab is still sampled.
                w[i] = std::max(layered_.walk_albedo(cos_o, layered_base_albedo_, layered_fi_),
                                0.05f * (1 - layered_.coat_albedo(cos_o)));
                break;
            case kMeasured:
            case kHair:
                w[i] = 1;  // the only lobe
                break;
        }
        w[i] = std::max(w[i], 0.0f);
    }
}

Bsdf::LobeAlbedos Bsdf::lobe_albedos(Vec3 wo) const {
    LobeAlbedos a;
    const float cos_o = std::fabs(dot(wo, frame_.n));
    if (lobes_ & (1u << kLambert)) a.diffuse += kd_;
    if (lobes_ & (1u << kDiffTrans)) a.diffuse += kdt_;
    if (lobes_ & kGlossyReflection) a.glossy = specular_reflectance(cos_o);
    if (lobes_ & (1u << kMirror)) a.specular = specular_reflectance(cos_o);
    if (lobes_ & (1u << kDielectric)) a.transmission = kt_;
    const auto add = [&](uint32_t kind, float albedo) {
        (kind == kDiffuse ? a.diffuse : kind == kSpecular ? a.specular : a.glossy) += Rgb(albedo);
    };
    if (lobes_ & (1u << kCoat)) add(layered_.coat_kind(), layered_.coat_albedo(cos_o));
    if (lobes_ & (1u << kWalk))
        add(layered_.walk_kind(), layered_.walk_albedo(cos_o, layered_base_albedo_, layered_fi_));
    if (lobes_ & (1u << kMeasured)) {
        const float s = side_of(wo, ng_);
        Vec3 wo_l = frame_.to_local(wo);
        wo_l.z *= s != 0 ? s : 1.0f;
        a.glossy += Rgb(measured_.albedo(wo_l));
    }
    if (lobes_ & (1u << kHair)) a.glossy += hair_.albedo(frame_.to_local(wo));
    return a;
}

uint32_t Bsdf::sharp_lobes(float sharp_exponent) const {
    uint32_t m = 0;
    if ((lobes_ & kGlossyReflection) && shininess_ >= sharp_exponent) m |= kGlossy;
    if ((lobes_ & (1u << kCoat)) && layered_.coat_kind() == kGlossy && coat_shininess_ >= sharp_exponent)
        m |= kGlossy;
    if ((lobes_ & (1u << kWalk)) && layered_.walk_kind() == kGlossy && walk_shininess_ >= sharp_exponent)
        m |= kGlossy;
    if ((lobes_ & (1u << kDielectric)) && !sharp_glass_ && t_shininess_ >= sharp_exponent) m |= kTransmission;
    if ((lobes_ & (1u << kMeasured)) && measured_shininess_ >= sharp_exponent) m |= kGlossy;
    if ((lobes_ & (1u << kHair)) && hair_shininess_ >= sharp_exponent) m |= kGlossy;
    return m;
}

void Bsdf::part_masks(float sharp_exponent, uint32_t& followed, uint32_t& estimated) const {
    followed = estimated = 0;
    const uint32_t sharp = sharp_lobes(sharp_exponent);
    const auto put = [&](uint32_t kind, bool follow) { (follow ? followed : estimated) |= kind; };
    if (lobes_ & (1u << kMirror)) followed |= kSpecular;
    if (lobes_ & (1u << kDielectric)) put(kTransmission, sharp_glass_ || (sharp & kTransmission));
    if (lobes_ & ((1u << kLambert) | (1u << kDiffTrans))) estimated |= kDiffuse;
    if (lobes_ & (kGlossyReflection | (1u << kMeasured) | (1u << kHair))) put(kGlossy, sharp & kGlossy);
    // The layered parts by their kinds: delta parts followed, diffuse ones estimated, glossy ones
    // by their sharpness.
    for (const int lobe : {kCoat, kWalk}) {
        if (!(lobes_ & (1u << lobe))) continue;
        const uint32_t kind = kind_of(lobe);
        put(kind, kind == kSpecular || (kind == kGlossy && (sharp & kGlossy)));
    }
}

bool Bsdf::has_estimated(float sharp_exponent) const {
    uint32_t followed, estimated;
    part_masks(sharp_exponent, followed, estimated);
    return estimated != 0;
}

bool Bsdf::has_followed(float sharp_exponent) const {
    uint32_t followed, estimated;
    part_masks(sharp_exponent, followed, estimated);
    return followed != 0;
}

Bsdf::LobeSplit Bsdf::split_lobes(Vec3 wo, float sharp_exponent) const {
    LobeSplit s;
    part_masks(sharp_exponent, s.followed, s.estimated);
    if (!s.estimated) {
        s.p_estimated = 0;
    } else if (s.followed) {
        const LobeAlbedos a = lobe_albedos(wo);
        const float kinds[4] = {a.diffuse.average(), a.glossy.average(), a.specular.average(),
                                a.transmission.average()};
        const uint32_t masks[4] = {kDiffuse, kGlossy, kSpecular, kTransmission};
        float est = 0, fol = 0;
        for (int k = 0; k < 4; ++k) (s.estimated & masks[k] ? est : fol) += std::max(kinds[k], 0.0f);
        s.p_estimated = est + fol > 0 ? est / (est + fol) : 1;
    }
    return s;
}

Spectrum Bsdf::eval_masked(Vec3 wo, Vec3 wi, uint32_t mask, const Wavelengths& lambda,
                           TransportMode mode) const {
    const float s = side_of(wo, ng_);
    if (s == 0 || lobes_ == 0) return Spectrum(0.0f);
    Vec3 wo_l = frame_.to_local(wo);
    wo_l.z *= s;
    return eval_local(wo_l, wi, s, mask, lambda, mode);
}

// eval_masked after its side test, with wo already in the (side-flipped) local frame.
Spectrum Bsdf::eval_local(Vec3 wo_l, Vec3 wi, float s, uint32_t mask, const Wavelengths& lambda,
                          TransportMode mode) const {
    Vec3 wi_l = frame_.to_local(wi);
    wi_l.z *= s;
    const float gi = dot(wi, ng_) * s;
    const bool refl = gi > 0 && wi_l.z > 0, trans = gi < 0 && wi_l.z < 0;
    if (!refl && !trans) return Spectrum(0.0f);
    const auto has = [&](int lobe) { return (lobes_ & (1u << lobe)) && (mask & kind_of(lobe)); };

    Spectrum f(0.0f);
    if (refl && has(kLambert)) f += kd_s_.sample(lambda) * kInvPi;
    if (refl && has(kPhong)) {
        const float ca = phong_cos_alpha(wo_l, wi_l);
        if (ca > 0) {
            Spectrum spec;
            if (conductor_ || cond_from_refl_) {
                const Vec3 h = wo_l + wi_l;
                const float cos_h = length_squared(h) > 0 ? dot(wo_l, normalize(h)) : 1.0f;
                spec = specular_reflectance(cos_h, lambda);
            } else {
                spec = ks_s_.sample(lambda);
            }
            // A mirror widened by regularized(): its lobe is the sampling density over cos theta_i,
            // so that it reflects ks at every incidence as the mirror does (the modified Phong
            // lobe reflects ks cos theta_i and would not tend to the mirror).
            if (widened_mirror_)
                f += spec * (warp::power_cosine_pdf(ca, shininess_) / wi_l.z);
            else
                f += spec * ((shininess_ + 2) * (0.5f * kInvPi) * std::pow(ca, shininess_));
        }
    }
    if (refl && has(kMicrofacet) && wo_l.z > 0) {
        // Torrance-Sparrow with Trowbridge-Reitz D and height-correlated Smith G (Heitz 2014,
        // eq. 99): f = F(wo.wm) D(wm) G(wo, wi) / (4 cos_o cos_i), wm the half vector.
        const Vec3 h = wo_l + wi_l;
        if (length_squared(h) > 0) {
            const Vec3 wm = normalize(h);
            f += specular_reflectance(std::fabs(dot(wo_l, wm)), lambda) *
                 (spec_dist_.D(wm) * spec_dist_.G(wo_l, wi_l) / (4 * wi_l.z * wo_l.z));
        }
    }
    if (refl && has(kCoat)) f += layered_.f(wo_l, wi_l, lambda, mode, LayeredPart::Coat);
    if (refl && has(kWalk)) f += layered_.f(wo_l, wi_l, lambda, mode, LayeredPart::Walk);
    // Measured tables and the hair model are not reciprocal: light paths (Importance) evaluate
    // the adjoint, f*(wo, wi) = f(wi, wo), so that a path's value does not depend on the direction
    // it was traced in.
    const bool adjoint = mode == TransportMode::Importance;
    if (refl && has(kMeasured))
        f += adjoint ? measured_.f(wi_l, wo_l, lambda) : measured_.f(wo_l, wi_l, lambda);
    if (has(kHair)) {
        const Vec3 a = unflipped(wo_l, s), b = unflipped(wi_l, s);
        f += adjoint ? hair_.f(b, a, lambda) : hair_.f(a, b, lambda);
    }
    if (trans && has(kDiffTrans)) f += kdt_s_.sample(lambda) * kInvPi;
    if (has(kDielectric) && !sharp_glass_) {
        const Spectrum kt = kt_s_.sample(lambda);
        if (ior_spectrum_) {  // each wavelength with its own index
            for (int i = 0; i < spectrum::kSpectrumSamples; ++i) {
                const float n = (*ior_spectrum_)(lambda[i]);
                f[i] += kt[i] * dielectric::rough_eval(dist_, wo_l, wi_l, s > 0 ? n : 1 / n, schlick_, mode);
            }
        } else {
            const float eta = s > 0 ? ior_ : 1 / ior_;
            f += kt * dielectric::rough_eval(dist_, wo_l, wi_l, eta, schlick_, mode);
        }
    }
    return f;
}

float Bsdf::pdf_masked(Vec3 wo, Vec3 wi, uint32_t mask) const {
    const float s = side_of(wo, ng_);
    if (s == 0 || lobes_ == 0) return 0;
    Vec3 wo_l = frame_.to_local(wo);
    wo_l.z *= s;
    float w[kNumLobes];
    selection_weights(wo_l, mask, w);
    return pdf_local(wo_l, wi, s, w);
}

// pdf_masked after its side test, with wo in the (side-flipped) local frame and the lobes'
// selection weights for the mask.
float Bsdf::pdf_local(Vec3 wo_l, Vec3 wi, float s, const float w[]) const {
    Vec3 wi_l = frame_.to_local(wi);
    wi_l.z *= s;
    const float gi = dot(wi, ng_) * s;
    const bool refl = gi > 0 && wi_l.z > 0, trans = gi < 0 && wi_l.z < 0;
    if (!refl && !trans) return 0;
    float total = 0;
    for (int i = 0; i < kNumLobes; ++i) total += w[i];
    if (!(total > 0)) return 0;

    float pdf = 0;
    if (refl && w[kLambert] > 0) pdf += w[kLambert] * warp::cosine_hemisphere_pdf(wi_l.z);
    if (refl && w[kPhong] > 0)
        pdf += w[kPhong] * warp::power_cosine_pdf(phong_cos_alpha(wo_l, wi_l), shininess_);
    if (refl && w[kMicrofacet] > 0 && wo_l.z > 0) {
        // Visible-normal density of the half vector times the reflection Jacobian 1 / (4 wo.wm).
        const Vec3 h = wo_l + wi_l;
        if (length_squared(h) > 0) {
            const Vec3 wm = normalize(h);
            const float c = std::fabs(dot(wo_l, wm));
            if (c > 0) pdf += w[kMicrofacet] * spec_dist_.pdf_wm(wo_l, wm) / (4 * c);
        }
    }
    if (trans && w[kDiffTrans] > 0) pdf += w[kDiffTrans] * warp::cosine_hemisphere_pdf(-wi_l.z);
    if (refl && w[kCoat] > 0) pdf += w[kCoat] * layered_.pdf(wo_l, wi_l, LayeredPart::Coat);
    if (refl && w[kWalk] > 0) pdf += w[kWalk] * layered_.pdf(wo_l, wi_l, LayeredPart::Walk);
    if (refl && w[kMeasured] > 0) pdf += w[kMeasured] * measured_.pdf(wo_l, wi_l);
    if (w[kHair] > 0) pdf += w[kHair] * hair_.pdf(unflipped(wo_l, s), unflipped(wi_l, s));
    if (w[kDielectric] > 0 && !sharp_glass_) {
        const float eta = s > 0 ? ior_ : 1 / ior_;
        pdf += w[kDielectric] * dielectric::rough_pdf(dist_, wo_l, wi_l, eta, schlick_);
    }
    return pdf / total;
}

Spectrum Bsdf::eval(Vec3 wo, Vec3 wi, const Wavelengths& lambda, TransportMode mode) const {
    return eval_masked(wo, wi, ~0u, lambda, mode);
}

float Bsdf::pdf(Vec3 wo, Vec3 wi) const { return pdf_masked(wo, wi, ~0u); }

Bsdf::Evaluation Bsdf::evaluate(Vec3 wo, Vec3 wi, const Wavelengths& lambda, TransportMode mode) const {
    if (lobes_ != 1u << kLambert) return {eval(wo, wi, lambda, mode), pdf(wo, wi), pdf(wi, wo)};
    // A lone Lambert lobe: eval_local's and pdf_local's operations for it (reflection only: b on
    // a's side of ng and of the shading normal; the pdf divides by the selection weight's total).
    const float w = std::max(kd_.average(), 0.0f);
    const auto reflects = [&](Vec3 a, Vec3 b, float& cos_b) {
        const float s = side_of(a, ng_);
        cos_b = dot(b, frame_.n) * s;
        return s != 0 && dot(b, ng_) * s > 0 && cos_b > 0;
    };
    Evaluation e{Spectrum(0.0f), 0, 0};
    float cos_i = 0, cos_o = 0;
    if (reflects(wo, wi, cos_i)) {
        e.f = kd_s_.sample(lambda) * kInvPi;
        if (w > 0) e.pdf = w * warp::cosine_hemisphere_pdf(cos_i) / w;
    }
    if (reflects(wi, wo, cos_o) && w > 0) e.pdf_rev = w * warp::cosine_hemisphere_pdf(cos_o) / w;
    return e;
}

std::optional<BsdfSample> Bsdf::sample(Vec3 wo, float u_lobe, Vec2 u, const Wavelengths& lambda,
                                       TransportMode mode) const {
    return sample_lobes(~0u, wo, u_lobe, u, lambda, mode);
}

std::optional<BsdfSample> Bsdf::sample_lobes(uint32_t lobe_mask, Vec3 wo, float u_lobe, Vec2 u,
                                             const Wavelengths& lambda, TransportMode mode) const {
    const float s = side_of(wo, ng_);
    if (s == 0 || lobes_ == 0) return std::nullopt;
    if (lobes_ == 1u << kLambert)
        return lobe_mask & kKind[kLambert] ? sample_lambert(frame_, ng_, kd_, kd_s_, s, u, lambda)
                                           : std::nullopt;
    Vec3 wo_l = frame_.to_local(wo);
    wo_l.z *= s;
    float w[kNumLobes];
    selection_weights(wo_l, lobe_mask, w);
    float total = 0;
    for (float x : w) total += x;
    if (!(total > 0)) return std::nullopt;

    // Pick the lobe and rescale u_lobe to [0, 1) within its interval, for reuse below.
    int lobe = -1;
    float target = u_lobe * total, acc = 0;
    for (int i = 0; i < kNumLobes; ++i) {
        if (w[i] <= 0) continue;
        lobe = i;
        if (target < acc + w[i]) break;
        acc += w[i];
    }
    const float sel = w[lobe] / total;
    const float u_re = std::clamp((target - acc) / w[lobe], 0.0f, 0x1.fffffep-1f);

    BsdfSample bs;
    Vec3 wi_l;
    bool delta = false, transmitted = false;
    Spectrum coefficient_over_prob;  // delta lobes: coefficient / branch probability
    float branch_prob = 1;
    // A layered part's sample: its own weight f |cos| / pdf (its pdf is only proportional to the
    // density, pbrt-v4's pdfIsProportional), divided by the part's selection probability.
    std::optional<Spectrum> layered_weight;
    switch (lobe) {
        case kLambert:
            wi_l = warp::cosine_hemisphere(u);
            bs.flags = kDiffuse | kReflection;
            break;
        case kDiffTrans:
            wi_l = warp::cosine_hemisphere(u);
            wi_l.z = -wi_l.z;
            transmitted = true;
            bs.flags = kDiffuse | kTransmission;
            break;
        case kPhong: {
            const Vec3 r(-wo_l.x, -wo_l.y, wo_l.z);
            wi_l = Frame(r).to_world(warp::power_cosine(u, shininess_));
            if (wi_l.z <= 0) return std::nullopt;  // below the surface: lost, pdf not renormalised
            bs.flags = kGlossy | kReflection | (widened_mirror_ ? kWidened : 0u);
            break;
        }
        case kCoat:
        case kWalk: {
            const auto ls = layered_.sample(wo_l, u_re, u, lambda, mode,
                                            lobe == kCoat ? LayeredPart::Coat : LayeredPart::Walk);
            if (!ls || ls->wi.z <= 0) return std::nullopt;
            wi_l = ls->wi;
            bs.flags = ls->is_specular() ? ls->flags : kReflection | kind_of(lobe);
            if (ls->is_specular()) {
                delta = true;
                coefficient_over_prob = ls->weight;
                branch_prob = ls->pdf;
            } else {
                layered_weight = ls->weight;
            }
            break;
        }
        case kMeasured: {
            const auto ms = measured_.sample(wo_l, u, lambda);
            if (!ms || !(ms->wi.z > 0)) return std::nullopt;
            wi_l = ms->wi;
            bs.flags = kGlossy | kReflection;
            break;
        }
        case kHair: {
            const auto hs = hair_.sample(unflipped(wo_l, s), u_re, u, lambda);
            if (!hs) return std::nullopt;
            wi_l = unflipped(hs->wi, s);
            transmitted = wi_l.z < 0;
            bs.flags = kGlossy | (transmitted ? kTransmission : kReflection);
            break;
        }
        case kMicrofacet: {
            if (!(wo_l.z > 0)) return std::nullopt;
            const Vec3 wm = spec_dist_.sample_wm(wo_l, u);  // visible normals (Heitz 2018)
            wi_l = wm * (2 * dot(wo_l, wm)) - wo_l;
            if (wi_l.z <= 0) return std::nullopt;
            bs.flags = kGlossy | kReflection;
            break;
        }
        case kMirror:
            wi_l = Vec3(-wo_l.x, -wo_l.y, wo_l.z);
            coefficient_over_prob = specular_reflectance(std::fabs(wo_l.z), lambda);
            delta = true;
            bs.flags = kSpecular | kReflection;
            break;
        case kDielectric: {
            // A thin sheet has the same medium on both faces: its reflectance is the same from
            // either side.
            if (sharp_glass_) {
                // A dispersive index bends each wavelength its own way: the hero's decides.
                const float n = ior_spectrum_ && !thin_ ? (*ior_spectrum_)(lambda[0]) : ior_;
                const float eta = s > 0 || thin_ ? n : 1 / n;
                const auto ds = dielectric::sample_smooth(wo_l, eta, thin_, schlick_, u_re, mode);
                if (!ds) return std::nullopt;
                wi_l = ds->wi;
                transmitted = ds->transmitted;
                branch_prob = ds->prob;
                coefficient_over_prob = kt_s_.sample(lambda) * (ds->coefficient / ds->prob);
                if (thin_ && ior_spectrum_) {
                    // A thin sheet does not bend light, so a dispersive one sends every wavelength
                    // the same way with its own reflectance: the branch, taken with the
                    // probability at the d line, weighs each wavelength by its own over that one.
                    for (int i = 0; i < spectrum::kSpectrumSamples; ++i) {
                        const float ri = thin_sheet_reflectance(dielectric::reflectance(
                            std::fabs(wo_l.z), (*ior_spectrum_)(lambda[i]), schlick_));
                        coefficient_over_prob[i] *= (transmitted ? 1 - ri : ri) / ds->coefficient;
                    }
                }
                bs.dispersive = ior_spectrum_ && !thin_;
                bs.eta = ds->eta;
                delta = true;
                bs.flags = kSpecular | (transmitted ? kTransmission : kReflection);
            } else {
                const float eta = s > 0 ? ior_ : 1 / ior_;
                const auto wi = dielectric::rough_sample(dist_, wo_l, eta, schlick_, u_re, u);
                if (!wi) return std::nullopt;
                wi_l = *wi;
                transmitted = wi_l.z < 0;
                if (transmitted) bs.eta = eta;
                bs.flags =
                    kGlossy | (transmitted ? kTransmission : kReflection) | (widened_glass_ ? kWidened : 0u);
            }
            break;
        }
        default:
            return std::nullopt;
    }

    Vec3 wi_world = wi_l;
    wi_world.z *= s;
    bs.wi = frame_.to_world(wi_world);
    // Light-leak rule: the sampled branch must agree with the geometric normal.
    const float gi = dot(bs.wi, ng_) * s;
    if (transmitted ? !(gi < 0) : !(gi > 0)) return std::nullopt;
    const float abs_cos = std::fabs(wi_l.z);
    if (!(abs_cos > 0)) return std::nullopt;

    if (delta) {
        bs.pdf = sel * branch_prob;
        if (!(bs.pdf > 0)) return std::nullopt;
        bs.weight = coefficient_over_prob / sel;
        bs.f = coefficient_over_prob * (branch_prob / abs_cos);
        return bs;
    }
    // eval_masked and pdf_masked of wi (their wo terms are the ones computed above).
    bs.f = eval_local(wo_l, bs.wi, s, lobe_mask, lambda, mode);
    bs.pdf = pdf_local(wo_l, bs.wi, s, w);
    if (layered_weight) {  // f and pdf (estimates) are for MIS; the walk's weight is the throughput
        if (!(bs.pdf > 0) || layered_weight->is_black()) return std::nullopt;
        bs.weight = *layered_weight / sel;
        return bs;
    }
    if (!(bs.pdf > 0) || bs.f.is_black()) return std::nullopt;
    bs.weight = bs.f * (abs_cos / bs.pdf);
    return bs;
}

std::optional<BsdfSample> LambertLobe::sample(Vec3 wo, Vec2 u, const Wavelengths& lambda) const {
    const float s = side_of(wo, ng);
    return s == 0 ? std::nullopt : sample_lambert(frame, ng, kd, kd_spectrum, s, u, lambda);
}

}  // namespace phos::shading
