// pbrt-v4's measured BRDF (measured_bxdf.h; PBR 4th ed. sec. 9.8, Dupuy & Jakob 2018).
#include "shading/measured_bxdf.h"

#include <cmath>

#include "shading/bsdf.h"
#include "spectrum/rgb_spectrum.h"

namespace phos::shading {

namespace {

// Dupuy & Jakob's map of spherical angles to the unit square and back.
float theta_to_u(float theta) { return std::sqrt(std::fmax(theta, 0.0f) * (2 / kPi)); }
float phi_to_u(float phi) { return phi * (1 / (2 * kPi)) + 0.5f; }
float u_to_theta(float u) { return u * u * (kPi / 2); }
float u_to_phi(float u) { return (2 * u - 1) * kPi; }
// atan2 rather than acos(z), which loses the angle near the normal (where the half vector of a
// near-mirror pair lies: float z steps of 6e-8 are 0.6 % of theta = 0.003).
float spherical_theta(Vec3 w) { return std::atan2(std::sqrt(w.x * w.x + w.y * w.y), w.z); }
float wrap01(float x) { return x - std::floor(x); }

// The density's jacobians: half vector -> wi (4 wo.wm) and unit square -> wm (2 pi^2 u sin theta,
// held above 1e-6 as pbrt-v4 does).
float direction_jacobian(Vec3 wo, Vec3 wm, float u_theta) {
    const float sin_theta_m = std::sqrt(wm.x * wm.x + wm.y * wm.y);
    return 4 * dot(wo, wm) * std::fmax(2 * kPi * kPi * u_theta * sin_theta_m, 1e-6f);
}

}  // namespace

uint32_t MeasuredBxdf::flags() const { return kGlossy | kReflection; }

Spectrum MeasuredBxdf::reduced(Vec2 u, float phi_o, float theta_o, const Wavelengths& lambda) const {
    const scene::PiecewiseLinear2D& table = data_->spectra();
    Spectrum fr;
    if (data_->spectral()) {
        for (int i = 0; i < spectrum::kSpectrumSamples; ++i) {
            const float param[3] = {phi_o, theta_o, lambda[i]};
            fr[i] = std::fmax(table.eval(u, param), 0.0f);
        }
        return fr;
    }
    float c[3];
    for (int ch = 0; ch < 3; ++ch) {
        const float param[3] = {phi_o, theta_o, float(ch)};
        c[ch] = std::fmax(table.eval(u, param), 0.0f);
    }
    return spectrum::RgbSpectrum(Rgb(c[0], c[1], c[2]), spectrum::RgbSpectrum::Use::Unbounded,
                                 spectrum::RgbSpectrum::Fit::Table)
        .sample(lambda);
}

Spectrum MeasuredBxdf::f(Vec3 wo, Vec3 wi, const Wavelengths& lambda) const {
    if (!data_ || !(wo.z * wi.z > 0)) return Spectrum(0.0f);
    if (wo.z < 0) {
        wo = -wo;
        wi = -wi;
    }
    Vec3 wm = wo + wi;
    if (dot(wm, wm) == 0) return Spectrum(0.0f);
    wm = normalize(wm);
    const float theta_o = spherical_theta(wo), phi_o = std::atan2(wo.y, wo.x);
    const float theta_m = spherical_theta(wm), phi_m = std::atan2(wm.y, wm.x);
    const Vec2 u_wo(theta_to_u(theta_o), phi_to_u(phi_o));
    const Vec2 u_wm(theta_to_u(theta_m), wrap01(phi_to_u(data_->isotropic() ? phi_m - phi_o : phi_m)));
    const float param[2] = {phi_o, theta_o};
    const scene::PiecewiseLinear2D::Result ui = data_->vndf().invert(u_wm, param);
    const float sigma = data_->sigma().eval(u_wo);
    if (!(sigma > 0)) return Spectrum(0.0f);
    return reduced(ui.p, phi_o, theta_o, lambda) * (data_->ndf().eval(u_wm) / (4 * sigma * wi.z));
}

float MeasuredBxdf::pdf(Vec3 wo, Vec3 wi) const {
    if (!data_ || !(wo.z * wi.z > 0)) return 0;
    if (wo.z < 0) {
        wo = -wo;
        wi = -wi;
    }
    Vec3 wm = wo + wi;
    if (dot(wm, wm) == 0) return 0;
    wm = normalize(wm);
    const float theta_o = spherical_theta(wo), phi_o = std::atan2(wo.y, wo.x);
    const float theta_m = spherical_theta(wm), phi_m = std::atan2(wm.y, wm.x);
    const Vec2 u_wm(theta_to_u(theta_m), wrap01(phi_to_u(data_->isotropic() ? phi_m - phi_o : phi_m)));
    const float param[2] = {phi_o, theta_o};
    const scene::PiecewiseLinear2D::Result ui = data_->vndf().invert(u_wm, param);
    const float lum_pdf = data_->luminance().eval(ui.p, param);
    return ui.pdf * lum_pdf / direction_jacobian(wo, wm, u_wm.x);
}

std::optional<MeasuredSample> MeasuredBxdf::sample(Vec3 wo, Vec2 u, const Wavelengths& lambda) const {
    if (!data_ || wo.z == 0 || !std::isfinite(wo.z)) return std::nullopt;
    const bool flip = wo.z < 0;
    if (flip) wo = -wo;
    const float theta_o = spherical_theta(wo), phi_o = std::atan2(wo.y, wo.x);
    const float param[2] = {phi_o, theta_o};
    // The luminance warp gives the point of the vndf warp's input square, the vndf warp the normal.
    const scene::PiecewiseLinear2D::Result lum = data_->luminance().sample(u, param);
    const scene::PiecewiseLinear2D::Result vn = data_->vndf().sample(lum.p, param);
    const Vec2 u_wm = vn.p;
    float phi_m = u_to_phi(u_wm.y);
    if (data_->isotropic()) phi_m += phi_o;
    const float theta_m = u_to_theta(u_wm.x), sin_m = std::sin(theta_m);
    const Vec3 wm(sin_m * std::cos(phi_m), sin_m * std::sin(phi_m), std::cos(theta_m));
    Vec3 wi = reflect(wo, wm);
    if (!(wi.z > 0)) return std::nullopt;
    const float pdf = lum.pdf * vn.pdf / direction_jacobian(wo, wm, u_wm.x);
    const float sigma = data_->sigma().eval(Vec2(theta_to_u(theta_o), phi_to_u(phi_o)));
    if (!(pdf > 0) || !(sigma > 0)) return std::nullopt;
    MeasuredSample s;
    s.f = reduced(lum.p, phi_o, theta_o, lambda) * (data_->ndf().eval(u_wm) / (4 * sigma * wi.z));
    s.pdf = pdf;
    s.flags = flags();
    s.weight = s.f * (wi.z / pdf);
    s.wi = flip ? -wi : wi;
    return s;
}

float MeasuredBxdf::albedo(Vec3 wo) const {
    if (!data_) return 0;
    if (wo.z < 0) wo = -wo;
    return data_->albedo(std::atan2(wo.y, wo.x), spherical_theta(wo));
}

}  // namespace phos::shading
