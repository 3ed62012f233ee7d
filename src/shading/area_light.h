// Diffuse area light: uniform radiance L leaving one side of a shape (the side its emitting normal
// faces, see shape_sampler.h) or both sides when two-sided. Flux pi L A (doubled when two-sided).
#pragma once

#include "shading/lights.h"
#include "shading/shape_sampler.h"

namespace phos::shading {

class AreaLight final : public Light {
public:
    AreaLight(const scene::Light& light, const scene::Shape& shape);
    LightLiSample sample_Li(Vec3 ref, Vec2 u, const Wavelengths& lambda) const override;
    float pdf_Li(Vec3 ref, Vec3 wi, Vec3 p_light, Vec3 n_light) const override;
    Spectrum Le(Vec3 n, Vec3 wo, const Wavelengths& lambda) const override;
    // Uniform by area, then cosine-weighted on the emitting side (a random side when two-sided):
    // weight = L pi A (x2 when two-sided) for every sample.
    LightLeSample sample_Le(Vec2 u_pos, Vec2 u_dir, const Wavelengths& lambda) const override;
    void pdf_Le(Vec3 n, Vec3 w, float& pdf_pos, float& pdf_dir) const override;
    Rgb power() const override;
    bool is_delta() const override { return false; }

    const ShapeSampler& sampler() const { return sampler_; }
    bool two_sided() const { return two_sided_; }

private:
    ShapeSampler sampler_;
    Rgb radiance_;
    bool two_sided_ = false;
};

}  // namespace phos::shading
