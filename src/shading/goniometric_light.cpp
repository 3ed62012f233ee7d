// Goniometric light: sample_Li is the point light's delta sample scaled by the map; sample_Le draws
// the direction from the map's pixel distribution, so each photon carries I map(w) / pdf_dir, which
// is constant within a pixel (nearest lookups) and averages to the flux.
#include "shading/goniometric_light.h"

#include <string>

#include "core/error.h"
#include "shading/point_light.h"

namespace phos::shading {

GoniometricLight::GoniometricLight(const scene::Light& light, const std::vector<scene::Texture>& textures)
    : Light(light),
      position_(light.to_world.point({0, 0, 0})),
      frame_(light_frame(light.to_world)),
      intensity_(light.color) {
    if (light.texture < 0 || size_t(light.texture) >= textures.size())
        throw InputError("goniometric light: texture index " + std::to_string(light.texture) +
                         " out of range");
    const scene::Texture& tex = textures[size_t(light.texture)];
    if (tex.kind != scene::Texture::Kind::Image || !tex.image || tex.image->width <= 0)
        throw InputError("goniometric light: the intensity map must be an image");
    if (tex.image->width != tex.image->height)
        throw InputError("goniometric light: the map '" + tex.filename + "' is not square (equal-area)");
    std::vector<Rgb> grey(tex.image->texels.size());
    for (size_t k = 0; k < grey.size(); ++k) grey[k] = Rgb(tex.image->texels[k].average());
    map_ = EqualAreaMap(std::move(grey), tex.image->width);
}

LightLiSample GoniometricLight::sample_Li(Vec3 ref, Vec2, const Wavelengths& lambda) const {
    LightLiSample s = sample_point_Li(position_, ref);
    if (s.pdf > 0) s.L = emission(lambda) * (profile(-s.wi) / (s.distance * s.distance));
    return s;
}

void GoniometricLight::pdf_Le(Vec3, Vec3 w, float& pdf_pos, float& pdf_dir) const {
    pdf_pos = 1;
    pdf_dir = map_.pdf(frame_.to_local(normalize(w)));
}

LightLeSample GoniometricLight::sample_Le(Vec2, Vec2 u_dir, const Wavelengths& lambda) const {
    LightLeSample s;
    float pdf = 0;
    const Vec3 w = normalize(frame_.to_world(map_.sample(u_dir, &pdf)));
    // Density and intensity from the final direction, exactly as pdf_Le and sample_Li see it.
    pdf = map_.pdf(frame_.to_local(w));
    if (!(pdf > 0)) return s;
    s.ray = {position_, w};
    s.n = w;
    s.Le = emission(lambda) * profile(w);
    s.pdf_pos = 1;
    s.pdf_dir = pdf;
    s.weight = s.Le / pdf;
    return s;
}

}  // namespace phos::shading
