// pbrt-v4's layered BSDF (PBR 4th ed., sec. 14.3; see layered_bxdf.h): the coat (pbrt-v4's
// DielectricBxDF restricted to reflection or transmission as its BxDFReflTransFlags do), the base
// (DiffuseBxDF, ConductorBxDF), and the random walks of f (sec. 14.3.2), sample and pdf (14.3.3).
// The interfaces are evaluated in a canonical frame where wo.z > 0 (a pair below is flipped, and
// the coat's eta inverted), which is how pbrt-v4's formulas treat the lower side.
#include "shading/layered_bxdf.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <initializer_list>
#include <limits>

#include "core/rng.h"
#include "core/warp.h"
#include "shading/bsdf.h"
#include "shading/dielectric.h"
#include "shading/fresnel.h"
#include "shading/phase.h"

namespace phos::shading {

static_assert(TransportMode{} == TransportMode::Radiance, "layered_bxdf.h's default transport mode");

bool LayeredSample::is_specular() const { return flags & kSpecular; }

uint32_t LayeredBxdf::coat_kind() const { return coat_smooth_ ? kSpecular : kGlossy; }

uint32_t LayeredBxdf::walk_kind() const {
    if (p_.base == LayeredParams::Base::Diffuse || medium_) return kDiffuse;
    return coat_smooth_ && base_smooth_ ? kSpecular : kGlossy;
}

namespace {

// Which of an interface's branches a sample or density may use (pbrt's BxDFReflTransFlags).
enum Parts : unsigned { kReflectPart = 1, kTransmitPart = 2, kAllParts = 3 };

constexpr float kSmoothAlpha = 1e-3f;

// An interface's sample: the new direction, the value, its density, and the branch.
struct Scatter {
    Vec3 wi;
    Spectrum f;
    float pdf = 0;
    bool specular = false;
    bool reflection = true;
};

bool usable(const std::optional<Scatter>& s) {
    return s && !s->f.is_black() && s->pdf > 0 && s->wi.z != 0 && std::isfinite(s->pdf);
}

TransportMode adjoint(TransportMode m) {
    return m == TransportMode::Radiance ? TransportMode::Importance : TransportMode::Radiance;
}

// Transmittance through a slab of depth dz along w (unit extinction).
float transmittance(float dz, Vec3 w) { return std::exp(-std::fabs(dz / w.z)); }

using dielectric::refract;

uint64_t hash_floats(std::initializer_list<float> values) {
    uint64_t h = 0x51ed2701a3b5c7e9ULL;
    for (float v : values) h = hash_combine(h, std::bit_cast<uint32_t>(v));
    return h;
}

// ---- The coat: pbrt-v4's DielectricBxDF (smooth: delta reflection / refraction; rough: Walter et
// al. 2007 with the generalised half vector), f and pdf 0 when smooth.
struct Coat {
    float eta = 1;
    bool smooth = true;
    const MicrofacetDistribution* dist = nullptr;

    // The generalised half vector of a canonical pair (wo.z > 0), facing +z; nullopt when
    // degenerate or back-facing (pbrt-v4 discards those).
    struct Half {
        Vec3 wm;
        float etap;
        bool reflect;
    };
    static std::optional<Half> half(Vec3 wo, Vec3 wi, float eta) {
        if (wo.z == 0 || wi.z == 0) return std::nullopt;
        const bool reflect = wi.z > 0;
        const float etap = reflect ? 1 : eta;
        Vec3 wm = wi * etap + wo;
        const float len2 = length_squared(wm);
        if (!(len2 > 0)) return std::nullopt;
        wm = wm / std::sqrt(len2);
        if (wm.z < 0) wm = -wm;
        if (dot(wm, wi) * wi.z < 0 || dot(wm, wo) * wo.z < 0) return std::nullopt;
        return Half{wm, etap, reflect};
    }

    float f(Vec3 wo, Vec3 wi, TransportMode mode) const {
        if (smooth) return 0;
        float e = eta;
        if (wo.z < 0) {
            wo = -wo;
            wi = -wi;
            e = 1 / e;
        }
        return dielectric::rough_eval(*dist, wo, wi, e, false, mode);  // Walter et al. 2007
    }

