// A measured isotropic or anisotropic BRDF in the tabulated form of Dupuy & Jakob 2018 ("An
// Adaptive Parameterization for Efficient Material Acquisition and Rendering", ACM TOG 37(6)), as
// the RGL database's `.bsdf` files hold it and pbrt-v4's `measured` material reads it
// (MeasuredBxDFData, bxdfs.cpp; PBR 4th ed. sec. 9.8). Directions are spherical angles (theta from
// the normal, phi = atan2(y, x) in [-pi, pi]) mapped to the unit square by
//   u(theta) = sqrt(2 theta / pi),  u(phi) = phi / (2 pi) + 1/2
// (x = theta, y = phi in every 2D table). Tables:
//  - ndf: the microfacet normal distribution D(wm) on an [ny][nx] grid over (u(theta_m), u(phi_m));
//  - sigma: the projected microfacet area sigma(wo) = int <wo, m> D(m) dm, same kind of grid over wo;
//  - vndf: the visible-normal distribution of each incident direction, conditioned on the axes
//    phi_i, theta_i ([phi_i][theta_i][ny][nx] over u of wm; for an isotropic file phi_m is taken
//    relative to phi_o), as a density over the unit square (the jacobian of the angle map
//    included: the file's `jacobian` flag);
//  - spectra: the "reduced" BRDF f cos(theta_i) / p_vndf(wi) over the vndf warp's *input* square
//    (the adaptive parameterisation: a regular n x n grid there is dense where the VNDF is),
//    [phi_i][theta_i][wavelength][n][n]; or `rgb` ([phi_i][theta_i][3][n][n]) when a file holds
//    no spectra;
//  - luminance: the reduced BRDF's luminance over the same square ([phi_i][theta_i][n][n]), which
//    importance sampling warps by first.
// MeasuredBsdfTables is exactly what a file holds (io/bsdf reads and writes it); MeasuredBsdf adds
// the interpolants and warps built from it once (what shading/measured_bxdf.h evaluates), and a
// directional-albedo table for lobe selection and Russian roulette. A material holds a
// std::shared_ptr<const MeasuredBsdf>.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "scene/piecewise_linear_2d.h"

namespace phos::scene {

struct MeasuredBsdfTables {
    std::string description;  // the file's free text (UTF-8, without a trailing NUL)
    bool jacobian = true;     // the file's flag (pbrt-v4 and phos read vndf as a density over u either way)
    // Parameter axes of the conditioned tables: radians, strictly increasing. An isotropic file has
    // at most two phi_i values; an anisotropic one covers the whole circle (phi_i from -pi to pi).
    std::vector<float> theta_i, phi_i;
    // nm, strictly increasing: the spectra's third axis. Empty in a file that holds `rgb` only.
    std::vector<float> wavelengths;
    int ndf_nx = 0, ndf_ny = 0;
    std::vector<float> ndf;  // [ndf_ny][ndf_nx]
    int sigma_nx = 0, sigma_ny = 0;
    std::vector<float> sigma;  // [sigma_ny][sigma_nx]
    int vndf_nx = 0, vndf_ny = 0;
    std::vector<float> vndf;       // [phi_i][theta_i][vndf_ny][vndf_nx]
    int n = 0;                     // the reduced BRDF's grid: n x n over the vndf warp's input square
    std::vector<float> luminance;  // [phi_i][theta_i][n][n]
    std::vector<float> spectra;    // [phi_i][theta_i][wavelengths][n][n] (or empty)
    std::vector<float> rgb;        // [phi_i][theta_i][3][n][n] (or empty)

    // pbrt-v4's rule: a file with at most two phi_i values is isotropic.
    bool isotropic() const { return phi_i.size() <= 2; }
    bool spectral() const { return !wavelengths.empty(); }
    // Empty when the tables are consistent and usable, else what is wrong with them (sizes that do
    // not match, a grid under 2 x 2, an axis not strictly increasing, a NaN or infinity, a negative
    // ndf / sigma / vndf / luminance value, a vndf or luminance slice with no mass, an anisotropic
    // phi_i that does not span 2 pi). Negative spectra are allowed (measurement noise; evaluation
    // clamps them to 0, as pbrt-v4 does).
    std::string check() const;
};

class MeasuredBsdf {
public:
    // Builds the interpolants; `tables` must pass check() (throws std::invalid_argument with its
    // message otherwise).
    explicit MeasuredBsdf(MeasuredBsdfTables tables);

    const MeasuredBsdfTables& tables() const { return t_; }
    bool isotropic() const { return t_.isotropic(); }
    bool spectral() const { return t_.spectral(); }

    // Interpolants (parameters in this order: phi_o, theta_o, then the wavelength in nm or the RGB
    // channel 0, 1, 2). ndf and sigma take no parameter.
    const PiecewiseLinear2D& ndf() const { return ndf_; }
    const PiecewiseLinear2D& sigma() const { return sigma_; }
    const PiecewiseLinear2D& vndf() const { return vndf_; }            // warp
    const PiecewiseLinear2D& luminance() const { return luminance_; }  // warp
    const PiecewiseLinear2D& spectra() const { return spectra_; }      // spectra or rgb values

    // Directional albedo estimate at the incident direction (phi_o, theta_o): the integral over the
    // warp's input square of the reduced BRDF, averaged over the wavelengths (or RGB channels),
    // interpolated between the table's axes. For a consistent table this is the hemispherical
    // reflectance int f cos dwi (Dupuy & Jakob 2018, sec. 5: the reduced BRDF is the vndf
    // sampling weight). Never negative.
    float albedo(float phi_o, float theta_o) const;
    // The roughness of the Trowbridge-Reitz distribution with the table's D at the normal
    // (D(n) = 1 / (pi alpha^2)), at most 1: how sharp the lobe is, for the --sharp-glossy and
    // regularisation decisions that Phong exponents and microfacet alphas take elsewhere.
    float equivalent_alpha() const { return equivalent_alpha_; }

private:
    MeasuredBsdfTables t_;
    PiecewiseLinear2D ndf_, sigma_, vndf_, luminance_, spectra_;
    PiecewiseLinear2D albedo_;  // eval-only, [phi_i][theta_i] on a 2 x 2 grid per slice (constant)
    float equivalent_alpha_ = 1;
};

}  // namespace phos::scene
