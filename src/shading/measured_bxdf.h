// pbrt-v4's measured BRDF (MeasuredBxDF, bxdfs.{h,cpp}; Pharr, Jakob & Humphreys, "Physically
// Based Rendering", 4th ed., sec. 9.8 "Measured BSDFs"), after Dupuy & Jakob 2018, "An Adaptive
// Parameterization for Efficient Material Acquisition and Rendering" (ACM TOG 37(6)): a BRDF
// tabulated (scene/measured_bsdf.h) as
//   f(wo, wi) = fr(u) D(wm) / (4 sigma(wo) cos theta_i),   wm = normalize(wo + wi),
// where u is the point of the vndf warp's input square that maps to wm (the warp inverted at wo),
// fr the tabulated reduced BRDF there (spectral: interpolated at each of the path's wavelengths,
// negative values read as 0; an `rgb` table is upsampled as an unbounded RGB spectrum), D the
// tabulated microfacet distribution and sigma the projected microfacet area.
// Sampling (sec. 9.8.2): u from the luminance warp (the reduced BRDF's luminance), wm from the vndf
// warp at u, wi = reflect(wo, wm); its density is
//   pdf = p_lum(u) p_vndf(wm in u-space) / (4 (wo . wm) 2 pi^2 u_theta(wm) sin theta_m)
// (the half-vector jacobian and that of the (theta, phi) -> unit-square map; the latter held above
// 1e-6 as pbrt-v4 does). pdf(wo, wi) computes the same density through the warp's inverse.
//
// Conventions (local shading frame, z = normal, x = dpdu; phos's Bsdf conventions, bsdf.h):
// - Reflection only, two-sided as pbrt-v4's MeasuredBxDF: a pair with wo.z < 0 is evaluated as
//   (-wo, -wi); f = pdf = 0 unless wo and wi are strictly on the same side; sample() returns
//   nullopt for wo.z == 0 and when the sampled wi is not on wo's side.
// - pdf and every choice read only the luminance and vndf warps: nothing depends on the
//   wavelengths. sample()'s f is the table at the sampled u itself (pbrt-v4's), which equals
//   f(wo, wi) to rounding; weight = f cos(theta_i) / pdf.
// - Flags: kGlossy | kReflection (as pbrt-v4).
// A MeasuredBxdf is a pointer to the tables (owned by the material through a shared_ptr): cheap to
// copy, and rebind() points a copy made as bytes in another process at that process's tables.
#pragma once

#include <cstdint>
#include <optional>

#include "core/vec.h"
#include "scene/measured_bsdf.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::shading {

struct MeasuredSample {
    Vec3 wi;
    Spectrum f;
    float pdf = 0;
    uint32_t flags = 0;  // bsdf.h's LobeFlags: kGlossy | kReflection
    Spectrum weight;     // f |cos theta_i| / pdf
};

class MeasuredBxdf {
public:
    MeasuredBxdf() = default;
    explicit MeasuredBxdf(const scene::MeasuredBsdf& data) : data_(&data) {}

    Spectrum f(Vec3 wo, Vec3 wi, const Wavelengths& lambda) const;
    float pdf(Vec3 wo, Vec3 wi) const;
    std::optional<MeasuredSample> sample(Vec3 wo, Vec2 u, const Wavelengths& lambda) const;
    // The directional albedo int f |cos theta_i| dwi at wo, estimated from the tables
    // (MeasuredBsdf::albedo, averaged over the table's wavelengths or channels): for lobe selection
    // and Russian roulette; it does not depend on the path's wavelengths.
    float albedo(Vec3 wo) const;

    uint32_t flags() const;  // kGlossy | kReflection
    const scene::MeasuredBsdf* data() const { return data_; }
    void rebind(const scene::MeasuredBsdf& data) { data_ = &data; }

private:
    // fr at u for the incident direction's (phi_o, theta_o), at each wavelength, clamped to >= 0.
    Spectrum reduced(Vec2 u, float phi_o, float theta_o, const Wavelengths& lambda) const;

    const scene::MeasuredBsdf* data_ = nullptr;
};

}  // namespace phos::shading
