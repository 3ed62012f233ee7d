// Spot light. Power is the exact integral of I * falloff over the sphere:
//   cos^n:      2 pi I (1 - c^(n+1)) / (n+1), c = cos(cutoff) (clamped to 0 when n > 0);
//   smoothstep: 2 pi I ((1 - cs) + (cs - ce) / 2), since the cubic 3t^2 - 2t^3 integrates to 1/2.
#include "shading/spot_light.h"

#include <cmath>

#include "core/warp.h"
#include "shading/point_light.h"

namespace phos::shading {
namespace {

float smoothstep(float x, float a, float b) {
    if (a == b) return x < a ? 0.0f : 1.0f;
    const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
    return t * t * (3 - 2 * t);
}

// Inverts F(t) = 2t^3 - t^4 (the CDF of the density 6t^2 - 4t^3 on [0,1]) by safeguarded Newton.
float invert_smooth_cdf(float v) {
    double lo = 0, hi = 1, t = std::cbrt(double(v) / 2) > 1 ? 1 : std::cbrt(double(v) / 2);
    for (int i = 0; i < 40; ++i) {
        const double f = 2 * t * t * t - t * t * t * t - v;
        if (std::fabs(f) < 1e-9) break;
        if (f > 0)
            hi = t;
        else
            lo = t;
        const double df = 6 * t * t - 4 * t * t * t;
        double next = df > 0 ? t - f / df : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        t = next;
    }
    return float(t);
}

}  // namespace

SpotLight::SpotLight(const scene::Light& light, const LightOptions& options)
    : Light(light),
      position_(light.position),
      frame_(normalize(light.direction)),
      intensity_(light.color),
      exponent_(std::max(0.0f, light.dropoff)),
      legacy_(options.legacy_attenuation),
      attenuation_(light.attenuation) {
    const float cutoff = std::clamp(light.cutoff, 0.0f, kPi);
    cos_cutoff_ = std::cos(cutoff);
    if (light.falloff_start >= 0) {
        smooth_ = true;
        cos_start_ = std::cos(std::min(light.falloff_start, cutoff));
    } else if (exponent_ > 0) {
        // cos^n is taken as max(cos, 0)^n: nothing is emitted backwards whatever the cutoff.
        cos_cutoff_ = std::max(cos_cutoff_, 0.0f);
    }
}

float SpotLight::falloff(float c) const {
    if (smooth_) return smoothstep(c, cos_cutoff_, cos_start_);
    if (c < cos_cutoff_) return 0;
    if (exponent_ == 0) return 1;
    return c > 0 ? std::pow(c, exponent_) : 0;
}

Rgb SpotLight::power() const {
    if (smooth_) return intensity_ * (2 * kPi * ((1 - cos_start_) + 0.5f * (cos_start_ - cos_cutoff_)));
    const float n1 = exponent_ + 1;
    return intensity_ * (2 * kPi * (1 - std::pow(cos_cutoff_, n1)) / n1);
}

LightLiSample SpotLight::sample_Li(Vec3 ref, Vec2, const Wavelengths& lambda) const {
    LightLiSample s = sample_point_Li(position_, ref);
    if (s.pdf > 0)
        s.L = emission(lambda) *
              (falloff(dot(-s.wi, frame_.n)) * distance_falloff(s.distance, legacy_, attenuation_));
    return s;
}

float SpotLight::direction_pdf(float z) const {
    if (z < cos_cutoff_) return 0;
    if (smooth_) {
        const float total = (1 - cos_start_) + 0.5f * (cos_start_ - cos_cutoff_);
        return total > 0 ? falloff(z) / (2 * kPi * total) : 0;
    }
    if (exponent_ == 0) return warp::uniform_cone_pdf(cos_cutoff_);
    const float n1 = exponent_ + 1;
    return n1 * std::pow(std::max(z, 0.0f), exponent_) / (2 * kPi * (1 - std::pow(cos_cutoff_, n1)));
}

void SpotLight::pdf_Le(Vec3, Vec3 w, float& pdf_pos, float& pdf_dir) const {
    pdf_pos = 1;
    pdf_dir = direction_pdf(dot(w, frame_.n));
}

LightLeSample SpotLight::sample_Le(Vec2, Vec2 u, const Wavelengths& lambda) const {
    float z = 1;
    const float phi = 2 * kPi * u.y;
    if (smooth_) {
        // Mixture of the flat core (cos in [cs, 1], falloff 1) and the smoothstep ring, each picked
        // with its share of the integral; inside the ring t = (cos - ce)/(cs - ce) has density
        // proportional to 3t^2 - 2t^3.
        const float core = 1 - cos_start_, ring = 0.5f * (cos_start_ - cos_cutoff_);
        const float total = core + ring;
        if (!(total > 0)) return {};
        const float p_core = core / total;
        if (u.x < p_core) {
            z = 1 - (u.x / p_core) * core;
        } else {
            const float v = std::min((u.x - p_core) / (1 - p_core), 1.0f);
            z = cos_cutoff_ + invert_smooth_cdf(v) * (cos_start_ - cos_cutoff_);
        }
        z = std::clamp(z, cos_cutoff_, 1.0f);
    } else if (exponent_ == 0) {
        z = std::clamp(1 - u.x * (1 - cos_cutoff_), cos_cutoff_, 1.0f);
    } else {
        z = std::max(warp::truncated_power_cosine(u, exponent_, cos_cutoff_).z, cos_cutoff_);
    }
    const float pdf = direction_pdf(z);
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    const Vec3 w = frame_.to_world({r * std::cos(phi), r * std::sin(phi), z});
    LightLeSample s;
    s.ray = {position_, w};
    s.n = w;
    s.Le = emission(lambda) * falloff(z);
    s.pdf_pos = 1;
    s.pdf_dir = pdf;
    s.weight = pdf > 0 ? s.Le / pdf : Spectrum(0.0f);
    return s;
}

}  // namespace phos::shading
