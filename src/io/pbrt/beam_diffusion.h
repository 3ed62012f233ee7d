// Photon beam diffusion (Habel, Christensen & Jarosz 2013, "Photon Beam Diffusion: A Hybrid Monte
// Carlo Method for Subsurface Scattering"), tabulated as pbrt-v4 tabulates it for its subsurface
// material (Physically Based Rendering, 3rd ed., sec. 15.5): the radial reflectance profile of a
// semi-infinite homogeneous medium under a smooth dielectric boundary, its integral over the
// surface (the effective albedo rho_eff of a single-scattering albedo rho) and the inverse, which
// turns a subsurface material's "reflectance" into coefficients (pbrt-v4's SubsurfaceFromDiffuse).
#pragma once

#include <vector>

namespace phos::io::pbrt {

// Multiple-scattering term of the profile at radius r: dipoles along the refracted beam, depths
// sampled by the beam's attenuation (100 stratified samples), Grosjean's diffusion coefficient,
// the Fresnel-moment boundary condition and Habel et al.'s empirical correction kappa.
float beam_diffusion_ms(float sigma_s, float sigma_a, float g, float eta, float r);
// Single-scattering term at radius r: one Henyey-Greenstein event on the normally refracted beam,
// leaving through the boundary below the critical angle.
float beam_diffusion_ss(float sigma_s, float sigma_a, float g, float eta, float r);

// The profile 2 pi r (ss + ms) tabulated over 100 albedos (denser near 1) and 64 radii (in mean
// free paths, 0 then 2.5e-3 growing by 1.2), integrated over r by Catmull-Rom quadrature: the
// effective albedo of each tabulated albedo. Built for one g and eta.
class BeamDiffusionTable {
public:
    BeamDiffusionTable(float g, float eta);

    const std::vector<float>& albedos() const { return rho_; }
    const std::vector<float>& radii() const { return radius_; }
    const std::vector<float>& effective_albedos() const { return rho_eff_; }

    // The effective albedo at albedo rho in [0, 1] (the table's Catmull-Rom spline).
    float effective_albedo(float rho) const;
    // The albedo whose effective albedo is `rho_eff` (the spline inverted; clamped to the table's
    // first and last albedo outside its range).
    float albedo_for(float rho_eff) const;

private:
    std::vector<float> rho_, radius_, rho_eff_;
};

// Catmull-Rom spline through (x[i], f[i]) (non-uniform knots, derivatives from the neighbours,
// one-sided at the ends): its integral over [x.front(), x.back()], and its value at t.
double integrate_catmull_rom(const std::vector<float>& x, const std::vector<float>& f);
double eval_catmull_rom(const std::vector<float>& x, const std::vector<float>& f, double t);

}  // namespace phos::io::pbrt
