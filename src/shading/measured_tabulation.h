// Tabulates an analytic BRDF into the measured-BSDF tables of Dupuy & Jakob 2018 ("An Adaptive
// Parameterization for Efficient Material Acquisition and Rendering", ACM TOG 37(6), sec. 4-5),
// the form RGL `.bsdf` files hold (scene/measured_bsdf.h): what tests, the fuzz seeds and
// tools/tabulate_bsdf use to make valid measured materials, since a measured file is only a
// parameterisation plus values. The parameterising microfacet distribution is a Trowbridge-Reitz
// (GGX) one of roughness (alpha_x, alpha_y):
//  - ndf: D(wm) over (u(theta_m), u(phi_m)); sigma(wo) = cos theta_o (1 + Lambda(wo));
//  - vndf: the visible normals <wo, wm> D(wm) / sigma(wo) as a density over the unit square
//    (times the angle map's jacobian 2 pi^2 u(theta_m) sin theta_m), per (phi_i, theta_i);
//  - the reduced BRDF fr(u) = f(wo, wi) 4 sigma(wo) cos theta_i / D(wm) on an n x n grid over the
//    vndf warp's input square (wm = the warp at u, wi = reflect(wo, wm); 0 where wi is below the
//    horizon), with D and sigma read from the tables themselves so that evaluating the tables at a
//    grid point gives f exactly; and its luminance (CIE Y weights over the table's wavelengths).
// Models: a Trowbridge-Reitz conductor (f = F(wo.wm) D G2 / (4 cos_o cos_i), Fresnel of the
// complex index eta + i k at each wavelength, height-correlated Smith G2), or a Lambertian
// reflector (f = reflectance / pi; its parameterising distribution is still the GGX one: alpha 1
// makes the vndf warp near-uniform).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/vec.h"
#include "scene/measured_bsdf.h"

namespace phos::shading {

struct TabulatedModel {
    enum class Kind { Conductor, Lambert } kind = Kind::Conductor;
    float alpha_x = 0.2f, alpha_y = 0.2f;  // equal: an isotropic table
    std::function<float(float)> eta, k;    // the conductor's index at a wavelength (nm)
    float reflectance = 0.8f;              // the Lambertian's
};

struct TabulationGrid {
    int n_theta_i = 10;  // incident elevations, uniform over [0, 0.999 pi/2]
    int n_phi_i = 9;     // incident azimuths over [-pi, pi] (anisotropic tables only)
    int ndf_n = 64;      // ndf and sigma: ndf_n x ndf_n
    int vndf_n = 32;     // vndf: vndf_n x vndf_n per incident direction
    int n = 32;          // reduced BRDF and luminance: n x n per incident direction
    // nm, increasing; empty: an `rgb` table (the model at 612, 549 and 465 nm, near the sRGB
    // primaries' dominant wavelengths) and no spectra.
    std::vector<float> wavelengths;
    std::string description = "tabulated by phos";
};

scene::MeasuredBsdfTables tabulate_brdf(const TabulatedModel& model, const TabulationGrid& grid);

// The model's own f(wo, wi) at one wavelength (local frame, both directions above the surface).
float analytic_brdf(const TabulatedModel& model, Vec3 wo, Vec3 wi, float lambda);

}  // namespace phos::shading
