// pbrt-v4's hair scattering model (HairBxDF; Pharr, Jakob & Humphreys, "Physically Based
// Rendering", 3rd ed., sec. 9.9 "Hair"): Chiang, Bitterli, Tappan & Burley 2016, "A Practical and
// Controllable Hair and Fur Model for Production Path Tracing", built on d'Eon, Francois, Hill,
// Letteri & Aubry 2011 (longitudinal scattering) and Marschner et al. 2003 (the R, TT, TRT paths
// through a rough dielectric cylinder with tilted cuticle scales).
//
// f(wo, wi) = sum_{p=0}^{2} M_p(theta_o, theta_i) A_p(theta_o, h) N_p(phi) / |cos(wi, z)|
//           + M_3(theta_o, theta_i) A_3(theta_o, h) / (2 pi) / |cos(wi, z)|
// p = 0 (R: reflection at the surface), 1 (TT: through the fibre), 2 (TRT: one internal reflection),
// 3 (all longer paths, azimuthally uniform).
// - M_p: d'Eon et al.'s longitudinal function (their eq. 7, with the modified Bessel function I0,
//   written with e^(-x) I0(x) so that nothing overflows for small v), of variance v_p from beta_m (Chiang
//   eq. 7: v_0 = (0.726 beta_m + 0.812 beta_m^2 + 3.7 beta_m^20)^2, v_1 = v_0 / 4,
//   v_2 = v_3 = 4 v_0), normalised over cos(theta_i) d theta_i; theta_o tilted by the scales (pbrt's
//   signs: R by -2 alpha, TT by +alpha, TRT by +4 alpha).
// - A_p: attenuation with exact dielectric Fresnel at cos(theta_o) cos(gamma_o) and the
//   transmittance T = exp(-sigma_a 2 cos(gamma_t) / cos(theta_t)) of one crossing (PBR3 eqs. 9.46-9.48;
//   the last term sums the geometric series of the longer paths).
// - N_p: the logistic distribution of scale s (Chiang eq. 8 from beta_n) trimmed to [-pi, pi]
//   around Phi(p) = 2 p gamma_t - 2 gamma_o + p pi.
// With sigma_a = 0 the A_p sum to 1 and M_p, N_p are normalised, so the integral of f |cos| over
// the sphere is exactly 1 for every wo and h.
//
// Conventions (phos):
// - Frame: the local shading frame, x = dpdu along the fibre, z = the shading normal, y = z x x.
//   As pbrt: sin(theta) = w.x, phi = atan2(w.z, w.y), and the |cos| that f divides by is |w.z|.
// - h in [-1, 1] is the offset across the fibre: at a curve hit h = -1 + 2 v (v = the curve's
//   across coordinate, accel/curves.h).
// - Spectra: f is per wavelength (sigma_a read at the path's wavelengths). Everything that chooses
//   (the lobe probabilities of sample and pdf, albedo()) reads an RGB sigma_a, the average of the
//   three channels' A_p, so pdf() has no wavelength argument (pbrt-v4 averages A_p over the four
//   sampled wavelengths instead).
// - Sampling is exact: sample() draws p with probability A_p / sum A_p (RGB), theta_i from M_p
//   (d'Eon et al.'s von Mises-Fisher warp, without pbrt's 1e-5 clamp of u), phi from N_p (inverse
//   CDF of the trimmed logistic; uniform for p = 3), so its pdf is pdf(wo, wi) at the drawn wi and
//   weight = f |wi.z| / pdf = sum M_p A_p N_p / sum M_p (A_p / sum A) N_p. With sigma_a = 0 the
//   weight is 1.
// - Flags: flags() = kGlossy | kReflection | kTransmission (one glossy lobe over the whole
//   sphere); a sample is kGlossy | kReflection when wi is on wo's side of z, else kGlossy |
//   kTransmission (pbrt-v4 marks every hair sample GlossyReflection).
// - Transport mode: the model is the same in both (pbrt ignores it): no 1/eta^2 scaling.
// - Side: unlike bsdf.h's lobes, nothing here depends on which side of z or of the geometric
//   normal wo is; directions must be passed in the frame above unflipped (negating z for both
//   mirrors phi, which is the model at -h).
// - Differences from pbrt-v4's values: I0 by Abramowitz & Stegun's approximations (relative error
//   < 5e-7) where pbrt sums 10 terms of its series (0.3 % low at 10, 2 % at 12,
//   past which it switches to an asymptotic form), so pbrt's f is up to 2 % lower at some
//   directions (measured on 2000 random cases; the median difference is 6e-7); eta below 1 is
//   read as 1.
// - f and sample allocate nothing; the object is trivially copyable (no pointers).
#pragma once

