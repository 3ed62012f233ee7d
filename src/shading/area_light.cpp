// Area light: the shape sampler supplies points and densities; this file adds the emission
// direction rules (one- or two-sided) and the cosine-weighted photon emission.
#include "shading/area_light.h"

#include <algorithm>
#include <cmath>

#include "core/frame.h"
#include "core/warp.h"

namespace phos::shading {

AreaLight::AreaLight(const scene::Light& light, const scene::Shape& shape)
    : Light(light), sampler_(shape), radiance_(light.color), two_sided_(light.two_sided) {}

Spectrum AreaLight::Le(Vec3 n, Vec3 wo, const Wavelengths& lambda) const {
    return (two_sided_ || dot(n, wo) > 0) ? emission(lambda) : Spectrum(0.0f);
}

Rgb AreaLight::power() const { return radiance_ * (kPi * sampler_.area() * (two_sided_ ? 2.0f : 1.0f)); }

LightLiSample AreaLight::sample_Li(Vec3 ref, Vec2 u, const Wavelengths& lambda) const {
    LightLiSample s;
    const ShapeSample ss = sampler_.sample(ref, u);
    if (!(ss.pdf > 0)) return s;
    const Vec3 d = ss.p - ref;
    const float dist = length(d);
    if (!(dist > 0)) return s;
    s.wi = d / dist;
    s.distance = dist;
    s.p_light = ss.p;
    s.n_light = ss.n;
    s.pdf = ss.pdf;
    s.L = Le(ss.n, -s.wi, lambda);
    return s;
}

float AreaLight::pdf_Li(Vec3 ref, Vec3 wi, Vec3 p_light, Vec3 n_light) const {
    return sampler_.pdf(ref, wi, p_light, n_light);
}

void AreaLight::pdf_Le(Vec3 n, Vec3 w, float& pdf_pos, float& pdf_dir) const {
    pdf_pos = sampler_.area() > 0 ? 1 / sampler_.area() : 0;
    const float c = dot(n, w);
    pdf_dir = two_sided_ ? 0.5f * std::fabs(c) / kPi : std::max(c, 0.0f) / kPi;
}

LightLeSample AreaLight::sample_Le(Vec2 u_pos, Vec2 u_dir, const Wavelengths& lambda) const {
    LightLeSample s;
    const ShapeSample ss = sampler_.sample_area(u_pos);
    if (!(ss.pdf > 0)) return s;
    Vec3 n = ss.n;
    float side_pdf = 1;
    if (two_sided_) {
        // Reuse u_dir.x: its lower half picks the front, the upper half the back.
        side_pdf = 0.5f;
        if (u_dir.x < 0.5f) {
            u_dir.x *= 2;
        } else {
            u_dir.x = std::min(2 * u_dir.x - 1, std::nextafter(1.0f, 0.0f));
            n = -n;
            s.back = true;
        }
    }
    const Vec3 local = warp::cosine_hemisphere(u_dir);
    const Vec3 w = Frame(n).to_world(local);
    // The ray starts on the emitting surface: skip that surface itself (a relative epsilon, as for
    // spawned rays), or the photon would "hit" its own light at t = 0.
    const float extent = std::max(std::fabs(ss.p.x), std::max(std::fabs(ss.p.y), std::fabs(ss.p.z)));
    s.ray = {ss.p, w, 1e-5f * (1 + extent)};
    s.n = n;
    s.Le = emission(lambda);
    s.pdf_pos = ss.pdf;
    s.pdf_dir = warp::cosine_hemisphere_pdf(local.z) * side_pdf;
    // L |cos| / (pdf_pos pdf_dir), which is L pi A / side_pdf; a grazing direction (cos = 0) takes
    // that limit instead of 0/0.
    s.weight = s.pdf_dir > 0 ? s.Le * (local.z / (s.pdf_pos * s.pdf_dir))
                             : s.Le * (kPi * sampler_.area() / side_pdf);
    return s;
}

}  // namespace phos::shading