    float pdf(Vec3 wo, Vec3 wi, unsigned parts) const {
        if (smooth) return 0;
        float e = eta;
        if (wo.z < 0) {
            wo = -wo;
            wi = -wi;
            e = 1 / e;
        }
        const auto h = half(wo, wi, e);
        if (!h) return 0;
        const float r = fresnel_dielectric(dot(wo, h->wm), e);
        const float pr = (parts & kReflectPart) ? r : 0, pt = (parts & kTransmitPart) ? 1 - r : 0;
        if (pr + pt <= 0) return 0;
        const float pdf_wm = dist->pdf_wm(wo, h->wm);
        if (h->reflect) return pdf_wm / (4 * std::fabs(dot(wo, h->wm))) * pr / (pr + pt);
        const float s = dot(wi, h->wm) + dot(wo, h->wm) / h->etap;
        return pdf_wm * std::fabs(dot(wi, h->wm)) / (s * s) * pt / (pr + pt);
    }

    std::optional<Scatter> sample(Vec3 wo, float uc, Vec2 u, TransportMode mode, unsigned parts) const {
        float e = eta, flip = 1;
        if (wo.z < 0) {
            wo = -wo;
            e = 1 / e;
            flip = -1;
        }
        if (wo.z == 0) return std::nullopt;
        Scatter s;
        if (smooth) {
            const float r = fresnel_dielectric(wo.z, e), t = 1 - r;
            const float pr = (parts & kReflectPart) ? r : 0, pt = (parts & kTransmitPart) ? t : 0;
            if (pr + pt <= 0) return std::nullopt;
            s.specular = true;
            if (uc < pr / (pr + pt)) {
                s.wi = Vec3(-wo.x, -wo.y, wo.z);
                s.f = Spectrum(r / s.wi.z);
                s.pdf = pr / (pr + pt);
            } else {
                const auto wi = refract(wo, Vec3(0, 0, 1), e);
                if (!wi || wi->z == 0) return std::nullopt;
                s.wi = *wi;
                s.reflection = false;
                float ft = t / std::fabs(wi->z);
                if (mode == TransportMode::Radiance) ft /= e * e;
                s.f = Spectrum(ft);
                s.pdf = pt / (pr + pt);
            }
        } else {
            const Vec3 wm = dist->sample_wm(wo, u);
            const float cos_om = dot(wo, wm);
            if (!(cos_om > 0)) return std::nullopt;
            const float r = fresnel_dielectric(cos_om, e);
            const float pr = (parts & kReflectPart) ? r : 0, pt = (parts & kTransmitPart) ? 1 - r : 0;
            if (pr + pt <= 0) return std::nullopt;
            const float dm = dist->D(wm);
            if (uc < pr / (pr + pt)) {
                const Vec3 wi = reflect(wo, wm);
                if (wi.z <= 0) return std::nullopt;
                s.wi = wi;
                s.pdf = dist->pdf_wm(wo, wm) / (4 * cos_om) * pr / (pr + pt);
                s.f = Spectrum(dm * dist->G(wo, wi) * r / (4 * wi.z * wo.z));
            } else {
                const auto wi = refract(wo, wm, e);
                if (!wi || wi->z >= 0) return std::nullopt;
                const float cos_im = dot(*wi, wm), den = cos_im + cos_om / e;
                const float den2 = den * den;
                s.wi = *wi;
                s.reflection = false;
                s.pdf = dist->pdf_wm(wo, wm) * std::fabs(cos_im) / den2 * pt / (pr + pt);
                float ft =
                    dm * dist->G(wo, *wi) * (1 - r) * std::fabs(cos_im * cos_om / (wi->z * wo.z * den2));
                if (mode == TransportMode::Radiance) ft /= e * e;
                s.f = Spectrum(ft);
            }
        }
        s.wi = s.wi * flip;
        return s;
    }
};

// ---- The base: pbrt-v4's DiffuseBxDF or ConductorBxDF, reflection only; `smooth`: a smooth
// conductor (a delta). Without `valued`, only directions and densities are computed (f is 1, or
// 0 for a black diffuse base), for pdf().
struct Base {
    bool conductor = false, smooth = false, valued = true, black = false;
    const MicrofacetDistribution* dist = nullptr;
    Spectrum r, eta, k;

