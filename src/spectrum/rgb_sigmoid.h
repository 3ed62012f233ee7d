// RGB to spectrum (Jakob & Hanika 2019, "A Low-Dimensional Function Space for Efficient Spectral
// Upsampling"): a reflectance RGB becomes the smooth spectrum s(λ) = S(c0 t² + c1 t + c2), t the
// wavelength mapped to [0, 1] over [kLambdaMin, kLambdaMax] and S(x) = 1/2 + x / (2 sqrt(1 + x²))
// a sigmoid, so s stays within [0, 1] at every wavelength. The coefficients are fitted so that
// the spectrum under the colour space's illuminant (D65 for sRGB), through the colour-matching
// functions (1 nm sums, color.h), gives back the RGB: Gauss-Newton with Levenberg-Marquardt
// damping on the RGB residual. A table over the RGB cube holds the fits (RgbSigmoidTable): the
// largest component m, its value z on a grid dense near 0 and 1, and the other two divided by it
// (x, y in [0, 1]) on grids dense near 0 and 1; a lookup interpolates the coefficients
// trilinearly (the paper's sec. 4), and exact() refines the result by a few more iterations.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec.h"
#include "spectrum/sampled_spectrum.h"

namespace phos::spectrum {

struct SigmoidPolynomial {
    std::array<float, 3> c{0, 0, 0};  // c0 t² + c1 t + c2, t = (λ − kLambdaMin) / (kLambdaMax − kLambdaMin)
    float operator()(float lambda) const;
    SampledSpectrum sample(const SampledWavelengths& w) const;
};

// The linear sRGB of reflectance `s` under D65 (1 nm sums over [360, 830]), 1 for s = 1.
Vec3 reflectance_to_srgb(const SigmoidPolynomial& s);

// Fits the coefficients for `rgb` (each in [0, 1]) starting from `start`; returns the largest
// residual component left (|RGB(fit) − rgb|, max over channels).
float fit_sigmoid(Vec3 rgb, SigmoidPolynomial& fit, int max_iterations = 64);

class RgbSigmoidTable {
public:
    // Fits every grid point (res x res x res per largest component; parallel, deterministic):
    // each (m, x, y) column starts from grey at the middle of z and walks up and down z from there,
    // each fit starting from its neighbour's. Returns the table and, in `worst`, the largest
    // residual of any grid point.
    static RgbSigmoidTable fit(int res, float* worst = nullptr);
    // The table phos renders with (sRGB, embedded: data/rgb_sigmoid_srgb.bin, made by
    // `rgb_sigmoid_table` from fit()).
    static const RgbSigmoidTable& srgb();

    // The spectrum of reflectance `rgb` (components clamped to [0, 1]) by interpolating the table:
    // fast (textures), its RGB within 3e-3 of `rgb` (the error is largest near the cube's bright
    // faces, where the coefficients grow fastest).
    SigmoidPolynomial lookup(Vec3 rgb) const;
    // The same refined by fit_sigmoid from the table's coefficients: its RGB within 1e-5 of `rgb`
    // (scene constants: material colours, light colours).
    SigmoidPolynomial exact(Vec3 rgb) const;

    int resolution() const { return res_; }
    // Serialised form: "PHOSRGBS", version, res, then the coefficients (float, little-endian).
    std::vector<uint8_t> bytes() const;
    static RgbSigmoidTable from_bytes(const uint8_t* data, size_t size);

private:
    size_t index(int m, int zi, int yi, int xi) const {
        return ((size_t(m) * size_t(res_) + size_t(zi)) * size_t(res_) + size_t(yi)) * size_t(res_) +
               size_t(xi);
    }
    int res_ = 0;
    std::vector<float> z_;
    std::vector<SigmoidPolynomial> coeffs_;
};

}  // namespace phos::spectrum
