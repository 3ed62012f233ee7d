// Scene spectra evaluated at any wavelength (see distribution.h).
#include "spectrum/distribution.h"

#include "spectrum/color.h"
#include "spectrum/piecewise_linear.h"

namespace phos::spectrum {

Distribution Distribution::constant(float c) {
    Distribution d;
    d.scale_ = c;
    return d;
}

Distribution Distribution::rgb(Rgb rgb, RgbSpectrum::Use use) {
    if (use != RgbSpectrum::Use::Illuminant && rgb.r == rgb.g && rgb.g == rgb.b) return constant(rgb.r);
    Distribution d;
    d.kind_ = Kind::Rgb;
    d.scale_ = 1;
    d.rgb_ = RgbSpectrum(rgb, use);
    return d;
}

Distribution Distribution::blackbody(float kelvin) {
    Distribution d;
    d.kind_ = Kind::Blackbody;
    d.scale_ = 1;
    d.kelvin_ = kelvin;
    d.blackbody_ = std::make_shared<const Blackbody>(kelvin);
    return d;
}

Distribution Distribution::tabulated(std::vector<float> lambda, std::vector<float> value) {
    Distribution d;
    d.kind_ = Kind::Tabulated;
    d.scale_ = 1;
    d.lambda_ = std::make_shared<const std::vector<float>>(std::move(lambda));
    d.value_ = std::make_shared<const std::vector<float>>(std::move(value));
    return d;
}

Distribution Distribution::sellmeier(const Sellmeier& s) {
    Distribution d;
    d.kind_ = Kind::Sellmeier;
    d.scale_ = 1;
    d.sellmeier_ = s;
    return d;
}

Distribution Distribution::cauchy(float a, float b) {
    Distribution d;
    d.kind_ = Kind::Cauchy;
    d.scale_ = 1;
    d.a_ = a, d.b_ = b;
    return d;
}

Distribution Distribution::abbe(float n_d, float v_d) {
    const auto inv2 = [](double nm) { return 1.0 / ((nm * 1e-3) * (nm * 1e-3)); };
    const double b = (double(n_d) - 1) / (double(v_d) * (inv2(kLineF) - inv2(kLineC)));
    return cauchy(float(double(n_d) - b * inv2(kLineD)), float(b));
}

Distribution Distribution::scaled(float s) const {
    Distribution d = *this;
    d.scale_ *= s;
    return d;
}

float Distribution::operator()(float lambda) const {
    switch (kind_) {
        case Kind::Constant:
            return scale_;
        case Kind::Rgb:
            return scale_ * rgb_(lambda);
        case Kind::Blackbody:
            return scale_ * (*blackbody_)(lambda);
        case Kind::Tabulated: {
            const std::vector<float>&x = *lambda_, &y = *value_;
            return scale_ *
                   piecewise_linear(
                       x.size(), [&](size_t i) { return x[i]; }, [&](size_t i) { return y[i]; }, lambda);
        }
        case Kind::Sellmeier:
            return scale_ * float(sellmeier_.ior(lambda));
        case Kind::Cauchy: {
            const float um = lambda * 1e-3f;
            return scale_ * (a_ + b_ / (um * um));
        }
    }
    return 0;
}

SampledSpectrum Distribution::sample(const SampledWavelengths& w) const {
    if (kind_ == Kind::Constant) return SampledSpectrum(scale_);
    if (kind_ == Kind::Rgb) return rgb_.sample(w) * scale_;
    SampledSpectrum s;
    for (int i = 0; i < kSpectrumSamples; ++i) s[i] = (*this)(w[i]);
    return s;
}

Vec3 Distribution::xyz() const {
    return integrate_xyz([this](double l) { return double((*this)(float(l))); });
}

Rgb Distribution::srgb() const {
    const Vec3 c = apply(xyz_to_srgb(), xyz());
    return {c.x, c.y, c.z};
}

}  // namespace phos::spectrum