#include <cstdint>
#include <optional>

#include "core/vec.h"
#include "spectrum/rgb_spectrum.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::shading {

// pbrt-v4's HairMaterial defaults.
inline constexpr float kHairDefaultEta = 1.55f;
inline constexpr float kHairDefaultBeta = 0.3f;          // beta_m and beta_n
inline constexpr float kHairDefaultAlphaDegrees = 2.0f;  // scale tilt
inline constexpr float kHairDefaultEumelanin = 1.3f;     // when no colour parameter is given

// Chiang et al. 2016 (as PBR3 sec. 9.9.6 gives them): absorption coefficients of the two melanins (per unit
// of the fibre's radius, the unit the model measures its paths in), linear sRGB: eumelanin (0.419,
// 0.697, 1.37), pheomelanin (0.187, 0.4, 1.05); sigma_a = ce e + cp p (pbrt-v4's SigmaAFromConcentration,
// read as an unbounded RGB spectrum).
Rgb hair_sigma_a_from_concentration(float eumelanin, float pheomelanin);

// Chiang et al. 2016, eq. 9: the absorption coefficient whose hair volume has the multiple-scattering
// colour c (in (0, 1]) under white light, for azimuthal roughness beta_n:
// sigma_a = (ln c / (5.969 - 0.215 b + 2.532 b^2 - 10.73 b^3 + 5.574 b^4 + 0.245 b^5))^2.
// (Fitted to renders of whole hair volumes, not one fibre.) c = 0 gives +infinity (opaque).
float hair_sigma_a_from_reflectance(float c, float beta_n);
Rgb hair_sigma_a_from_reflectance(Rgb c, float beta_n);
// The inverse of eq. 9: the colour c = exp(-D(beta_n) sqrt(sigma_a)).
float hair_reflectance_from_sigma_a(float sigma_a, float beta_n);

// The absorption coefficient of a fibre in one of pbrt-v4's three parameterisations:
// - of_sigma_a: an RGB sigma_a (negative components read as 0), upsampled as an unbounded spectrum
//   (pbrt's "sigma_a"; also what of_concentration gives);
// - of_reflectance: an RGB colour (clamped to [0, 1]), upsampled as an albedo spectrum and
//   inverted per wavelength by eq. 9 as pbrt-v4 does (pbrt's "reflectance" / "color");
// - of_concentration: melanin concentrations (negative read as 0; pbrt's "eumelanin" /
//   "pheomelanin"; the default material is of_concentration(1.3, 0)).
// Fit: Exact for scene constants, Table per texel or per hit (rgb_spectrum.h).
class HairAbsorption {
public:
    HairAbsorption() = default;  // sigma_a = 0: a lossless fibre
    static HairAbsorption of_sigma_a(Rgb sigma_a,
                                     spectrum::RgbSpectrum::Fit fit = spectrum::RgbSpectrum::Fit::Exact);
    static HairAbsorption of_reflectance(Rgb colour, float beta_n,
                                         spectrum::RgbSpectrum::Fit fit = spectrum::RgbSpectrum::Fit::Exact);
    static HairAbsorption of_concentration(
        float eumelanin, float pheomelanin,
        spectrum::RgbSpectrum::Fit fit = spectrum::RgbSpectrum::Fit::Exact);

    // sigma_a at the path's wavelengths.
    Spectrum at(const Wavelengths& lambda) const;
    // The RGB sigma_a that choices read (for of_reflectance, eq. 9 per channel).
    Rgb rgb() const { return rgb_; }

private:
    spectrum::RgbSpectrum spectrum_;  // sigma_a, or the colour for of_reflectance
    Rgb rgb_;
    float inv_d_ = 0;  // of_reflectance: 1 / D(beta_n) of eq. 9; 0 for the other two
};