    Spectrum fresnel(float cos_i) const {
        Spectrum f;
        for (int i = 0; i < spectrum::kSpectrumSamples; ++i) f[i] = fresnel_conductor(cos_i, eta[i], k[i]);
        return f;
    }

    Spectrum f(Vec3 wo, Vec3 wi) const {
        if (wo.z * wi.z <= 0) return Spectrum(0);
        if (!conductor) return r * kInvPi;
        if (smooth) return Spectrum(0);
        if (wo.z < 0) {
            wo = -wo;
            wi = -wi;
        }
        Vec3 wm = wo + wi;
        const float len2 = length_squared(wm);
        if (!(len2 > 0)) return Spectrum(0);
        wm = wm / std::sqrt(len2);
        return fresnel(std::fabs(dot(wo, wm))) * (dist->D(wm) * dist->G(wo, wi) / (4 * wi.z * wo.z));
    }

    float pdf(Vec3 wo, Vec3 wi) const {
        if (wo.z * wi.z <= 0) return 0;
        if (!conductor) return std::fabs(wi.z) * kInvPi;
        if (smooth) return 0;
        if (wo.z < 0) {
            wo = -wo;
            wi = -wi;
        }
        Vec3 wm = wo + wi;
        const float len2 = length_squared(wm);
        if (!(len2 > 0)) return 0;
        wm = wm / std::sqrt(len2);
        return dist->pdf_wm(wo, wm) / (4 * std::fabs(dot(wo, wm)));
    }

