// Point light: a delta position, so sample_Li is deterministic (pdf 1) and emission is uniform over
// the sphere of directions.
#include "shading/point_light.h"

#include "core/warp.h"

namespace phos::shading {

float distance_falloff(float d, bool legacy, Vec3 att) {
    if (legacy) {
        const float denom = att.x + att.y * d + att.z * d * d;
        return denom > 0 ? 1 / denom : 0;
    }
    return d > 0 ? 1 / (d * d) : 0;
}

PointLight::PointLight(const scene::Light& light, const LightOptions& options)
    : Light(light),
      position_(light.position),
      intensity_(light.color),
      legacy_(options.legacy_attenuation),
      attenuation_(light.attenuation) {}

LightLiSample sample_point_Li(Vec3 position, Vec3 ref) {
    LightLiSample s;
    const Vec3 d = position - ref;
    const float dist = length(d);
    s.delta = true;
    s.p_light = position;
    if (!(dist > 0)) return s;  // pdf 0: the reference point sits on the light
    s.wi = d / dist;
    s.distance = dist;
    s.n_light = -s.wi;
    s.pdf = 1;
    return s;
}

LightLiSample PointLight::sample_Li(Vec3 ref, Vec2, const Wavelengths& lambda) const {
    LightLiSample s = sample_point_Li(position_, ref);
    if (s.pdf > 0) s.L = emission(lambda) * distance_falloff(s.distance, legacy_, attenuation_);
    return s;
}

LightLeSample PointLight::sample_Le(Vec2, Vec2 u_dir, const Wavelengths& lambda) const {
    LightLeSample s;
    const Vec3 w = warp::uniform_sphere(u_dir);
    s.ray = {position_, w};
    s.n = w;
    s.Le = emission(lambda);
    s.pdf_pos = 1;
    s.pdf_dir = warp::uniform_sphere_pdf();
    s.weight = s.Le / s.pdf_dir;
    return s;
}

}  // namespace phos::shading
