// pbrt-v4's hair BxDF (Chiang et al. 2016; d'Eon et al. 2011): see hair_bxdf.h for the model, the
// frame and the conventions. Equation numbers are PBR 3rd ed. sec. 9.9 unless a paper is named.
#include "shading/hair_bxdf.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "shading/bsdf.h"
#include "shading/fresnel.h"

namespace phos::shading {

// A BSDF holding one is copied as bytes between processes (MPI ranks).
static_assert(std::is_trivially_copyable_v<HairBxdf>);

namespace {

constexpr double kPiD = 3.14159265358979323846;

template <typename T>
constexpr T sqr(T x) {
    return x * x;
}

// e^(-x) I0(x), I0 the modified Bessel function of the first kind of order 0, for x >= 0: the
// polynomial approximations of Abramowitz & Stegun 9.8.1 (x <= 3.75) and 9.8.2 (x > 3.75),
// relative error below 5e-7 everywhere (pbrt sums ten terms of I0's series, 0.3 % short at x = 10,
// and past 12 uses log I0's asymptotic form to first order).
float scaled_bessel_i0(float x) {
    if (x <= 3.75f) {
        const float t = sqr(x / 3.75f);
        return std::exp(-x) *
               (1 + t * (3.5156229f +
                         t * (3.0899424f +
                              t * (1.2067492f + t * (0.2659732f + t * (0.0360768f + t * 0.0045813f))))));
    }
    const float t = 3.75f / x;
    return (0.39894228f +
            t * (0.01328592f +
                 t * (0.00225319f +
                      t * (-0.00157565f +
                           t * (0.00916281f +
                                t * (-0.02057706f +
                                     t * (0.02635537f + t * (-0.01647633f + t * 0.00392377f)))))))) /
           std::sqrt(x);
}

// d'Eon et al. 2011, eq. 7: M(theta_i) = exp(-sin_i sin_o / v) I0(cos_i cos_o / v) / (2 v sinh(1/v)),
// a density over cos(theta_i) d theta_i. Written as
// exp((cos_i cos_o - sin_i sin_o - 1) / v + log_norm) (e^(-a) I0(a)), a = cos_i cos_o / v,
// log_norm = -log v - log(1 - e^(-2/v)) (as 2 v sinh(1/v) = v e^(1/v) (1 - e^(-2/v))), so that no
// term overflows for any v (pbrt switches to logarithms for v <= 0.1 for the same reason); the
// exponent, cos(theta_i + theta_o) - 1 over v, is formed in double against cancellation.
float longitudinal(float cos_i, float cos_o, float sin_i, float sin_o, float inv_v, float log_norm) {
    const double e = (double(cos_i) * double(cos_o) - double(sin_i) * double(sin_o) - 1) * double(inv_v);
    return std::exp(float(e) + log_norm) * scaled_bessel_i0(cos_i * cos_o * inv_v);
}

// The logistic distribution of scale s (PBR3 eqs. 9.50-9.52): its density and CDF; trimmed to
// [-pi, pi], the density is divided by CDF(pi) - CDF(-pi) and sampled by the inverse CDF.
float logistic(float x, float s) {
    const float e = std::exp(-std::fabs(x) / s);
    return e / (s * sqr(1 + e));
}
double logistic_cdf(double x, double s) { return 1 / (1 + std::exp(-x / s)); }
float sample_trimmed_logistic(float u, float s, double cdf_lo, double cdf_hi) {
    const double q = cdf_lo + double(u) * (cdf_hi - cdf_lo);
    const double x = -double(s) * std::log(1 / q - 1);
    return float(std::clamp(x, -kPiD, kPiD));
}

// A_p for one wavelength (PBR3 eqs. 9.46-9.48): the Fresnel reflectance f and the transmittance t
// of one crossing; the last term sums the paths of p >= 3 as a geometric series.
void attenuation(float f, float t, float ap[HairBxdf::kPMax + 1]) {
    ap[0] = f;
    ap[1] = sqr(1 - f) * t;
    ap[2] = ap[1] * t * f;
    const float rest = 1 - t * f;
    ap[3] = rest > 0 ? ap[2] * f * t / rest : 0;
}

float d_of_beta_n(float b) {
    // Chiang et al. 2016, eq. 9's denominator.
    return 5.969f - 0.215f * b + 2.532f * sqr(b) - 10.73f * b * b * b + 5.574f * sqr(sqr(b)) +
           0.245f * sqr(sqr(b)) * b;
}

float clamp_beta(float b) { return std::clamp(std::isnan(b) ? 1.0f : b, 0.01f, 1.0f); }

}  // namespace

Rgb hair_sigma_a_from_concentration(float eumelanin, float pheomelanin) {
    const Rgb eu(0.419f, 0.697f, 1.37f), pheo(0.187f, 0.4f, 1.05f);
    return eu * std::max(0.0f, eumelanin) + pheo * std::max(0.0f, pheomelanin);
}

float hair_sigma_a_from_reflectance(float c, float beta_n) {
    return sqr(std::log(std::clamp(c, 0.0f, 1.0f)) / d_of_beta_n(beta_n));
}

Rgb hair_sigma_a_from_reflectance(Rgb c, float beta_n) {
    return {hair_sigma_a_from_reflectance(c.r, beta_n), hair_sigma_a_from_reflectance(c.g, beta_n),
            hair_sigma_a_from_reflectance(c.b, beta_n)};
}

float hair_reflectance_from_sigma_a(float sigma_a, float beta_n) {
    return std::exp(-d_of_beta_n(beta_n) * std::sqrt(std::max(0.0f, sigma_a)));
}

HairAbsorption HairAbsorption::of_sigma_a(Rgb sigma_a, spectrum::RgbSpectrum::Fit fit) {
    HairAbsorption a;
    a.rgb_ = Rgb(std::max(0.0f, sigma_a.r), std::max(0.0f, sigma_a.g), std::max(0.0f, sigma_a.b));
    a.spectrum_ = spectrum::RgbSpectrum(a.rgb_, spectrum::RgbSpectrum::Use::Unbounded, fit);
    return a;
}

HairAbsorption HairAbsorption::of_reflectance(Rgb colour, float beta_n, spectrum::RgbSpectrum::Fit fit) {
    const float bn = clamp_beta(beta_n);
    const Rgb c(std::clamp(colour.r, 0.0f, 1.0f), std::clamp(colour.g, 0.0f, 1.0f),
                std::clamp(colour.b, 0.0f, 1.0f));
    HairAbsorption a;
    a.rgb_ = hair_sigma_a_from_reflectance(c, bn);
    a.spectrum_ = spectrum::RgbSpectrum(c, spectrum::RgbSpectrum::Use::Albedo, fit);
    a.inv_d_ = 1 / d_of_beta_n(bn);
    return a;
}

HairAbsorption HairAbsorption::of_concentration(float eumelanin, float pheomelanin,
                                                spectrum::RgbSpectrum::Fit fit) {
    return of_sigma_a(hair_sigma_a_from_concentration(eumelanin, pheomelanin), fit);
}

Spectrum HairAbsorption::at(const Wavelengths& lambda) const {
    Spectrum s = spectrum_.sample(lambda);
    if (inv_d_ == 0) return s;
    for (int i = 0; i < spectrum::kSpectrumSamples; ++i)
        s[i] = sqr(std::log(std::clamp(s[i], 0.0f, 1.0f)) * inv_d_);
    return s;
}

HairBxdf::HairBxdf(const HairParams& p) : eta_(std::max(1.0f, p.eta)), sigma_a_(p.sigma_a) {
    set_h(p.h);
    const float bm = clamp_beta(p.beta_m), bn = clamp_beta(p.beta_n);
    // Chiang et al. 2016, eq. 7 (longitudinal variances) and eq. 8 (logistic scale).
    v_[0] = sqr(0.726f * bm + 0.812f * sqr(bm) + 3.7f * std::pow(bm, 20.0f));
    v_[1] = 0.25f * v_[0];
    v_[2] = 4 * v_[0];
    v_[3] = v_[2];
    for (int q = 0; q <= kPMax; ++q) {
        inv_v_[q] = 1 / v_[q];
        log_norm_[q] = float(-std::log(double(v_[q])) - std::log1p(-std::exp(-2.0 / double(v_[q]))));
    }
    s_ = float(std::sqrt(kPiD / 8)) * (0.265f * bn + 1.194f * sqr(bn) + 5.372f * std::pow(bn, 22.0f));
    cdf_lo_ = logistic_cdf(-kPiD, s_);
    cdf_hi_ = logistic_cdf(kPiD, s_);
    logistic_norm_ = float(1 / (cdf_hi_ - cdf_lo_));
    // sin / cos of 2^k alpha, k = 0, 1, 2 (double-angle formulas).
    sin_2k_alpha_[0] = std::sin(p.alpha_degrees * kPi / 180);
    cos_2k_alpha_[0] = std::sqrt(std::max(0.0f, 1 - sqr(sin_2k_alpha_[0])));
    for (int k = 1; k < kPMax; ++k) {
        sin_2k_alpha_[k] = 2 * cos_2k_alpha_[k - 1] * sin_2k_alpha_[k - 1];
        cos_2k_alpha_[k] = sqr(cos_2k_alpha_[k - 1]) - sqr(sin_2k_alpha_[k - 1]);
    }
}

void HairBxdf::set_h(float h) {
    h_ = std::clamp(std::isnan(h) ? 0.0f : h, -1.0f, 1.0f);
    gamma_o_ = std::asin(h_);
    cos_gamma_o_ = std::sqrt(std::max(0.0f, 1 - sqr(h_)));
}

HairBxdf::Geometry HairBxdf::geometry(Vec3 wo) const {
    Geometry g;
    g.sin_o = std::clamp(wo.x, -1.0f, 1.0f);
    g.cos_o = std::sqrt(std::max(0.0f, 1 - sqr(g.sin_o)));
    g.phi_o = std::atan2(wo.z, wo.y);
    // The cuticle tilt (PBR3 sec. 9.9.3): R towards theta_o - 2 alpha, TT theta_o + alpha, TRT
    // theta_o + 4 alpha (pbrt's signs); the residual lobe untilted.
    const float so = g.sin_o, co = g.cos_o;
    g.sin_tilted[0] = so * cos_2k_alpha_[1] - co * sin_2k_alpha_[1];
    g.cos_tilted[0] = co * cos_2k_alpha_[1] + so * sin_2k_alpha_[1];
    g.sin_tilted[1] = so * cos_2k_alpha_[0] + co * sin_2k_alpha_[0];
    g.cos_tilted[1] = co * cos_2k_alpha_[0] - so * sin_2k_alpha_[0];
    g.sin_tilted[2] = so * cos_2k_alpha_[2] + co * sin_2k_alpha_[2];
    g.cos_tilted[2] = co * cos_2k_alpha_[2] - so * sin_2k_alpha_[2];
    g.sin_tilted[3] = so;
    g.cos_tilted[3] = co;
    for (float& c : g.cos_tilted) c = std::fabs(c);
    // The refracted ray (PBR3 eqs. 9.40-9.42): theta_t by Snell in the longitudinal plane, gamma_t
    // by the modified index eta' = sqrt(eta^2 - sin^2 theta_o) / cos theta_o (Bravais).
    const float sin_t = so / eta_, cos_t = std::sqrt(std::max(0.0f, 1 - sqr(sin_t)));
    const float eta_cos = std::sqrt(std::max(0.0f, sqr(eta_) - sqr(so)));  // eta' cos(theta_o)
    const float sin_gamma_t = eta_cos > 0 ? std::clamp(h_ * co / eta_cos, -1.0f, 1.0f) : 0.0f;
    const float cos_gamma_t = std::sqrt(std::max(0.0f, 1 - sqr(sin_gamma_t)));
    g.gamma_t = std::asin(sin_gamma_t);
    g.path = std::max(2 * cos_gamma_t / std::max(cos_t, 1e-6f), 1e-6f);
    g.fresnel = fresnel_dielectric(co * cos_gamma_o_, eta_);
    return g;
}

void HairBxdf::lobe_densities(const Geometry& g, Vec3 wi, float out[kPMax + 1]) const {
    const float sin_i = std::clamp(wi.x, -1.0f, 1.0f);
    const float cos_i = std::sqrt(std::max(0.0f, 1 - sqr(sin_i)));
    const float phi = std::atan2(wi.z, wi.y) - g.phi_o;
    for (int p = 0; p < kPMax; ++p) {
        // N_p around Phi(p) = 2 p gamma_t - 2 gamma_o + p pi (PBR3 eq. 9.49), the difference wrapped
        // to [-pi, pi].
        const double centre = 2.0 * p * g.gamma_t - 2.0 * gamma_o_ + p * kPiD;
        const double d = double(phi) - centre;
        const float dphi = float(d - 2 * kPiD * std::round(d * (0.5 / kPiD)));
        out[p] = longitudinal(cos_i, g.cos_tilted[p], sin_i, g.sin_tilted[p], inv_v_[p], log_norm_[p]) *
                 logistic(dphi, s_) * logistic_norm_;
    }
    out[kPMax] =
        longitudinal(cos_i, g.cos_o, sin_i, g.sin_o, inv_v_[kPMax], log_norm_[kPMax]) * float(1 / (2 * kPiD));
}

void HairBxdf::lobe_probabilities(const Geometry& g, float out[kPMax + 1]) const {
    const Rgb sa = sigma_a_.rgb();
    float sum = 0;
    for (int p = 0; p <= kPMax; ++p) out[p] = 0;
    for (int c = 0; c < 3; ++c) {
        float ap[kPMax + 1];
        attenuation(g.fresnel, std::exp(-sa[c] * g.path), ap);
        for (int p = 0; p <= kPMax; ++p) out[p] += ap[p];
    }
    for (int p = 0; p <= kPMax; ++p) sum += out[p];
    for (int p = 0; p <= kPMax; ++p) out[p] = sum > 0 ? out[p] / sum : 0.0f;
}

Rgb HairBxdf::albedo(Vec3 wo) const {
    const Geometry g = geometry(wo);
    const Rgb sa = sigma_a_.rgb();
    Rgb r;
    for (int c = 0; c < 3; ++c) {
        float ap[kPMax + 1];
        attenuation(g.fresnel, std::exp(-sa[c] * g.path), ap);
        r[c] = ap[0] + ap[1] + ap[2] + ap[3];
    }
    return r;
}

namespace {
// sum_p M_p N_p A_p(lambda) for each wavelength.
Spectrum weighted_sum(const float dens[HairBxdf::kPMax + 1], float fresnel, float path,
                      const Spectrum& sigma_a) {
    Spectrum s;
    for (int i = 0; i < spectrum::kSpectrumSamples; ++i) {
        float ap[HairBxdf::kPMax + 1];
        attenuation(fresnel, std::exp(-sigma_a[i] * path), ap);
        float v = 0;
        for (int p = 0; p <= HairBxdf::kPMax; ++p) v += dens[p] * ap[p];
        s[i] = v;
    }
    return s;
}
}  // namespace

uint32_t HairBxdf::flags() { return kGlossy | kReflection | kTransmission; }

Spectrum HairBxdf::f(Vec3 wo, Vec3 wi, const Wavelengths& lambda) const {
    const Geometry g = geometry(wo);
    float dens[kPMax + 1];
    lobe_densities(g, wi, dens);
    Spectrum s = weighted_sum(dens, g.fresnel, g.path, sigma_a_.at(lambda));
    const float c = std::fabs(wi.z);
    return c > 0 ? s / c : s;  // pbrt leaves f undivided where wi.z = 0
}

float HairBxdf::pdf(Vec3 wo, Vec3 wi) const {
    const Geometry g = geometry(wo);
    float dens[kPMax + 1], prob[kPMax + 1];
    lobe_densities(g, wi, dens);
    lobe_probabilities(g, prob);
    float pdf = 0;
    for (int p = 0; p <= kPMax; ++p) pdf += dens[p] * prob[p];
    return pdf;
}

std::optional<HairSample> HairBxdf::sample(Vec3 wo, float uc, Vec2 u, const Wavelengths& lambda) const {
    const Geometry g = geometry(wo);
    float prob[kPMax + 1];
    lobe_probabilities(g, prob);
    // The lobe, by its probability; uc remapped to [0, 1) within it (pbrt's SampleDiscrete).
    int p = 0;
    float below = 0;
    while (p < kPMax && uc >= below + prob[p]) below += prob[p++];
    while (p > 0 && prob[p] <= 0) below -= prob[--p];  // rounding past the last non-empty lobe
    if (!(prob[p] > 0)) return std::nullopt;
    uc = std::clamp((uc - below) / prob[p], 0.0f, 0x1.fffffep-1f);

    // theta_i from M_p (d'Eon et al. 2011, sec. 4.3; PBR3 eq. 9.44's sampling): the cosine of a von
    // Mises-Fisher direction of concentration 1 / v around the tilted specular cone, then its
    // latitude relative to the fibre.
    const double v = v_[p];
    const double cos_theta =
        std::clamp(1 + v * std::log(double(u.x) + (1 - double(u.x)) * std::exp(-2 / v)), -1.0, 1.0);
    const double sin_theta = std::sqrt(std::max(0.0, 1 - sqr(cos_theta)));
    const double cos_phi = std::cos(2 * kPiD * double(u.y));
    const float sin_i =
        float(std::clamp(-cos_theta * g.sin_tilted[p] + sin_theta * cos_phi * g.cos_tilted[p], -1.0, 1.0));
    const float cos_i = std::sqrt(std::max(0.0f, 1 - sqr(sin_i)));
    // phi from N_p around Phi(p), or uniform for the residual lobe.
    const double dphi = p < kPMax ? 2.0 * p * g.gamma_t - 2.0 * gamma_o_ + p * kPiD +
                                        double(sample_trimmed_logistic(uc, s_, cdf_lo_, cdf_hi_))
                                  : 2 * kPiD * double(uc);
    const double phi_i = double(g.phi_o) + dphi;
    const Vec3 wi = normalize(Vec3(sin_i, cos_i * float(std::cos(phi_i)), cos_i * float(std::sin(phi_i))));

    float dens[kPMax + 1];
    lobe_densities(g, wi, dens);
    float pdf = 0;
    for (int q = 0; q <= kPMax; ++q) pdf += dens[q] * prob[q];
    if (!(pdf > 0) || !std::isfinite(pdf)) return std::nullopt;
    HairSample s;
    s.wi = wi;
    s.pdf = pdf;
    const Spectrum sum = weighted_sum(dens, g.fresnel, g.path, sigma_a_.at(lambda));
    s.weight = sum / pdf;
    const float c = std::fabs(wi.z);
    s.f = c > 0 ? sum / c : sum;
    s.flags = kGlossy | (wi.z * wo.z >= 0 ? kReflection : kTransmission);
    return s;
}

}  // namespace phos::shading