    std::optional<Scatter> sample(Vec3 wo, Vec2 u) const {
        Scatter s;
        if (!conductor) {
            s.wi = warp::cosine_hemisphere(u);
            if (wo.z < 0) s.wi.z = -s.wi.z;
            s.pdf = std::fabs(s.wi.z) * kInvPi;
            s.f = valued ? r * kInvPi : Spectrum(black ? 0.0f : 1.0f);
            return s;
        }
        if (wo.z == 0) return std::nullopt;
        if (smooth) {
            s.wi = Vec3(-wo.x, -wo.y, wo.z);
            s.pdf = 1;
            s.specular = true;
            const float c = std::fabs(s.wi.z);
            s.f = valued ? fresnel(c) / c : Spectrum(1);
            return s;
        }
        const float flip = wo.z < 0 ? -1.0f : 1.0f;
        wo = wo * flip;
        const Vec3 wm = dist->sample_wm(wo, u);
        const Vec3 wi = reflect(wo, wm);
        if (wi.z <= 0) return std::nullopt;
        const float cos_om = std::fabs(dot(wo, wm));
        s.wi = wi * flip;
        s.pdf = dist->pdf_wm(wo, wm) / (4 * cos_om);
        s.f = valued ? fresnel(cos_om) * (dist->D(wm) * dist->G(wo, wi) / (4 * wi.z * wo.z)) : Spectrum(1);
        return s;
    }
};

// Distance along z to the next extinction event for direction w (unit extinction).
float sample_depth(float u, Vec3 w) { return -std::log1p(-u) * std::fabs(w.z); }

// The random walks' deterministic random numbers.
constexpr uint64_t kEvalStream = 0x6c61796572656466ULL, kSampleStream = 0x6c61796572656473ULL,
                   kPdfStream = 0x6c61796572656470ULL;

}  // namespace

LayeredBxdf::LayeredBxdf(const LayeredParams& params) : p_(params) {
    if (p_.eta == 0) p_.eta = 1;
    p_.thickness = std::max(p_.thickness, std::numeric_limits<float>::min());
    p_.n_samples = std::max(p_.n_samples, 1);
    p_.max_depth = std::max(p_.max_depth, 0);
    p_.g = std::clamp(p_.g, -1.0f, 1.0f);
    coat_smooth_ = p_.eta == 1 || std::max(p_.coat_alpha_x, p_.coat_alpha_y) < kSmoothAlpha;
    coat_dist_ = MicrofacetDistribution(p_.coat_alpha_x, p_.coat_alpha_y);
    const bool conductor = p_.base == LayeredParams::Base::Conductor;
    base_smooth_ = conductor && std::max(p_.base_alpha_x, p_.base_alpha_y) < kSmoothAlpha;
    base_dist_ = MicrofacetDistribution(p_.base_alpha_x, p_.base_alpha_y);
    medium_ = !p_.albedo.is_black();
    flags_ = kReflection;
    if (coat_smooth_) flags_ |= kSpecular;
    if (!conductor || medium_)
        flags_ |= kDiffuse;
    else if (!coat_smooth_ || !base_smooth_)
        flags_ |= kGlossy;
}

namespace {

// The coat and base of a LayeredBxdf at `lambda` (spectral values) or without values (pdf()).
struct Stack {
    Coat coat;
    Base base;
};

Stack make_stack(const LayeredParams& p, bool coat_smooth, bool base_smooth,
                 const MicrofacetDistribution& coat_dist, const MicrofacetDistribution& base_dist,
                 const Wavelengths* lambda) {
    Stack s;
    s.coat.eta = p.eta;
    s.coat.smooth = coat_smooth;
    s.coat.dist = &coat_dist;
    s.base.conductor = p.base == LayeredParams::Base::Conductor;
    s.base.smooth = base_smooth;
    s.base.dist = &base_dist;
    s.base.valued = lambda != nullptr;
    s.base.black = !s.base.conductor && p.reflectance.is_black();
    if (!lambda) return s;
    if (!s.base.conductor) {
        s.base.r = p.reflectance.sample(*lambda);
        for (float& v : s.base.r.v) v = std::clamp(v, 0.0f, 1.0f);
        return s;
    }
    if (p.conductor_from_reflectance) {
        Spectrum r = p.reflectance.sample(*lambda);
        s.base.eta = Spectrum(1);
        for (int i = 0; i < spectrum::kSpectrumSamples; ++i) {
            const float ri = std::clamp(r[i], 0.0f, 0.9999f);
            s.base.k[i] = 2 * std::sqrt(ri) / std::sqrt(1 - ri);
        }
    } else {
        s.base.eta = p.conductor_eta.at(*lambda);
        s.base.k = p.conductor_k.at(*lambda);
    }
    s.base.eta = s.base.eta / p.eta;
    s.base.k = s.base.k / p.eta;
    return s;
}

}  // namespace

Spectrum LayeredBxdf::f(Vec3 wo, Vec3 wi, const Wavelengths& lambda, TransportMode mode,
                        LayeredPart part) const {
    // Two-sided: always enter through the coat. The bases are opaque, so only reflection remains,
    // and the exit is the coat (exit depth = thickness).
    if (wo.z < 0) {
        wo = -wo;
        wi = -wi;
    }
    if (!(wo.z > 0 && wi.z > 0)) return Spectrum(0);
    const Stack st = make_stack(p_, coat_smooth_, base_smooth_, coat_dist_, base_dist_, &lambda);
    const Coat& coat = st.coat;
    const Base& base = st.base;
    const float thick = p_.thickness;
    Spectrum albedo;
    if (medium_) {
        albedo = p_.albedo.sample(lambda);
        for (float& v : albedo.v) v = std::clamp(v, 0.0f, 1.0f);
    }
    const PhaseFunction phase{p_.g};

    // The coat's own reflection.
    if (part == LayeredPart::Coat) return Spectrum(coat.f(wo, wi, mode));
    Spectrum f(part == LayeredPart::All ? float(p_.n_samples) * coat.f(wo, wi, mode) : 0.0f);
    Sampler rng(p_.seed, hash_floats({wo.x, wo.y, wo.z}), hash_floats({wi.x, wi.y, wi.z}), kEvalStream);
    for (int s = 0; s < p_.n_samples; ++s) {
        // Enter through the coat at wo; the exit's virtual light comes through the coat at wi.
        float uc = rng.next();
        Vec2 u = rng.next2();
        const auto wos = coat.sample(wo, uc, u, mode, kTransmitPart);
        if (!usable(wos)) continue;
        uc = rng.next();
        u = rng.next2();
        const auto wis = coat.sample(wi, uc, u, adjoint(mode), kTransmitPart);
        if (!usable(wis)) continue;

        Spectrum beta = wos->f * (std::fabs(wos->wi.z) / wos->pdf);
        float z = thick;
        Vec3 w = wos->wi;
        for (int depth = 0; depth < p_.max_depth; ++depth) {
            // Russian roulette (pbrt-v4: after 3 events, below a throughput of 0.25).
            if (depth > 3 && beta.max() < 0.25f) {
                const float q = std::max(0.0f, 1 - beta.max());
                if (rng.next() < q) break;
                beta = beta / (1 - q);
            }
            if (!medium_) {
                z = z == thick ? 0 : thick;
                beta *= transmittance(thick, w);
            } else {
                const float dz = sample_depth(rng.next(), w);
                const float zp = w.z > 0 ? z + dz : z - dz;
                if (zp == z) continue;
                if (0 < zp && zp < thick) {
                    // Scattering in the slab: connect to the exit through wis (MIS against the
                    // phase function's own sampling when the coat is rough).
                    const float p_exit = phase.eval(-w, -wis->wi);
                    float wt = 1;
                    if (!coat.smooth) wt = warp::power_heuristic(wis->pdf, p_exit);
                    f += beta * albedo * wis->f *
                         (p_exit * wt * transmittance(zp - thick, wis->wi) / wis->pdf);
                    Vec3 nw;
                    const float ppdf = phase.sample(-w, rng.next2(), nw);
                    if (!(ppdf > 0) || nw.z == 0) continue;
                    beta *= albedo;  // p / pdf = 1 for Henyey-Greenstein
                    w = nw;
                    z = zp;
                    // Leaving upwards: the phase sample's own connection through the coat.
                    if (z < thick && w.z > 0 && !coat.smooth) {
                        const float f_exit = coat.f(-w, wi, mode);
                        if (f_exit > 0) {
                            // The density of wis's strategy for this inner direction (not
                            // pbrt-v4's reverse density; see layered_bxdf.h).
                            const float exit_pdf = coat.pdf(wi, -w, kTransmitPart);
                            const float wt2 = warp::power_heuristic(ppdf, exit_pdf);
                            f += beta * (transmittance(zp - thick, w) * f_exit * wt2);
                        }
                    }
                    continue;
                }
                z = std::clamp(zp, 0.0f, thick);
            }

            if (z == thick) {
                // The coat's underside: reflect back into the slab (its transmission is what the
                // connections above account for).
                const auto bs = coat.sample(-w, rng.next(), rng.next2(), mode, kReflectPart);
                if (!usable(bs)) break;
                beta *= bs->f * (std::fabs(bs->wi.z) / bs->pdf);
                w = bs->wi;
            } else {
                // The base: connect to the exit through wis, then scatter.
                if (!base.smooth) {
                    float wt = 1;
                    if (!coat.smooth) wt = warp::power_heuristic(wis->pdf, base.pdf(-w, -wis->wi));
                    f += beta * base.f(-w, -wis->wi) * wis->f *
                         (std::fabs(wis->wi.z) * wt * transmittance(thick, wis->wi) / wis->pdf);
                }
                const Vec2 ub = rng.next2();
                const auto bs = base.sample(-w, ub);
                if (!usable(bs)) break;
                beta *= bs->f * (std::fabs(bs->wi.z) / bs->pdf);
                w = bs->wi;
                if (!coat.smooth) {
                    const float f_exit = coat.f(-w, wi, mode);
                    if (f_exit > 0) {
                        float wt = 1;  // MIS against wis's strategy drawing the same inner direction
                        if (!bs->specular)
                            wt = warp::power_heuristic(bs->pdf, coat.pdf(wi, -w, kTransmitPart));
                        f += beta * (transmittance(thick, bs->wi) * f_exit * wt);
                    }
                }
            }
        }
    }
    return f / float(p_.n_samples);
}

std::optional<LayeredSample> LayeredBxdf::sample(Vec3 wo, float uc, Vec2 u, const Wavelengths& lambda,
                                                 TransportMode mode, LayeredPart part) const {
    bool flip = false;
    if (wo.z < 0) {
        wo = -wo;
        flip = true;
    }
    const Stack st = make_stack(p_, coat_smooth_, base_smooth_, coat_dist_, base_dist_, &lambda);
    const Coat& coat = st.coat;
    const Base& base = st.base;
    const auto finish = [&](Vec3 wi, const Spectrum& f, float pdf, uint32_t flags) {
        LayeredSample s;
        s.wi = flip ? -wi : wi;
        s.f = f;
        s.pdf = pdf;
        s.flags = flags;
        s.weight = f * (std::fabs(wi.z) / pdf);
        s.pdf_is_proportional = true;
        return s;
    };

    // The entrance: the coat reflects (done) or transmits into the slab.
    const unsigned entrance =
        part == LayeredPart::All ? kAllParts : (part == LayeredPart::Coat ? kReflectPart : kTransmitPart);
    const auto bs = coat.sample(wo, uc, u, mode, entrance);
    if (!usable(bs)) return std::nullopt;
    if (bs->reflection) {
        LayeredSample s = finish(bs->wi, bs->f, bs->pdf, kReflection | (bs->specular ? kSpecular : kGlossy));
        s.pdf_is_proportional = part != LayeredPart::Coat;
        s.part = LayeredPart::Coat;
        return s;
    }

    Vec3 w = bs->wi;
    bool specular_path = bs->specular;
    Sampler rng(p_.seed, hash_floats({wo.x, wo.y, wo.z}), hash_floats({uc, u.x, u.y}), kSampleStream);
    Spectrum f = bs->f * std::fabs(bs->wi.z);
    float pdf = bs->pdf;
    const float thick = p_.thickness;
    Spectrum albedo;
    if (medium_) {
        albedo = p_.albedo.sample(lambda);
        for (float& v : albedo.v) v = std::clamp(v, 0.0f, 1.0f);
    }
    const PhaseFunction phase{p_.g};
    float z = thick;
    for (int depth = 0; depth < p_.max_depth; ++depth) {
        // Russian roulette on the largest throughput over the path's wavelengths, as pbrt-v4
        // (see layered_bxdf.h); its number is drawn whatever the throughput, so the directions
        // the walk draws do not depend on the wavelengths.
        if (depth > 3) {
            const float u_rr = rng.next();
            const float rr = f.max() / pdf;
            if (rr < 0.25f) {
                const float q = std::max(0.0f, 1 - rr);
                if (u_rr < q) return std::nullopt;
                pdf *= 1 - q;
            }
        }
        if (w.z == 0) return std::nullopt;
        if (medium_) {
            const float dz = sample_depth(rng.next(), w);
            const float zp = w.z > 0 ? z + dz : z - dz;
            if (zp == z) return std::nullopt;
            if (0 < zp && zp < thick) {
                Vec3 nw;
                const float ppdf = phase.sample(-w, rng.next2(), nw);
                if (!(ppdf > 0) || nw.z == 0) return std::nullopt;
                f *= albedo * ppdf;
                pdf *= ppdf;
                specular_path = false;
                w = nw;
                z = zp;
                continue;
            }
            z = std::clamp(zp, 0.0f, thick);
        } else {
            z = z == thick ? 0 : thick;
            f *= transmittance(thick, w);
        }
        const float uci = rng.next();
        const Vec2 ui = rng.next2();
        const auto is = z == 0 ? base.sample(-w, ui) : coat.sample(-w, uci, ui, mode, kAllParts);
        if (!usable(is)) return std::nullopt;
        f *= is->f;
        pdf *= is->pdf;
        specular_path = specular_path && is->specular;
        w = is->wi;
        if (!is->reflection) {
            // Left through the coat (the base never transmits).
            const uint32_t flags =
                (w.z > 0 ? kReflection : kTransmission) | (specular_path ? kSpecular : kGlossy);
            return finish(w, f, pdf, flags);
        }
        f *= std::fabs(is->wi.z);
    }
    return std::nullopt;
}

float LayeredBxdf::pdf(Vec3 wo, Vec3 wi, LayeredPart part) const {
    if (wo.z < 0) {
        wo = -wo;
        wi = -wi;
    }
    const Stack st = make_stack(p_, coat_smooth_, base_smooth_, coat_dist_, base_dist_, nullptr);
    const Coat& coat = st.coat;
    const Base& base = st.base;
    if (part == LayeredPart::Coat) return wo.z > 0 && wi.z > 0 ? coat.pdf(wo, wi, kReflectPart) : 0.0f;
    Sampler rng(p_.seed, hash_floats({wi.x, wi.y, wi.z}), hash_floats({wo.x, wo.y, wo.z}), kPdfStream);
    float pdf_sum = 0;
    // Only reflection has density (the bases are opaque): the transmission-transmission term of
    // pbrt-v4's estimate is always 0 here.
    if (wo.z > 0 && wi.z > 0) {
        if (part == LayeredPart::All) pdf_sum += float(p_.n_samples) * coat.pdf(wo, wi, kReflectPart);
        for (int s = 0; s < p_.n_samples; ++s) {
            // The transmission-reflection-transmission term (PBR 4th ed., eq. 14.38 and its MIS).
            float uc = rng.next();
            Vec2 u = rng.next2();
            const auto wos = coat.sample(wo, uc, u, TransportMode::Radiance, kTransmitPart);
            uc = rng.next();
            u = rng.next2();
            const auto wis = coat.sample(wi, uc, u, TransportMode::Importance, kTransmitPart);
            if (!usable(wos) || !usable(wis)) continue;
            if (coat.smooth) {
                pdf_sum += base.pdf(-wos->wi, -wis->wi);
                continue;
            }
            const auto rs = base.sample(-wos->wi, rng.next2());
            if (!usable(rs)) continue;
            if (rs->specular) {
                pdf_sum += coat.pdf(-rs->wi, wi, kAllParts);
            } else {
                const float r_pdf = base.pdf(-wos->wi, -wis->wi);
                pdf_sum += warp::power_heuristic(wis->pdf, r_pdf) * r_pdf;
                const float t_pdf = coat.pdf(-rs->wi, wi, kAllParts);
                pdf_sum += warp::power_heuristic(rs->pdf, t_pdf) * t_pdf;
            }
        }
    }
    // pbrt-v4: Lerp(0.9, 1 / (4 pi), estimate).
    return 0.1f * warp::uniform_sphere_pdf() + 0.9f * pdf_sum / float(p_.n_samples);
}

float LayeredBxdf::coat_albedo(float cos_o) const { return fresnel_dielectric(std::fabs(cos_o), p_.eta); }

float LayeredBxdf::walk_albedo(float cos_o, float base_albedo, float fi) const {
    const float a = std::clamp(base_albedo, 0.0f, 1.0f);
    return (1 - coat_albedo(cos_o)) * a * (1 - fi) / (1 - a * fi);
}

float LayeredBxdf::internal_reflectance(float eta) {
    // Midpoint rule in mu = cos theta over 2 mu F(mu, 1 / eta) (error ~1e-4 with the kink at the
    // critical angle).
    if (eta == 0) eta = 1;
    const int n = 256;
    float acc = 0;
    for (int i = 0; i < n; ++i) {
        const float mu = (float(i) + 0.5f) / float(n);
        acc += fresnel_dielectric(mu, 1 / eta) * 2 * mu;
    }
    return acc / float(n);
}

}  // namespace phos::shading
