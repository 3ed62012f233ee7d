// Directional light: sample_Li returns the fixed direction towards the light; photons start on a
// disk perpendicular to the direction, tangent to the scene's bounding sphere on the upstream side.
#include "shading/directional_light.h"

#include "core/warp.h"

namespace phos::shading {

DirectionalLight::DirectionalLight(const scene::Light& light, const SceneSphere& sphere)
    : Light(light), frame_(normalize(light.direction)), irradiance_(light.color), sphere_(sphere) {}

LightLiSample DirectionalLight::sample_Li(Vec3 ref, Vec2, const Wavelengths& lambda) const {
    LightLiSample s;
    s.wi = -frame_.n;
    s.L = emission(lambda);
    s.pdf = 1;
    s.delta = true;
    s.distance = kInf;
    // A point certainly outside the scene, for callers that want a finite shadow-ray target.
    s.p_light = ref + s.wi * (2 * (sphere_.radius + length(ref - sphere_.center)) + 1);
    s.n_light = frame_.n;
    return s;
}

LightLeSample DirectionalLight::sample_Le(Vec2 u_pos, Vec2, const Wavelengths& lambda) const {
    LightLeSample s;
    const float R = sphere_.radius;
    const Vec2 d = warp::concentric_disk(u_pos);
    s.ray = {sphere_.center + (frame_.s * d.x + frame_.t * d.y - frame_.n) * R, frame_.n};
    s.n = frame_.n;
    s.Le = emission(lambda);
    s.pdf_pos = R > 0 ? 1 / (kPi * R * R) : 0;
    s.pdf_dir = 1;
    s.weight = s.Le * (kPi * R * R);
    return s;
}

}  // namespace phos::shading
