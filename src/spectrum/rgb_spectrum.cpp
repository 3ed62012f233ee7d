// RGB values as spectra (see rgb_spectrum.h).
#include "spectrum/rgb_spectrum.h"

#include <algorithm>
#include <cmath>

#include "spectrum/cie_tables.h"
#include "spectrum/color.h"
#include "spectrum/rgb_sigmoid.h"

namespace phos::spectrum {

namespace {

float sigmoid_of(float c0, float c1, float c2, float lambda) {
    const float t = (lambda - kLambdaMin) * (1.0f / (kLambdaMax - kLambdaMin));
    const float x = (c0 * t + c1) * t + c2;
    if (!std::isfinite(x)) return x > 0 ? 1.0f : 0.0f;
    return 0.5f + x / (2 * std::sqrt(1 + x * x));
}

}  // namespace

RgbSpectrum::RgbSpectrum(Rgb rgb, Use use, Fit fit) {
    rgb = Rgb(std::max(rgb.r, 0.0f), std::max(rgb.g, 0.0f), std::max(rgb.b, 0.0f));
    const float m = rgb.max();
    illuminant_ = use == Use::Illuminant;
    if (m == 0) return;                      // black
    if (rgb.r == rgb.g && rgb.g == rgb.b) {  // flat: S(0) = 1/2
        scale_ = 2 * m;
        return;
    }
    Vec3 target(rgb.r, rgb.g, rgb.b);
    if (use == Use::Albedo && m <= 1) {
        scale_ = 1;
    } else {
        scale_ = 2 * m;
        target = target / scale_;
    }
    const RgbSigmoidTable& table = RgbSigmoidTable::srgb();
    const SigmoidPolynomial p = fit == Fit::Exact ? table.exact(target) : table.lookup(target);
    c0_ = p.c[0], c1_ = p.c[1], c2_ = p.c[2];
}

float RgbSpectrum::operator()(float lambda) const {
    if (scale_ == 0) return 0;
    const float v = scale_ * sigmoid_of(c0_, c1_, c2_, lambda);
    return illuminant_ ? v * d65_luminance_1(lambda) : v;
}

}  // namespace phos::spectrum