// What pbrt-v4's HairMaterial gives HairBxDF (its textures already evaluated at the hit).
struct HairParams {
    float h = 0;  // offset across the fibre, clamped to [-1, 1]
    float eta = kHairDefaultEta;
    // Longitudinal and azimuthal roughness, clamped to [0.01, 1] as pbrt-v4's HairMaterial does.
    float beta_m = kHairDefaultBeta, beta_n = kHairDefaultBeta;
    float alpha_degrees = kHairDefaultAlphaDegrees;  // cuticle scale tilt
    HairAbsorption sigma_a;
};

struct HairSample {
    Vec3 wi;
    Spectrum f;
    float pdf = 0;
    uint32_t flags = 0;  // LobeFlags (bsdf.h)
    Spectrum weight;     // f |wi.z| / pdf
};

class HairBxdf {
public:
    HairBxdf() = default;
    explicit HairBxdf(const HairParams& params);

    // Moves the BxDF to another offset across the fibre (what placing a material's BxDF at a hit
    // changes); the rest stays.
    void set_h(float h);
    float h() const { return h_; }
    // Replaces the absorption (a textured colour evaluated at a hit).
    void set_sigma_a(const HairAbsorption& sigma_a) { sigma_a_ = sigma_a; }

    Spectrum f(Vec3 wo, Vec3 wi, const Wavelengths& lambda) const;
    float pdf(Vec3 wo, Vec3 wi) const;
    // uc picks the lobe p and is then reused (remapped) for N_p, u draws M_p, as pbrt-v4.
    // nullopt only where the density underflows to 0.
    std::optional<HairSample> sample(Vec3 wo, float uc, Vec2 u, const Wavelengths& lambda) const;

    // The directional albedo (integral of f |cos| over the sphere) at wo and this h, exactly: the
    // sum of the A_p, with the RGB sigma_a. For Russian roulette and lobe selection.
    Rgb albedo(Vec3 wo) const;

    // M_p's variance v_p for p = 0..3 (each longitudinal lobe is about sqrt(v_p) radians wide); the
    // sharpest is v_1 = v_0 / 4 (TT). A modified-Phong lobe cos^n has about the width of v = 1 / n,
    // so the hair is as sharp as a Phong lobe of exponent 1 / v_1 (what bsdf.h's sharp_lobes compares).
    float longitudinal_variance(int p) const { return v_[p]; }

    // kGlossy | kReflection | kTransmission (bsdf.h's LobeFlags).
    static uint32_t flags();
    static constexpr int kPMax = 3;

private:
    // What depends on wo (and h) only.
    struct Geometry {
        float sin_o, cos_o, phi_o;
        float sin_tilted[kPMax + 1], cos_tilted[kPMax + 1];  // theta_o shifted by each lobe's tilt
        float gamma_t;
        float path;     // 2 cos(gamma_t) / cos(theta_t): one crossing of the fibre
        float fresnel;  // at cos(theta_o) cos(gamma_o)
    };
    Geometry geometry(Vec3 wo) const;
    // M_p N_p of each lobe at wi (N_3 = 1 / (2 pi)): each a density over solid angle.
    void lobe_densities(const Geometry& g, Vec3 wi, float out[kPMax + 1]) const;
    // The lobe probabilities A_p / sum A_p from the RGB sigma_a.
    void lobe_probabilities(const Geometry& g, float out[kPMax + 1]) const;

    float h_ = 0, gamma_o_ = 0, cos_gamma_o_ = 1;
    float eta_ = kHairDefaultEta;
    float v_[kPMax + 1] = {};  // M_p's variances, their inverses and -log(2 v sinh(1/v)) + 1/v
    float inv_v_[kPMax + 1] = {}, log_norm_[kPMax + 1] = {};
    float s_ = 0;  // N_p's logistic scale, the trimmed distribution's normaliser and CDF at -+pi
    float logistic_norm_ = 1;
    double cdf_lo_ = 0, cdf_hi_ = 1;
    float sin_2k_alpha_[kPMax] = {}, cos_2k_alpha_[kPMax] = {};
    HairAbsorption sigma_a_;
};

}  // namespace phos::shading
